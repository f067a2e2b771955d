// `dyncc sim2real-bench`: the diagnosis checked blind. Logs are made with hidden effects (zero,
// one or two, 2-20 % of the torque RMS) on several arms, trajectories and rates; the truth is
// written to its own file; `dyncc diagnose` runs as a separate process on the log alone; then its
// JSON is scored against the truth.
#include <fmt/core.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "diagnose/synthetic_log.hpp"

namespace dyncc::cli {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string arm;
  double rate = 0, fraction = 0;
  std::vector<diagnose::Injection> effects;
  std::vector<double> effect_rms;  // per injected effect: its torque RMS on its joint (or the arm's largest)
};

// The parameter of the diagnosis that measures an injected effect, and its true value.
std::pair<std::string, double> measured_parameter(const diagnose::Injection& e) {
  const int j = e.joint + 1;
  if (e.effect == "coulomb_friction") return {fmt::format("fc{}", j), e.size};
  if (e.effect == "viscous_friction") return {fmt::format("fv{}", j), e.size};
  if (e.effect == "stribeck_friction") return {fmt::format("fs{}", j), e.size};
  if (e.effect == "rotor_inertia") return {fmt::format("ia{}", j), e.size};
  if (e.effect == "torque_gain") return {fmt::format("gain{}", j), e.size};
  if (e.effect == "position_offset") return {fmt::format("offset{}", j), e.size};
  if (e.effect == "payload") return {"mass", e.size};
  if (e.effect == "contact") return {"", e.size};  // the fit's constant force + spring is not the injected peak
  return {"delay", e.size};
}

// Unit sizes, scaled afterwards to the wanted share of the torque RMS.
double unit_size(const std::string& effect) {
  if (effect == "torque_gain") return 0.1;  // as gain - 1
  if (effect == "sensor_delay") return 0.01;
  if (effect == "position_offset") return 0.02;
  if (effect == "payload") return 0.2;
  if (effect == "rotor_inertia") return 0.01;
  if (effect == "contact") return 1.0;  // N
  return 0.1;
}

// Sizes a real arm could have; a draw outside is redrawn (a 20 % torque change by a 0.5 s delay
// is not a sensor delay).
bool plausible_size(const diagnose::Injection& e) {
  if (e.effect == "torque_gain") return e.size > 0.7 && e.size < 1.4;
  if (e.effect == "sensor_delay") return e.size <= 0.05;
  if (e.effect == "position_offset") return e.size <= 0.2;
  if (e.effect == "payload") return e.size <= 5.0;
  if (e.effect == "rotor_inertia") return e.size <= 3.0;
  if (e.effect == "contact") return e.size <= 500.0;
  return true;
}

std::string self_path() {
  std::error_code error;
  const fs::path p = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string("dyncc") : p.string();
}

std::string shell_quoted(const fs::path& p) { return fmt::format("'{}'", p.string()); }

}  // namespace

int run_sim2real_bench(const BenchOptions& o) {
  const std::vector<std::string> arms = o.arms;
  std::map<std::string, std::unique_ptr<pipeline::Derivation>> derived;
  for (const std::string& arm : arms) {
    auto d =
        load_and_derive((fs::path(o.robots) / fmt::format("{}.yaml", arm)).string(), {.prove_base_parameters = false});
    if (!d) return kBadInput;
    derived[arm] = std::move(d);
  }
  std::error_code error;
  fs::create_directories(o.out, error);
  if (error) {
    fmt::print(stderr, "{}: error: cannot create the folder: {}\n", o.out, error.message());
    return kBadInput;
  }
  std::mt19937 random(o.seed);
  const double rates[] = {81, 200, 500, 1000};
  const double fractions[] = {0.05, 0.1, 0.2};
  const std::vector<std::string> effects = diagnose::injectable_effects();

  struct Score {
    int cases = 0, top1 = 0, located = 0, locatable = 0, parameters_ok = 0, parameters = 0, closure_ok = 0,
        closures = 0;
  };
  std::map<std::string, Score> by_size;  // "none", "5%", "10%", "20%"
  std::map<std::string, Score> by_effect;
  std::string rows;
  for (int c = 0; c < o.cases; ++c) {
    Case k;
    k.arm = arms[static_cast<std::size_t>(c) % arms.size()];
    const pipeline::Derivation& d = *derived[k.arm];
    const auto n = static_cast<int>(d.robot.coordinates.size());
    k.rate = rates[random() % 4];
    const int count = c % 5 == 0 ? 0 : (c % 5 == 4 ? 2 : 1);
    k.fraction = fractions[random() % 3];
    diagnose::SyntheticOptions so;
    so.rate = k.rate;
    so.seed = o.seed * 1000U + static_cast<unsigned>(c);
    so.duration = 40;
    std::vector<std::string> pool = effects;
    for (int e = 0; e < count; ++e) {
      // Draw until the effect is observable on the trajectory and its size physically plausible.
      for (int attempt = 0; attempt < 100; ++attempt) {
        const std::size_t pick = random() % pool.size();
        diagnose::Injection inj;
        inj.effect = pool[pick];
        inj.joint = static_cast<int>(random() % static_cast<unsigned>(n));
        const double unit = unit_size(inj.effect);
        inj.size = inj.effect == "torque_gain" ? 1.0 + unit : unit;
        // Scale so the effect is `fraction` of the torque RMS where it acts (a second one half as big).
        const diagnose::EffectSize size = diagnose::effect_size(d, {inj}, so);
        const double share = e == 0 ? k.fraction : 0.5 * k.fraction;
        auto j = static_cast<Eigen::Index>(inj.joint);
        if (!diagnose::acts_on_one_joint(inj.effect)) {
          size.effect_rms.cwiseQuotient(size.clean_rms.cwiseMax(1e-12)).maxCoeff(&j);
          inj.joint = static_cast<int>(j);
        }
        const double ratio = size.effect_rms[j] / std::max(size.clean_rms[j], 1e-12);
        if (ratio < 1e-3) continue;  // e.g. an offset of the vertical yaw axis: no torque at all
        const double scale = share / ratio;
        inj.size = inj.effect == "torque_gain" ? 1.0 + unit * scale : unit * scale;
        if (!plausible_size(inj)) continue;
        k.effects.push_back(inj);
        pool.erase(pool.begin() + static_cast<std::ptrdiff_t>(pick));
        break;
      }
    }
    const fs::path dir = fs::path(o.out) / fmt::format("case{:03d}", c);
    fs::create_directories(dir);
    diagnose::write_synthetic_log(d, k.effects, so, dir / "log.csv");
    nlohmann::json truth = {{"arm", k.arm},
                            {"rate", k.rate},
                            {"fraction", k.fraction},
                            {"effects", nlohmann::json::array()}};
    for (const auto& e : k.effects)
      truth["effects"].push_back({{"effect", e.effect}, {"joint", e.joint + 1}, {"size", e.size}});
    std::ofstream(dir / "truth.json") << truth.dump(2) << "\n";

    // The diagnosis as its own process, on the log alone.
    const std::string command =
        fmt::format("{} diagnose {} {} --json {} > {} 2>&1", shell_quoted(self_path()),
                    shell_quoted(fs::path(o.robots) / fmt::format("{}.yaml", k.arm)), shell_quoted(dir / "log.csv"),
                    shell_quoted(dir / "diagnosis.json"), shell_quoted(dir / "diagnosis.txt"));
    const int status = std::system(command.c_str());
    if (status != 0) {
      fmt::print(stderr, "case {}: dyncc diagnose failed (status {}); see {}\n", c, status,
                 (dir / "diagnosis.txt").string());
      return kCheckFailed;
    }
    std::ifstream in(dir / "diagnosis.json");
    const nlohmann::json result = nlohmann::json::parse(in);
    const std::string verdict = result["verdict"]["effect"];
    const std::string first = verdict.substr(0, verdict.find(" or "));
    const std::vector<int> joints = result["verdict"]["joints"].get<std::vector<int>>();

    const std::string bin = k.effects.empty() ? std::string("none") : fmt::format("{:.0f} %", 100 * k.fraction);
    const std::string truth_name = k.effects.empty() ? std::string("none") : k.effects.front().effect;
    Score& s = by_size[bin];
    Score& se = by_effect[truth_name];
    for (Score* x : {&s, &se}) ++x->cases;
    const bool right = first == truth_name;
    if (right) {
      ++s.top1;
      ++se.top1;
    }
    std::string detail;
    if (!k.effects.empty()) {
      const auto& main = k.effects.front();
      if (diagnose::acts_on_one_joint(main.effect)) {
        ++s.locatable;
        ++se.locatable;
        const bool located = right && joints == std::vector<int>{main.joint + 1};
        s.located += located ? 1 : 0;
        se.located += located ? 1 : 0;
      }
      if (right && !result["selected"].empty()) {
        const auto& sel = result["selected"][0];
        const auto [name, value] = measured_parameter(main);
        for (const auto& p : sel["parameters"]) {
          if (name.empty() || p["name"] != name) continue;
          const double fitted = p["value"];
          const double target = value;
          const bool ok = main.effect == "sensor_delay"  ? std::abs(fitted - target) <= 1.0 / k.rate
                          : main.effect == "payload"     ? std::abs(fitted - target) <= 0.03 * std::abs(target)
                          : main.effect == "torque_gain" ? std::abs(fitted - target) <= 0.1 * std::abs(target - 1.0)
                                                         : std::abs(fitted - target) <= 0.1 * std::abs(target);
          ++s.parameters;
          ++se.parameters;
          s.parameters_ok += ok ? 1 : 0;
          se.parameters_ok += ok ? 1 : 0;
          detail = fmt::format("{} = {:.4g} (true {:.4g})", name, fitted, target);
        }
        // Gap closure on the effect's joint: the share of the held-out gap that is gone.
        const auto j = static_cast<std::size_t>(main.joint);
        const double before = result["gap"]["heldout_rms"][j], after = result["gap"]["heldout_rms_after_selected"][j];
        const double closure = before > 0 ? 1.0 - (after * after) / (before * before) : 0.0;
        ++s.closures;
        ++se.closures;
        s.closure_ok += closure >= 0.8 ? 1 : 0;
        se.closure_ok += closure >= 0.8 ? 1 : 0;
        detail = fmt::format("{}, closure {:.0f} %", detail, 100 * closure);
      }
    }
    std::string injected;
    for (const auto& e : k.effects) {
      injected =
          fmt::format("{}{}{}@{} {:.3g}", injected, injected.empty() ? "" : " + ", e.effect, e.joint + 1, e.size);
    }
    rows += fmt::format("| {} | {} | {:.0f} | {} | {} | {} | {} | {} |\n", c, k.arm, k.rate,
                        injected.empty() ? "none" : injected, bin, verdict, fmt::join(joints, ","), detail);
    fmt::print("case {:3d} {:8} {:5.0f} Hz  {:<48} -> {} [{}] {}\n", c, k.arm, k.rate,
               injected.empty() ? "none" : injected, verdict, fmt::join(joints, ","), right ? "" : "(wrong)");
  }
  auto pct = [](int a, int b) {
    return b > 0 ? fmt::format("{:.0f} % ({}/{})", 100.0 * a / b, a, b) : std::string("-");
  };
  std::string table =
      "| effect size | cases | top-1 effect | joint located | parameters within goal | gap closure >= 80 % "
      "|\n|---|---|---|---|---|---|\n";
  for (const auto& [bin, s] : by_size) {
    table +=
        fmt::format("| {} | {} | {} | {} | {} | {} |\n", bin, s.cases,
                    bin == "none" ? fmt::format("{} said none", pct(s.top1, s.cases)) : pct(s.top1, s.cases),
                    pct(s.located, s.locatable), pct(s.parameters_ok, s.parameters), pct(s.closure_ok, s.closures));
  }
  std::string effect_table =
      "| injected (largest) effect | cases | top-1 | joint located | parameters | closure "
      "|\n|---|---|---|---|---|---|\n";
  for (const auto& [name, s] : by_effect) {
    effect_table +=
        fmt::format("| {} | {} | {} | {} | {} | {} |\n", name, s.cases, pct(s.top1, s.cases),
                    pct(s.located, s.locatable), pct(s.parameters_ok, s.parameters), pct(s.closure_ok, s.closures));
  }
  const std::string summary = fmt::format(
      "{}\n{}\n| case | arm | Hz | injected | size | verdict | joints | fit |\n|---|---|---|---|---|---|---|---|\n{}",
      table, effect_table, rows);
  fmt::print("\n{}\n{}", table, effect_table);
  std::ofstream(fs::path(o.out) / "summary.md") << summary;
  return kSuccess;
}

}  // namespace dyncc::cli
