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
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "diagnose/bench_truth.hpp"
#include "diagnose/crossval.hpp"
#include "diagnose/dataset.hpp"
#include "diagnose/effects.hpp"
#include "diagnose/joint_log.hpp"
#include "diagnose/synthetic_log.hpp"

namespace dyncc::cli {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string arm;
  std::string plant = "model";         // "model" (open-loop inverse dynamics), or dyncc-sim's "dyncc" / "mujoco"
  std::string trajectory = "fourier";  // or "teleop" (closed loop only)
  double rate = 0, fraction = 0;
  std::vector<diagnose::Injection> effects;
  std::vector<double> effect_rms;  // per injected effect: its torque RMS on its joint (or the arm's largest)

  // The effect the case is scored by: the largest injected one, or "none".
  [[nodiscard]] std::string scored_effect() const { return effects.empty() ? "none" : effects.front().effect; }
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
  if (e.effect == "joint_elasticity") return {fmt::format("stiffness{}", j), e.size};
  if (e.effect == "backlash") return {fmt::format("width{}", j), e.size};
  if (e.effect == "payload") return {"mass", e.size};
  if (e.effect == "contact") return {"", e.size};  // the fit's constant force + spring is not the injected peak
  return {"delay", e.size};
}

// Unit sizes, scaled afterwards to the wanted share of the torque RMS.
double unit_size(const std::string& effect, bool closed) {
  if (effect == "contact") return closed ? 0.01 : 1.0;  // m of table above the lowest hook point; N of peak force
  if (effect == "torque_gain") return 0.1;              // as gain - 1
  if (effect == "sensor_delay") return 0.01;
  if (effect == "position_offset") return 0.02;
  if (effect == "payload") return 0.2;
  if (effect == "rotor_inertia") return 0.01;
  if (effect == "backlash") return 0.01;            // rad of dead band
  if (effect == "joint_elasticity") return 1000.0;  // N m/rad: the one effect that shrinks as its size grows
  return 0.1;
}

// The size that makes an effect `scale` times as large as it is at `size`: its torque is linear in
// the size, except an elastic joint's, which goes as the compliance 1 / stiffness, and a gain's,
// which goes as gain - 1.
double scaled_size(const std::string& effect, double size, double scale) {
  if (effect == "torque_gain") return 1.0 + (size - 1.0) * scale;
  if (effect == "joint_elasticity") return size / scale;
  return size * scale;
}

// Sizes a real arm could have; a draw outside is redrawn (a 20 % torque change by a 0.5 s delay
// is not a sensor delay).
bool plausible_size(const diagnose::Injection& e, bool closed) {
  if (closed && e.effect == "contact") return e.size <= 0.2;
  if (closed && e.effect == "payload") return e.size <= 3.0;
  if (closed && e.effect == "rotor_inertia") return e.size <= 1.0;
  if (e.effect == "torque_gain") return e.size > 0.7 && e.size < 1.4;
  if (e.effect == "sensor_delay") return e.size <= 0.05;
  if (e.effect == "position_offset") return e.size <= 0.2;
  if (e.effect == "backlash") return e.size <= 2 * diagnose::kLargestDeflection;
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

// Closed-loop logs: the Kraft arm on one of the simulation's plants (dyncc-sim excite, run
// through `dyncc excite`), the hidden effects in the plant, described in its effects file.
nlohmann::json effects_file(const std::vector<diagnose::Injection>& effects) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& e : effects) {
    nlohmann::json entry = {{"effect", e.effect}};
    if (diagnose::acts_on_one_joint(e.effect)) {
      static const std::map<std::string, std::string> names = {
          {"coulomb_friction", "fc"}, {"viscous_friction", "fv"},       {"stribeck_friction", "fs"},
          {"rotor_inertia", "ia"},    {"torque_gain", "gain"},          {"position_offset", "offset"},
          {"backlash", "width"},      {"joint_elasticity", "stiffness"}};
      entry["joints"] = {e.joint + 1};
      entry["parameters"] = {{names.at(e.effect), {e.size}}};
    } else {
      const std::string name = e.effect == "payload" ? "mass" : (e.effect == "contact" ? "depth" : "delay");
      entry["parameters"] = {{name, e.size}};
    }
    list.push_back(entry);
  }
  return {{"effects", list}};
}

// What one closed-loop run needs.
struct Run {
  std::string plant, trajectory;
  double rate = 0;
  unsigned seed = 0;
};

bool run_excite(const Run& k, const std::vector<diagnose::Injection>& effects, const fs::path& log) {
  const fs::path file = fs::path(log).replace_extension(".effects.json");
  std::ofstream(file) << effects_file(effects).dump(2) << "\n";
  const std::string command = fmt::format(
      "{} excite --plant {} --trajectory {} --rate {:.0f} --duration 60 --seed {} --effects {} --out {} "
      "> {} 2>&1",
      shell_quoted(self_path()), k.plant, k.trajectory, k.rate, k.seed, shell_quoted(file), shell_quoted(log),
      shell_quoted(fs::path(log).replace_extension(".excite.txt")));
  return std::system(command.c_str()) == 0;
}

// What the diagnosis would see of a closed-loop log: its residual against the nominal model, and
// the torque RMS per joint. An effect's size is the RMS of the change it makes to that residual.
// Read with the torque at its time stamps, as when the bench's draws were made: the held command's
// half period shifts the clean and the probe run alike, so it hardly moves a difference's RMS,
// and reading it held here would change every seed's drawn sizes.
struct Seen {
  Eigen::VectorXd residual, torque_rms;
  diagnose::Dataset data;
};
Seen seen(const pipeline::Derivation& d, const fs::path& log) {
  const auto n = static_cast<Eigen::Index>(d.robot.coordinates.size());
  diagnose::Dataset data = diagnose::build_dataset({diagnose::read_joint_log(log.string(), n)}, d);
  Eigen::VectorXd residual = data.residual;
  Eigen::VectorXd torque_rms = (data.analysis_tau.array().square().colwise().mean()).sqrt().transpose();
  return {std::move(residual), std::move(torque_rms), std::move(data)};
}

// The torque an effect of a joint adds along a closed-loop log, from its own formula on the log's
// motion and through the filter the diagnosis applies: per-joint RMS. (The residual change
// between a run with the effect and a clean run would also count how the two runs' small
// residuals at reversals differ once the motion shifts, and size small effects too small.)
// Empty for the effects whose plant model has no formula here (payload on the hook, table
// contact): those are sized by a probe run.
std::optional<Eigen::VectorXd> modelled_effect_rms(const diagnose::Dataset& data, const diagnose::Injection& e) {
  constexpr double kSimStribeckVelocity = 0.1;  // rad/s, dyncc-sim's default vs
  const Eigen::Index n = data.n, j = e.joint;
  Eigen::MatrixXd torque = Eigen::MatrixXd::Zero(data.samples() * n, 1);
  for (Eigen::Index s = 0; s < data.samples(); ++s) {
    const double v = data.qd(s, j);
    if (e.effect == "coulomb_friction")
      torque(s * n + j, 0) = e.size * diagnose::smooth_sign(v);
    else if (e.effect == "viscous_friction")
      torque(s * n + j, 0) = e.size * v;
    else if (e.effect == "stribeck_friction")
      torque(s * n + j, 0) = e.size * diagnose::stribeck_fade(v, kSimStribeckVelocity) * diagnose::smooth_sign(v);
    else if (e.effect == "rotor_inertia")
      torque(s * n + j, 0) = e.size * data.qdd(s, j);
    else if (e.effect == "torque_gain")
      torque(s * n + j, 0) = (1.0 / e.size - 1.0) * data.model_tau(s, j);
    else if (e.effect == "position_offset")
      torque.block(s * n, 0, n, 1) = -data.dtau_dq[static_cast<std::size_t>(s)].col(j) * e.size;
    else if (e.effect == "sensor_delay")
      torque.block(s * n, 0, n, 1) = data.model_tau_rate.row(s).transpose() * e.size;
    else
      return std::nullopt;
  }
  return diagnose::joint_rms(diagnose::conditioned_columns(data, e.effect, torque).col(0), n);
}

// Whether a fitted parameter meets the goal for its effect: within 10 % (a gain's
// deviation from 1 within 10 %), a payload's mass within 3 %, a delay within one sample.
bool within_goal(const std::string& effect, double fitted, double target, double rate) {
  if (effect == "sensor_delay") return std::abs(fitted - target) <= 1.0 / rate;
  if (effect == "payload") return std::abs(fitted - target) <= 0.03 * std::abs(target);
  if (effect == "torque_gain") return std::abs(fitted - target) <= 0.1 * std::abs(target - 1.0);
  return std::abs(fitted - target) <= 0.1 * std::abs(target);
}

// A wrong first name that a tie names the injected effect `e` beside ("A or B", B injected): the
// log could not tell them apart. B's scored parameter as fitted in A's place (the diagnosis's
// `alternatives`), for scoring as a fit.
std::vector<double> tie_fits(const nlohmann::json& result, const diagnose::Injection& e) {
  const auto [name, value] = measured_parameter(e);
  std::vector<double> out;
  for (const auto& sel : result.at("selected")) {
    if (name.empty() || !sel.contains("alternatives")) continue;
    for (const auto& a : sel.at("alternatives")) {
      if (a.at("effect") != e.effect) continue;
      for (const auto& p : a.at("parameters")) {
        if (p.at("name") == name) out.push_back(p.at("value").get<double>());
      }
    }
  }
  return out;
}

struct Score {
  int cases = 0, top1 = 0, located = 0, locatable = 0, parameters_ok = 0, parameters = 0, closure_ok = 0, closures = 0;
  int covered = 0;  // fitted parameters whose truth lies within their stated 95 % interval
  // Wrong top-1 verdicts that name the injected effect later in a tie ("A or B", B injected), and
  // of those with a fit of B in A's place (AlternativeFit), the ones within the parameters' goal.
  int ties = 0, tie_fits = 0, tie_fits_ok = 0;
};

std::string pct(int a, int b) {
  return b > 0 ? fmt::format("{:.0f} % ({}/{})", 100.0 * a / b, a, b) : std::string("-");
}

// The goals of the issue over all cases, then the scores by effect size, by injected effect and by
// the log's source, as Markdown tables.
std::string score_tables(const std::map<std::string, Score>& by_size, const std::map<std::string, Score>& by_effect,
                         const std::map<std::string, Score>& by_source) {
  std::string table =
      "| effect size | cases | top-1 effect | joint located | parameters within goal | gap closure >= 80 % "
      "|\n|---|---|---|---|---|---|\n";
  for (const auto& [bin, s] : by_size) {
    table +=
        fmt::format("| {} | {} | {} | {} | {} | {} |\n", bin, s.cases,
                    bin == "none" ? fmt::format("{} said none", pct(s.top1, s.cases)) : pct(s.top1, s.cases),
                    pct(s.located, s.locatable), pct(s.parameters_ok, s.parameters), pct(s.closure_ok, s.closures));
  }
  auto score_table = [&](const char* title, const std::map<std::string, Score>& scores) {
    std::string out =
        fmt::format("| {} | cases | top-1 | joint located | parameters | closure |\n|---|---|---|---|---|---|\n",
                    title);
    for (const auto& [name, s] : scores) {
      out +=
          fmt::format("| {} | {} | {} | {} | {} | {} |\n", name, s.cases, pct(s.top1, s.cases),
                      pct(s.located, s.locatable), pct(s.parameters_ok, s.parameters), pct(s.closure_ok, s.closures));
    }
    return out;
  };
  // The goals over all cases.
  Score large, small, all;
  for (const auto& [bin, s] : by_size) {
    if (bin == "none") continue;
    Score& into = bin == "5 %" ? small : large;
    into.cases += s.cases;
    into.top1 += s.top1;
    for (Score* x : {&all}) {
      x->cases += s.cases;
      x->top1 += s.top1;
      x->located += s.located;
      x->locatable += s.locatable;
      x->parameters += s.parameters;
      x->parameters_ok += s.parameters_ok;
      x->covered += s.covered;
      x->closures += s.closures;
      x->closure_ok += s.closure_ok;
      x->ties += s.ties;
      x->tie_fits += s.tie_fits;
      x->tie_fits_ok += s.tie_fits_ok;
    }
  }
  const Score none = by_size.contains("none") ? by_size.at("none") : Score{};
  auto verdict_of = [](int a, int b, double goal, bool at_most) {
    if (b == 0) return "-";
    const double value = static_cast<double>(a) / b;
    return (at_most ? value <= goal : value >= goal) ? "met" : "NOT met";
  };
  const std::string goals = fmt::format(
      "| goal | measured | |\n|---|---|---|\n"
      "| top-1 effect >= 90 % at sizes >= 10 % | {} | {} |\n"
      "| top-1 effect >= 70 % at 5 % | {} | {} |\n"
      "| joint localisation >= 95 % | {} | {} |\n"
      "| false alarms on effect-free logs <= 5 % | {} | {} |\n"
      "| held-out gap closure >= 80 % of the injected effect's (correctly named) | {} | {} |\n"
      "| parameters within 10 % (payload 3 %, delay one sample) | {} | {} |\n"
      "| (not a goal) truth within the stated 95 % interval of the fitted parameter | {} | |\n"
      "| (not a goal) wrong top-1 effects that name the injected one later in a tie | {} | |\n"
      "| (not a goal) ... whose fit in the named one's place is within the parameters' goal | {} | |\n",
      pct(large.top1, large.cases), verdict_of(large.top1, large.cases, 0.9, false), pct(small.top1, small.cases),
      verdict_of(small.top1, small.cases, 0.7, false), pct(all.located, all.locatable),
      verdict_of(all.located, all.locatable, 0.95, false), pct(none.cases - none.top1, none.cases),
      verdict_of(none.cases - none.top1, none.cases, 0.05, true), pct(all.closure_ok, all.closures),
      verdict_of(all.closure_ok, all.closures, 0.8, false), pct(all.parameters_ok, all.parameters),
      verdict_of(all.parameters_ok, all.parameters, 1.0 - 1e-9, false), pct(all.covered, all.parameters),
      pct(all.ties, all.cases - all.top1), pct(all.tie_fits_ok, all.tie_fits));
  const std::string effect_table = score_table("injected (largest) effect", by_effect);
  const std::string source_table = score_table("log from", by_source);
  return fmt::format("{}\n{}\n{}\n{}", goals, table, effect_table, source_table);
}

// One case scored: counted into `scores` (its size's, its injected effect's and its source's
// tallies); the fit as a line of the summary and the goals the case misses, for its line on the
// terminal: which logs to look at, without the tables.
struct CaseScore {
  std::string detail;
  std::vector<std::string> misses;
};
CaseScore score_case(const Case& k, const nlohmann::json& result, const std::vector<Score*>& scores) {
  const std::string verdict = result.at("verdict").at("effect");
  const std::string first = verdict.substr(0, verdict.find(" or "));
  const std::vector<int> joints = result.at("verdict").at("joints").get<std::vector<int>>();
  const std::string truth_name = k.scored_effect();
  auto count_in = [&](int Score::*field, bool yes) {
    for (Score* x : scores) x->*field += yes ? 1 : 0;
  };
  count_in(&Score::cases, true);
  const bool right = diagnose::names_injected_effect(first, k.effects);
  count_in(&Score::top1, right);
  if (!right && !k.effects.empty() && verdict.find(" or " + truth_name) != std::string::npos) {
    count_in(&Score::ties, true);
    for (const double fitted : tie_fits(result, k.effects.front())) {
      count_in(&Score::tie_fits, true);
      count_in(&Score::tie_fits_ok,
               within_goal(truth_name, fitted, measured_parameter(k.effects.front()).second, k.rate));
    }
  }
  CaseScore out;
  if (!right) out.misses.emplace_back(k.effects.empty() ? "false alarm" : "wrong");
  if (!k.effects.empty()) {
    const auto& main = k.effects.front();
    if (diagnose::acts_on_one_joint(main.effect)) {
      const bool located = right && joints == std::vector<int>{main.joint + 1};
      count_in(&Score::locatable, true);
      count_in(&Score::located, located);
      if (right && !located) out.misses.emplace_back("joint");
    }
    if (right && !result.at("selected").empty()) {
      const auto& sel = result.at("selected").at(0);
      const auto [name, value] = measured_parameter(main);
      for (const auto& p : sel.at("parameters")) {
        if (name.empty() || p.at("name") != name) continue;
        const double fitted = p.at("value");
        const double error = p.at("error");
        const double target = value;
        const bool ok = within_goal(main.effect, fitted, target, k.rate);
        count_in(&Score::parameters, true);
        count_in(&Score::parameters_ok, ok);
        if (!ok) out.misses.emplace_back("parameter");
        // Whether the stated uncertainty is honest: a miss of the goal within it is the noise of the
        // log, not a bias of the diagnosis. The 95 % interval as stated (null: unbounded on that
        // side; none stated: the value alone).
        constexpr double kUnbounded = std::numeric_limits<double>::infinity();
        double low = fitted, high = fitted;
        if (p.contains("interval95")) {
          const auto& interval = p.at("interval95");
          low = interval[0].is_null() ? -kUnbounded : interval[0].get<double>();
          high = interval[1].is_null() ? kUnbounded : interval[1].get<double>();
        }
        count_in(&Score::covered, low <= target && target <= high);
        out.detail =
            fmt::format("{} = {:.4g} +- {:.2g} [{:.4g}, {:.4g}] (true {:.4g})", name, fitted, error, low, high, target);
      }
      // Gap closure on the effect's joint: the share of the held-out gap that is gone.
      const auto j = static_cast<std::size_t>(main.joint);
      const double before = result.at("gap").at("heldout_rms").at(j),
                   after = result.at("gap").at("heldout_rms_after_selected").at(j);
      const double closure = before > 0 ? 1.0 - (after * after) / (before * before) : 0.0;
      count_in(&Score::closures, true);
      count_in(&Score::closure_ok, closure >= 0.8);
      if (closure < 0.8) out.misses.emplace_back("closure");
      out.detail = fmt::format("{}, closure {:.0f} %", out.detail, 100 * closure);
    }
  }
  return out;
}

}  // namespace

// A case's hidden effects: `count` of them from `pool`, the first `fraction` of the torque RMS on
// the joint where it is largest and a second half as big, each drawn again until it is observable
// on the trajectory and its size physically plausible. `measure` sizes a drawn effect (false: the
// plant refused it).
using Measure = std::function<bool(const diagnose::Injection&, diagnose::EffectSize&)>;
std::vector<diagnose::Injection> draw_effects(std::mt19937& random, std::vector<std::string> pool, int count,
                                              double fraction, int n, bool closed, const Measure& measure) {
  std::vector<diagnose::Injection> drawn_effects;
  for (int e = 0; e < count && !pool.empty(); ++e) {
    // Draw until the effect is observable on the trajectory and its size physically plausible.
    for (int attempt = 0; attempt < 100; ++attempt) {
      const std::size_t pick = random() % pool.size();
      diagnose::Injection inj;
      inj.effect = pool[pick];
      // Not yet in closed loop: on the Kraft's rigid plant (MuJoCo's joints are rigid) a 5 % spring
      // of the elbow left a gap below the friction floor at reversals, read as none.
      if (closed && (inj.effect == "backlash" || inj.effect == "joint_elasticity")) continue;
      inj.joint = static_cast<int>(random() % static_cast<unsigned>(n));
      const double unit = unit_size(inj.effect, closed);
      inj.size = inj.effect == "torque_gain" ? 1.0 + unit : unit;
      const double drawn = inj.size;
      // Scale so the effect is `fraction` of the torque RMS on the joint where it is largest (a
      // second one half as big): an offset of a shoulder joint changes the elbow's gravity
      // torque more than its own, and sized on its own joint a "second, half as big" offset
      // was the larger effect of its case.
      diagnose::EffectSize size;
      if (!measure(inj, size)) continue;  // a probe the plant refused
      const double share = e == 0 ? fraction : 0.5 * fraction;
      Eigen::Index j = 0;
      const double ratio = size.effect_rms.cwiseQuotient(size.clean_rms.cwiseMax(1e-12)).maxCoeff(&j);
      if (!diagnose::acts_on_one_joint(inj.effect)) inj.joint = static_cast<int>(j);
      if (ratio < 1e-3) continue;  // e.g. an offset of the vertical yaw axis: no torque at all
      inj.size = scaled_size(inj.effect, drawn, share / ratio);
      if (!plausible_size(inj, closed)) continue;
      // A spring that deflects by more than 0.05 rad RMS under the joint's own torque is a loose
      // joint, not an elastic transmission.
      if (inj.effect == "joint_elasticity" && size.clean_rms[inj.joint] / inj.size > diagnose::kLargestDeflection)
        continue;
      // A dead band whose torque never turns over is never crossed: the link sits on one side of
      // it, and that is a position offset, not a backlash anyone could see.
      if (inj.effect == "backlash" && size.reversing[inj.joint] < diagnose::kBacklashTurnOver) continue;
      drawn_effects.push_back(inj);
      pool.erase(pool.begin() + static_cast<std::ptrdiff_t>(pick));
      break;
    }
  }
  return drawn_effects;
}

// A payload is carried over the whole log, from a pick-up to a put-down, or from a pick-up on (a
// generator of its own, seeded by the case: the draws of the cases stay as they were).
void draw_carrying(diagnose::SyntheticOptions& so) {
  std::mt19937 carrying(so.seed);
  std::uniform_real_distribution<double> share(0.0, 1.0);
  const unsigned mode = carrying() % 3;
  if (mode > 0) so.payload_on = so.duration * (0.15 + 0.25 * share(carrying));
  if (mode == 1) so.payload_off = so.duration * (0.6 + 0.3 * share(carrying));
}

// What the diagnosis must not read: the injected effects and where a log came from.
nlohmann::json truth_json(const Case& k, const diagnose::SyntheticOptions& so, bool closed) {
  nlohmann::json truth = {{"arm", k.arm},   {"plant", k.plant},       {"trajectory", k.trajectory},
                          {"rate", k.rate}, {"fraction", k.fraction}, {"effects", nlohmann::json::array()}};
  for (const auto& e : k.effects) {
    truth["effects"].push_back({{"effect", e.effect}, {"joint", e.joint + 1}, {"size", e.size}});
    if (e.effect == "payload" && !closed && so.payload_on > 0) truth["effects"].back()["picked_up_at"] = so.payload_on;
    if (e.effect == "payload" && !closed && so.payload_off < so.duration)
      truth["effects"].back()["put_down_at"] = so.payload_off;
  }
  return truth;
}

// The scores of the cases so far, by size, by injected effect and by the log's source, and the
// summary's rows.
struct Tallies {
  std::map<std::string, Score> by_size;  // "none", "5%", "10%", "20%"
  std::map<std::string, Score> by_effect;
  std::map<std::string, Score> by_source;  // "open loop (model)", "dyncc fourier", "mujoco teleop", ...
  std::string rows;

  // Case c scored: counted, its row of the summary kept, its line printed.
  void add(int c, const Case& k, const nlohmann::json& result) {
    const std::string verdict = result.at("verdict").at("effect");
    const std::vector<int> joints = result.at("verdict").at("joints").get<std::vector<int>>();
    const std::string bin = k.effects.empty() ? std::string("none") : fmt::format("{:.0f} %", 100 * k.fraction);
    const std::string truth_name = k.scored_effect();
    const std::string source = k.plant == "model" ? std::string("open loop (model)") : k.plant + " " + k.trajectory;
    const CaseScore scored = score_case(k, result, {&by_size[bin], &by_effect[truth_name], &by_source[source]});
    std::string injected;
    for (const auto& e : k.effects) {
      injected =
          fmt::format("{}{}{}@{} {:.3g}", injected, injected.empty() ? "" : " + ", e.effect, e.joint + 1, e.size);
    }
    rows += fmt::format("| {} | {} | {} | {:.0f} | {} | {} | {} | {} | {} |\n", c, k.arm, source, k.rate,
                        injected.empty() ? "none" : injected, bin, verdict, fmt::join(joints, ","), scored.detail);
    fmt::print("case {:3d} {:8} {:17} {:5.0f} Hz  {:<48} -> {} [{}] {}\n", c, k.arm, source, k.rate,
               injected.empty() ? "none" : injected, verdict, fmt::join(joints, ","),
               scored.misses.empty() ? "" : fmt::format("({})", fmt::join(scored.misses, ", ")));
    std::fflush(stdout);
  }

  // The goals' tables on the terminal; with the rows, summary.md in `out`.
  void write_summary(const std::string& out) const {
    const std::string tables = score_tables(by_size, by_effect, by_source);
    const std::string summary = fmt::format(
        "{}\n| case | arm | log from | Hz | injected | size | verdict | joints | fit |\n"
        "|---|---|---|---|---|---|---|---|---|\n{}",
        tables, rows);
    fmt::print("\n{}", tables);
    std::ofstream(fs::path(out) / "summary.md") << summary;
  }
};

// A case as its truth.json states it (truth_json's inverse; its joints are numbered from 1).
Case case_from_truth(const nlohmann::json& truth) {
  Case k;
  k.arm = truth.at("arm");
  k.plant = truth.at("plant");
  k.trajectory = truth.at("trajectory");
  k.rate = truth.at("rate");
  k.fraction = truth.at("fraction");
  for (const auto& e : truth.at("effects")) {
    diagnose::Injection inj;
    inj.effect = e.at("effect");
    inj.joint = e.at("joint").get<int>() - 1;
    inj.size = e.at("size");
    k.effects.push_back(inj);
  }
  return k;
}

// The case folders of a stored bench (caseNNN with a truth.json), in order; empty when there are
// none or the folder cannot be read.
std::vector<std::pair<int, fs::path>> stored_cases(const fs::path& bench) {
  std::vector<std::pair<int, fs::path>> cases;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(bench, error)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name.size() > 4 && name.starts_with("case") &&
        name.find_first_not_of("0123456789", 4) == std::string::npos && fs::exists(entry.path() / "truth.json")) {
      cases.emplace_back(std::stoi(name.substr(4)), entry.path());
    }
  }
  if (error) cases.clear();
  std::sort(cases.begin(), cases.end());
  return cases;
}

// A stored file that is not what the bench writes, named with what is wrong in it.
void say_not_the_benchs(const fs::path& file, const nlohmann::json::exception& e) {
  fmt::print(stderr, "{}: error: expected the bench's {} ({})\n", file.string(), file.filename().string(), e.what());
}

// A stored JSON file, or nullopt (said on stderr) when it does not parse.
std::optional<nlohmann::json> read_stored_json(const fs::path& file) {
  try {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    say_not_the_benchs(file, e);
    return std::nullopt;
  }
}

// The diagnosis as its own process, on the log alone, writing dir/diagnosis.json (and its text
// beside it). What it is told is how the log was written, as a user knows it of their own: the
// closed-loop torque is the controller's command, held over each period; the open-loop torque is
// the model's at the row's instant. Its JSON, or nullopt (said on stderr) when it failed.
std::optional<nlohmann::json> diagnose_case(const BenchOptions& o, int c, const Case& k, const fs::path& log,
                                            const fs::path& dir) {
  const bool closed = k.plant != "model";
  const std::string command = fmt::format("{} diagnose {} {}{} --json {} > {} 2>&1", shell_quoted(self_path()),
                                          shell_quoted(fs::path(o.robots) / fmt::format("{}.yaml", k.arm)),
                                          shell_quoted(log), closed ? " --held-torque" : "",
                                          shell_quoted(dir / "diagnosis.json"), shell_quoted(dir / "diagnosis.txt"));
  const int status = std::system(command.c_str());
  if (status != 0) {
    fmt::print(stderr, "case {}: dyncc diagnose failed (status {}); see {}\n", c, status,
               (dir / "diagnosis.txt").string());
    return std::nullopt;
  }
  return read_stored_json(dir / "diagnosis.json");
}

// --rescore: the cases already in the folder (caseNNN/truth.json and diagnosis.json) scored again,
// nothing simulated or diagnosed: a change of the scoring, checked on stored benches.
// --rediagnose FROM: the logs of FROM's cases diagnosed again by this binary into --out (each
// case's truth.json copied, its log read where it is), then scored: a change of the diagnosis,
// checked on stored benches without simulating them again, FROM's own diagnoses kept to compare.
int score_stored_bench(const BenchOptions& o) {
  const bool rediagnose = !o.rediagnose.empty();
  const fs::path from = rediagnose ? fs::path(o.rediagnose) : fs::path(o.out);
  const auto cases = stored_cases(from);
  if (cases.empty()) {
    fmt::print(stderr, "{}: error: {}: expected caseNNN folders with a truth.json (a bench's --out)\n", from.string(),
               rediagnose ? "--rediagnose" : "--rescore");
    return kBadInput;
  }
  Tallies tallies;
  for (const auto& [c, stored] : cases) {
    const auto truth = read_stored_json(stored / "truth.json");
    if (!truth) return kBadInput;
    Case k;
    try {
      k = case_from_truth(*truth);
    } catch (const nlohmann::json::exception& e) {
      say_not_the_benchs(stored / "truth.json", e);
      return kBadInput;
    }
    const fs::path dir = rediagnose ? fs::path(o.out) / stored.filename() : stored;  // where its diagnosis is
    std::optional<nlohmann::json> diagnosis;
    if (rediagnose) {
      const fs::path log = stored / "log.csv";
      if (!fs::exists(log)) {
        fmt::print(stderr, "{}: error: --rediagnose: the case's log is missing\n", log.string());
        return kBadInput;
      }
      std::error_code error;
      fs::create_directories(dir, error);
      if (!error) fs::copy_file(stored / "truth.json", dir / "truth.json", fs::copy_options::overwrite_existing, error);
      if (error) {
        fmt::print(stderr, "{}: error: cannot write the case: {}\n", dir.string(), error.message());
        return kBadInput;
      }
      diagnosis = diagnose_case(o, c, k, log, dir);
      if (!diagnosis) return kCheckFailed;
    } else {
      diagnosis = read_stored_json(dir / "diagnosis.json");
      if (!diagnosis) return kBadInput;
    }
    try {
      tallies.add(c, k, *diagnosis);
    } catch (const nlohmann::json::exception& e) {
      say_not_the_benchs(dir / "diagnosis.json", e);
      return kBadInput;
    }
  }
  tallies.write_summary(o.out);
  return kSuccess;
}

int run_sim2real_bench(const BenchOptions& o) {
  if (o.rescore || !o.rediagnose.empty()) return score_stored_bench(o);
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
  // Backlash only when asked for: where the drive's Coulomb friction is large (the PUMA's first
  // joints, 6-26 N m), the motor's quick crossing of the dead band flips that friction for a few
  // samples, which the diagnosis' velocity estimate (a 4 Hz low-pass) cannot follow; such logs are
  // read as an elastic joint (1 of 6 PUMA backlash logs named; 6 of 6 with the friction zeroed).
  // The unit test on the Panda names and sizes it.
  std::vector<std::string> effects = o.effects;
  if (effects.empty()) {
    for (const std::string& e : diagnose::injectable_effects()) {
      if (e != "backlash") effects.push_back(e);
    }
  }

  Tallies tallies;
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
    draw_carrying(so);
    const bool closed = o.closed_loop && k.arm == "kraft" && k.rate >= 200;
    if (closed) {  // alternate the plants, and the trajectories every second time
      const int turn = c / static_cast<int>(arms.size());
      k.plant = turn % 2 == 0 ? "dyncc" : "mujoco";
      k.trajectory = (turn / 2) % 2 == 0 ? "fourier" : "teleop";
    }
    const fs::path dir = fs::path(o.out) / fmt::format("case{:03d}", c);
    fs::create_directories(dir);
    const Run run{k.plant, k.trajectory, k.rate, so.seed};
    Seen clean;
    if (closed) {
      if (!run_excite(run, {}, dir / "clean.csv")) {
        fmt::print(stderr, "case {}: dyncc excite failed; see {}\n", c, (dir / "clean.excite.txt").string());
        return kCheckFailed;
      }
      clean = seen(d, dir / "clean.csv");
    }
    // The RMS per joint of the torque change an effect makes (as the diagnosis sees it), and of
    // the clean torque: from the model along the open-loop trajectory; in closed loop from the
    // effect's formula along the clean run, or from a run with the effect alone against the clean
    // run.
    auto measure = [&](const diagnose::Injection& inj, diagnose::EffectSize& size) {
      if (!closed) {
        size = diagnose::effect_size(d, {inj}, so);
        return true;
      }
      size.reversing = diagnose::minority_sign_share(clean.data.tau);  // the drive's friction included
      size.clean_rms = clean.torque_rms;
      if (auto modelled = modelled_effect_rms(clean.data, inj)) {
        size.effect_rms = *modelled;
        return true;
      }
      if (!run_excite(run, {inj}, dir / "probe.csv")) return false;
      const Seen probe = seen(d, dir / "probe.csv");
      size.effect_rms = diagnose::joint_rms(probe.residual - clean.residual, n);
      return true;
    };
    k.effects = draw_effects(random, effects, count, k.fraction, n, closed, measure);
    if (closed) {
      fs::remove(dir / "probe.csv");
      if (!run_excite(run, k.effects, dir / "log.csv")) {
        fmt::print(stderr, "case {}: dyncc excite failed; see {}\n", c, (dir / "log.excite.txt").string());
        return kCheckFailed;
      }
    } else {
      diagnose::write_synthetic_log(d, k.effects, so, dir / "log.csv");
    }
    std::ofstream(dir / "truth.json") << truth_json(k, so, closed).dump(2) << "\n";

    const auto diagnosis = diagnose_case(o, c, k, dir / "log.csv", dir);
    if (!diagnosis) return kCheckFailed;
    tallies.add(c, k, *diagnosis);
  }
  tallies.write_summary(o.out);
  return kSuccess;
}

}  // namespace dyncc::cli
