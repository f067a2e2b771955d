// dyncc-sim: the tele-operation simulation's command line, run as `dyncc simulate`,
// `dyncc report` and `dyncc excite` (gen/cli forwards to it; see sim/README.md).
#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "effects_file.hpp"
#include "excite.hpp"
#include "findings.hpp"
#include "report.hpp"
#include "scenario.hpp"
#include "summary.hpp"

namespace {

using namespace dyncc::sim;
constexpr int kBadInput = 2;

// A progress bar on the terminal, shown only once a run has taken more than a second.
class ProgressBar {
 public:
  void operator()(const std::string& label, double fraction) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (!tty_ || elapsed < 1.0) return;
    const int width = 30, done = static_cast<int>(fraction * width);
    if (done == last_ && label == label_ && fraction < 1.0) return;
    last_ = done;
    label_ = label;
    std::fprintf(stderr, "\r%-36s [%s%s] %3.0f%% %5.1f s", label.c_str(),
                 std::string(static_cast<std::size_t>(done), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - done), '.').c_str(), 100 * fraction, elapsed);
    if (fraction >= 1.0) std::fputc('\n', stderr);
    std::fflush(stderr);
  }
  void restart() {
    start_ = std::chrono::steady_clock::now();
    last_ = -1;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  bool tty_ = ::isatty(STDERR_FILENO) != 0;
  int last_ = -1;
  std::string label_;
};

std::string default_mjcf() {
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  return ((error ? std::filesystem::path(".") : self.parent_path()) / "kraft.xml").string();
}

PlantKind plant_kind(const std::string& name) { return name == "mujoco" ? PlantKind::mujoco : PlantKind::dyncc; }

struct SimulateOptions {
  std::string scenario, adaptation = "on", plant = "dyncc", out, master_csv, mjcf = default_mjcf();
  double payload = -1, duration = 0;
  unsigned seed = 1;
};

int run_simulate(const SimulateOptions& o) {
  ScenarioSettings s = scenario_settings(o.scenario);
  s.adaptation = o.adaptation == "on";
  s.plant = plant_kind(o.plant);
  s.mjcf = o.mjcf;
  s.master_csv = o.master_csv;
  s.seed = o.seed;
  s.duration = o.duration;
  if (o.payload >= 0) s.payload = o.payload;
  const std::filesystem::path out =
      o.out.empty() ? std::filesystem::path("sim-out") /
                          fmt::format("{}-{}-{}", o.scenario, o.plant, s.adaptation ? "adaptive" : "fixed")
                    : std::filesystem::path(o.out);
  std::filesystem::create_directories(out);
  ProgressBar bar;
  const Run run = simulate(s, [&](double f) { bar(fmt::format("{} {} {}", o.scenario, o.plant, o.adaptation), f); });
  write_csv(run, out / "log.csv");
  write_run_figures(run, out);
  const Summary summary = summarize(run);
  const std::string text = summary_table({summary}) + "\n" + estimate_table({summary});
  std::ofstream(out / "summary.txt") << text;
  std::fputs(text.c_str(), stdout);
  std::printf("\nwrote %s/{log.csv, summary.txt, angles, errors, estimates (.png, .svg)}\n", out.string().c_str());
  return 0;
}

struct ReportOptions {
  std::string out = "report", plant = "both", mjcf = default_mjcf();
};

int run_report(const ReportOptions& o) {
  std::vector<PaperRuns> plants;
  ProgressBar bar;
  for (const char* name : {"dyncc", "mujoco"}) {
    if (o.plant != "both" && o.plant != name) continue;
    bar.restart();
    plants.push_back(run_paper_scenarios(plant_kind(name), o.mjcf, std::ref(bar)));
  }
  write_report(plants, o.out);
  bool all = true;
  for (const PaperRuns& p : plants) {
    std::printf("\n== plant %s ==\n%s\n", p.plant == PlantKind::mujoco ? "mujoco" : "dyncc",
                summary_table(p.summaries).c_str());
    for (const Finding& f : paper_findings(p)) {
      std::printf("(%s) %-13s %s\n    %s\n", f.id.c_str(), f.holds ? "holds" : "DOES NOT HOLD", f.claim.c_str(),
                  f.evidence.c_str());
      all = all && f.holds;
    }
  }
  std::printf("\nreport: %s\n", (std::filesystem::path(o.out) / "index.html").string().c_str());
  return all ? 0 : 1;
}

struct ExciteOptions {
  std::string plant = "dyncc", trajectory = "fourier", effects, out, mjcf = default_mjcf();
  double rate = 200, duration = 60, quantum = kPotentiometerQuantum, noise = kPotentiometerNoise;
  unsigned seed = 1;
};

int run_excite(const ExciteOptions& o) {
  ExciteSettings s;
  s.plant = plant_kind(o.plant);
  s.mjcf = o.mjcf;
  s.trajectory = o.trajectory == "teleop" ? Trajectory::teleop : Trajectory::fourier;
  s.rate = o.rate;
  s.duration = o.duration;
  s.seed = o.seed;
  s.quantum = o.quantum;
  s.noise = o.noise;
  if (!o.effects.empty()) {
    s.effects = read_effects(o.effects);
    require_playable(s.effects, s.plant, o.effects);
  }
  ProgressBar bar;
  const ExciteRun run = excite(s, [&](double f) { bar(fmt::format("excite {} {}", o.plant, o.trajectory), f); });
  write_excite_log(run, o.out);
  std::fputs(excite_summary(run).c_str(), stdout);
  std::printf("wrote %s\n", o.out.c_str());
  return 0;
}

void add_excite_command(CLI::App& app, ExciteOptions& ex, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "excite", "A log for checking the diagnosis: the arm in closed loop with hidden effects (t,q1..3,tau1..3)");
  cmd->add_option("--plant", ex.plant, "dyncc (generated model, RK4) or mujoco (the exported MJCF)")
      ->check(CLI::IsMember({"dyncc", "mujoco"}));
  cmd->add_option("--trajectory", ex.trajectory, "fourier (excitation) or teleop (the paper task's master motion)")
      ->check(CLI::IsMember({"fourier", "teleop"}));
  cmd->add_option("--rate", ex.rate, "control and log rate (Hz)")->check(CLI::Range(81.0, 1000.0));
  cmd->add_option("--duration", ex.duration, "seconds to log")->check(CLI::Range(0.1, 3600.0));
  cmd->add_option("--seed", ex.seed, "seed of the Fourier series, the sensor noise and the operator's run");
  cmd->add_option("--effects", ex.effects, "hidden effects (JSON, see sim/README.md); none if left out");
  cmd->add_option("--out", ex.out, "the log (CSV)")->required();
  cmd->add_option("--quantum", ex.quantum, "position quantisation step (rad; 0: none; default 2 pi / 4096)")
      ->check(CLI::Range(0.0, 0.1));
  cmd->add_option("--noise", ex.noise, "position noise, standard deviation (rad; default 0.3e-3)")
      ->check(CLI::Range(0.0, 0.1));
  cmd->add_option("--mjcf", ex.mjcf, "the exported Kraft MJCF (default: kraft.xml next to this program)");
  cmd->callback([&] { exit_code = run_excite(ex); });
}

int run(int argc, char** argv) {
  CLI::App app{"dyncc-sim: the tele-operated Kraft arm (run as `dyncc simulate`, `dyncc report`, `dyncc excite`)"};
  app.require_subcommand(1);
  int exit_code = 0;
  SimulateOptions sim;
  auto* simulate_cmd = app.add_subcommand("simulate", "One scenario: CSV log, figures and a summary");
  simulate_cmd
      ->add_option("--scenario", sim.scenario,
                   "paper-0.5kg, paper-1kg, paper-simplified, paper-contact or paper-unloaded")
      ->required()
      ->check(CLI::IsMember(scenario_names()));
  simulate_cmd->add_option("--adaptation", sim.adaptation, "on (adaptive) or off (fixed model)")
      ->check(CLI::IsMember({"on", "off"}));
  simulate_cmd->add_option("--plant", sim.plant, "dyncc (generated model, RK4) or mujoco (the exported MJCF)")
      ->check(CLI::IsMember({"dyncc", "mujoco"}));
  simulate_cmd->add_option("--payload", sim.payload, "payload mass (kg) instead of the scenario's")
      ->check(CLI::Range(0.0, 3.0));
  simulate_cmd->add_option("--out", sim.out, "output folder (default sim-out/SCENARIO-PLANT-MODE)");
  simulate_cmd->add_option("--master-csv", sim.master_csv,
                           "replay this master trajectory (t,q1,q2,q3) instead of the operator model");
  simulate_cmd->add_option("--mjcf", sim.mjcf, "the exported Kraft MJCF (default: kraft.xml next to this program)");
  simulate_cmd->add_option("--seed", sim.seed, "potentiometer noise seed");
  simulate_cmd->add_option("--duration", sim.duration, "seconds to simulate (default: the whole task)")
      ->check(CLI::Range(0.0, 3600.0));
  simulate_cmd->callback([&] { exit_code = run_simulate(sim); });

  ReportOptions report;
  auto* report_cmd = app.add_subcommand(
      "report", "Every scenario, adaptive and fixed, on both plants: one HTML page; exit 1 if a finding fails");
  report_cmd->add_option("--out", report.out, "output folder (default report/)");
  report_cmd->add_option("--plant", report.plant, "dyncc, mujoco or both")
      ->check(CLI::IsMember({"dyncc", "mujoco", "both"}));
  report_cmd->add_option("--mjcf", report.mjcf, "the exported Kraft MJCF (default: kraft.xml next to this program)");
  report_cmd->callback([&] { exit_code = run_report(report); });
  ExciteOptions excite_options;
  add_excite_command(app, excite_options, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "dyncc: %s\n", e.what());
    return kBadInput;
  } catch (const std::exception& e) {  // unreadable input files, unwritable output, MuJoCo load errors
    std::fprintf(stderr, "dyncc: %s\n", e.what());
    return kBadInput;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (...) {  // the messages of known failures are printed in run; this is the last resort
    std::fputs("dyncc: internal error\n", stderr);
  }
  return kBadInput;
}
