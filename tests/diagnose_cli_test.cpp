// `dyncc diagnose` and `dyncc sim2real-bench` from the command line: exit codes, the JSON the
// issue specifies, bad input, and a bench whose truth stays in files of their own.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "diagnose/synthetic_log.hpp"
#include "dynamics_support.hpp"

namespace dyncc::test {
namespace {

const std::filesystem::path kKraft = std::filesystem::path(DYNCC_SOURCE_DIR) / "robots" / "kraft.yaml";

TEST(DiagnoseCommand, BadInputExitsTwoAndNamesThePlace) {
  const auto missing = write_text("missing.csv", "t,q1,q2,q3,tau1,tau2\n0,0,0,0,0,0\n");
  const auto two_joints = write_text("two.csv", "t,q1,q2,tau1,tau2\n0,0,0,0,0\n");
  struct Case {
    std::string arguments, expected;
  };
  const Case cases[] = {
      {"diagnose " + quoted(kKraft) + " /nonexistent.csv", "/nonexistent.csv: error: cannot open the log"},
      {"diagnose " + quoted(kKraft) + " " + quoted(missing), "missing.csv:1:1: error: missing column 'tau3'"},
      {"diagnose " + quoted(kKraft) + " " + quoted(two_joints), "two.csv:1:1: error: missing column 'q3'"},
      {"diagnose " + quoted(kKraft) + " " + quoted(missing) + " --map time",
       "--map: 'time': expected THEIR_NAME=OUR_NAME"},
      {"diagnose /nonexistent.yaml " + quoted(missing), "/nonexistent.yaml"},
      {"diagnose " + quoted(kKraft), "LOGS is required"},
      {"sim2real-bench --effects friction", "--effects: friction not in {coulomb_friction"},
  };
  for (const Case& c : cases) {
    const DynccRun run = run_dyncc(c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.errors;
    EXPECT_NE(run.errors.find(c.expected), std::string::npos) << c.arguments << "\n" << run.errors;
  }
}

// A small blind bench: the logs, their truths and the diagnoses are separate files, the JSON has
// the issue's keys, and a log without effects is not diagnosed with one.
TEST(Sim2RealBench, WritesTruthApartAndDiagnosesEachLog) {
  const auto out = output_path("bench");
  // Three logs, each simulated (closed loop) and diagnosed: minutes under the sanitizers.
  const DynccRun run =
      run_dyncc("sim2real-bench --cases 3 --seed 5 --arms kraft --robots " +
                    quoted(std::filesystem::path(DYNCC_SOURCE_DIR) / "robots") + " --out " + quoted(out),
                600);
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  for (int c = 0; c < 3; ++c) {
    const auto dir = out / ("case00" + std::to_string(c));
    ASSERT_TRUE(std::filesystem::exists(dir / "log.csv"));
    ASSERT_TRUE(std::filesystem::exists(dir / "truth.json"));
    std::ifstream in(dir / "diagnosis.json");
    const nlohmann::json d = nlohmann::json::parse(in);
    for (const char* key : {"verdict", "ranking", "gap"}) EXPECT_TRUE(d.contains(key)) << key;
    for (const char* key : {"effect", "joints", "confidence"}) EXPECT_TRUE(d["verdict"].contains(key)) << key;
    for (const auto& r : d["ranking"]) {
      for (const char* key : {"effect", "joints", "parameters", "heldout_rms_before", "heldout_rms_after", "shrink"}) {
        EXPECT_TRUE(r.contains(key)) << key;
      }
      EXPECT_EQ(r["heldout_rms_before"].size(), 3U);
    }
    // Where the log came from is part of the truth: the model along an open-loop trajectory, or
    // one of the simulation's plants in closed loop (Kraft at 200 Hz and above).
    std::ifstream truth_file(dir / "truth.json");
    const nlohmann::json truth = nlohmann::json::parse(truth_file);
    const std::string plant = truth["plant"];
    EXPECT_TRUE(plant == "model" || plant == "dyncc" || plant == "mujoco") << plant;
    EXPECT_EQ(plant != "model", truth["rate"].get<double>() >= 200) << plant;
    // The log itself says nothing about the truth: its header is only t, q*, tau*.
    std::ifstream log(dir / "log.csv");
    std::string header;
    std::getline(log, header);
    EXPECT_EQ(header, "t,q1,q2,q3,tau1,tau2,tau3");
  }
  std::ifstream truth(out / "case000" / "truth.json");
  const nlohmann::json t = nlohmann::json::parse(truth);
  EXPECT_TRUE(t["effects"].empty()) << "case 0 is effect-free";
  std::ifstream first(out / "case000" / "diagnosis.json");
  EXPECT_EQ(nlohmann::json::parse(first)["verdict"]["effect"], "none");
  EXPECT_TRUE(std::filesystem::exists(out / "summary.md"));
}

// A bench's case folder as the bench leaves it: caseNNN/truth.json and diagnosis.json.
void write_bench_case(const std::filesystem::path& out, int c, const std::string& truth, const std::string& diagnosis) {
  const auto dir = out / fmt::format("case{:03d}", c);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "truth.json") << truth;
  std::ofstream(dir / "diagnosis.json") << diagnosis;
}

// --rescore scores stored cases again without making or diagnosing anything: an effect-free log
// said none, a Coulomb friction injected with a Stribeck excess of its joint named as the Stribeck
// friction (right, its fc scored), and a gain named as a rotor inertia (wrong).
TEST(Sim2RealBench, RescoreScoresTheStoredCasesAgain) {
  const auto out = output_path("rescored");
  const std::string gap =
      R"("gap": {"heldout_rms": [0.05, 0.01, 0.01], "heldout_rms_after_selected": [0.01, 0.01, 0.01]})";
  write_bench_case(out, 0,
                   R"({"arm": "kraft", "plant": "dyncc", "trajectory": "fourier", "rate": 200, "fraction": 0.2,
                       "effects": []})",
                   R"({"verdict": {"effect": "none", "joints": [], "confidence": 1}, "selected": [], )" + gap + "}");
  write_bench_case(out, 1,
                   R"({"arm": "kraft", "plant": "dyncc", "trajectory": "fourier", "rate": 200, "fraction": 0.2,
                       "effects": [{"effect": "coulomb_friction", "joint": 1, "size": 0.0700},
                                   {"effect": "stribeck_friction", "joint": 1, "size": 0.141}]})",
                   R"({"verdict": {"effect": "stribeck_friction", "joints": [1], "confidence": 1},
                       "selected": [{"effect": "stribeck_friction", "joints": [1], "parameters": [
                         {"name": "fc1", "value": 0.0701, "error": 0.0002, "interval95": [0.0697, 0.0705]},
                         {"name": "fs1", "value": 0.157, "error": 0.007, "interval95": [0.143, 0.171]}]}], )" +
                       gap + "}");
  write_bench_case(out, 2,
                   R"({"arm": "kraft", "plant": "mujoco", "trajectory": "teleop", "rate": 500, "fraction": 0.2,
                       "effects": [{"effect": "torque_gain", "joint": 2, "size": 1.1}]})",
                   R"({"verdict": {"effect": "rotor_inertia", "joints": [2], "confidence": 1},
                       "selected": [{"effect": "rotor_inertia", "joints": [2], "parameters": [
                         {"name": "ia2", "value": 0.1, "error": 0.01, "interval95": [0.08, 0.12]}]}], )" +
                       gap + "}");
  const DynccRun run = run_dyncc("sim2real-bench --rescore --out " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  std::ifstream in(out / "summary.md");
  const std::string summary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(summary.find("| top-1 effect >= 90 % at sizes >= 10 % | 50 % (1/2) | NOT met |"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("| false alarms on effect-free logs <= 5 % | 0 % (0/1) | met |"), std::string::npos);
  EXPECT_NE(summary.find("| parameters within 10 % (payload 3 %, delay one sample) | 100 % (1/1) | met |"),
            std::string::npos);
  EXPECT_NE(summary.find("fc1 = 0.0701"), std::string::npos) << "the Coulomb friction's fit is scored";

  // A folder that is not a bench's, and a diagnosis that is not the bench's JSON: exit 2, the
  // place named.
  const auto empty = output_path("not-a-bench");
  std::filesystem::create_directories(empty);
  const DynccRun none = run_dyncc("sim2real-bench --rescore --out " + quoted(empty));
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.errors.find("--rescore: expected caseNNN folders with a truth.json"), std::string::npos)
      << none.errors;
  write_bench_case(out, 3,
                   R"({"arm": "kraft", "plant": "dyncc", "trajectory": "fourier", "rate": 200, "fraction": 0.1,
                       "effects": []})",
                   R"({"verdict": {"effect": "none"}})");
  const DynccRun broken = run_dyncc("sim2real-bench --rescore --out " + quoted(out));
  EXPECT_EQ(broken.exit_code, 2);
  EXPECT_NE(broken.errors.find("case003/diagnosis.json: error: expected the bench's diagnosis.json"), std::string::npos)
      << broken.errors;
}

// --rediagnose diagnoses a stored bench's logs again into another folder and scores them there,
// leaving the stored diagnoses as they were: one open-loop Kraft log with a Coulomb friction of
// joint 2, stored with a diagnosis that names something else.
TEST(Sim2RealBench, RediagnoseDiagnosesTheStoredLogsAgainIntoAnotherFolder) {
  const auto stored = output_path("stored-bench");
  const std::string stale = R"({"verdict": {"effect": "none", "joints": [], "confidence": 1}, "selected": [],
                                "gap": {"heldout_rms": [0.05, 0.01, 0.01], "heldout_rms_after_selected": [0.05, 0.01, 0.01]}})";
  write_bench_case(stored, 7,
                   R"({"arm": "kraft", "plant": "model", "trajectory": "fourier", "rate": 200, "fraction": 0.2,
                       "effects": [{"effect": "coulomb_friction", "joint": 2, "size": 0.15}]})",
                   stale);
  diagnose::SyntheticOptions options;
  options.duration = 20;
  diagnose::write_synthetic_log(kraft_derivation(), {{.effect = "coulomb_friction", .joint = 1, .size = 0.15}}, options,
                                stored / "case007" / "log.csv");
  const auto out = output_path("rediagnosed");
  const std::string robots = " --robots " + quoted(std::filesystem::path(DYNCC_SOURCE_DIR) / "robots");
  const DynccRun run =
      run_dyncc("sim2real-bench" + robots + " --rediagnose " + quoted(stored) + " --out " + quoted(out), 600);
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  std::ifstream fresh(out / "case007" / "diagnosis.json");
  const nlohmann::json d = nlohmann::json::parse(fresh);
  EXPECT_EQ(d["verdict"]["effect"], "coulomb_friction");
  EXPECT_EQ(d["verdict"]["joints"], std::vector<int>{2});
  EXPECT_TRUE(std::filesystem::exists(out / "case007" / "truth.json"));
  EXPECT_FALSE(std::filesystem::exists(out / "case007" / "log.csv")) << "the log is read where it is stored";
  std::ifstream kept(stored / "case007" / "diagnosis.json");
  EXPECT_EQ(nlohmann::json::parse(kept)["verdict"]["effect"], "none") << "the stored diagnosis is kept";
  std::ifstream in(out / "summary.md");
  const std::string summary((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(summary.find("| top-1 effect >= 90 % at sizes >= 10 % | 100 % (1/1) | met |"), std::string::npos)
      << summary;

  // A stored case without its log, and a folder that is not a bench's: exit 2, the place named.
  std::filesystem::remove(stored / "case007" / "log.csv");
  const DynccRun missing =
      run_dyncc("sim2real-bench" + robots + " --rediagnose " + quoted(stored) + " --out " + quoted(out));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.errors.find("case007/log.csv: error: --rediagnose: the case's log is missing"), std::string::npos)
      << missing.errors;
  const auto empty = output_path("not-a-stored-bench");
  std::filesystem::create_directories(empty);
  const DynccRun none = run_dyncc("sim2real-bench --rediagnose " + quoted(empty) + " --out " + quoted(out));
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.errors.find("--rediagnose: expected caseNNN folders with a truth.json"), std::string::npos)
      << none.errors;
}

// One entry of an effects file: `effect` on `joint` (from 1), its parameter `name` = `value`.
std::string joint_effect(const char* effect, int joint, const char* name, double value) {
  return fmt::format(R"({{"effect": "{}", "joints": [{}], "parameters": {{"{}": [{}]}}}})", effect, joint, name, value);
}

// An effects file's text with these entries.
std::string effects_file_of(const std::vector<std::string>& entries) {
  return fmt::format(R"({{"effects": [{}]}})", fmt::join(entries, ", "));
}

// A closed-loop log of the Kraft arm (by default the MuJoCo plant, a Fourier reference at 200 Hz,
// the blind bench's seed 37, case 39), simulated by `dyncc excite` and diagnosed from the file
// alone, told (as the bench tells it) that the logged torque is the controller's held command.
nlohmann::json diagnose_excited(const std::string& name, const std::string& effects_json,
                                const std::string& run = "--plant mujoco --trajectory fourier --rate 200 --seed 37039",
                                const std::string& diagnose_options = "--held-torque") {
  std::string effects;
  if (!effects_json.empty()) effects = " --effects " + quoted(write_text(name + ".effects.json", effects_json));
  const auto log = output_path(name + ".csv"), json = output_path(name + ".json");
  const DynccRun excite = run_dyncc("excite " + run + " --duration 60" + effects + " --out " + quoted(log));
  EXPECT_EQ(excite.exit_code, 0) << excite.errors;
  const DynccRun diagnosis =
      run_dyncc("diagnose " + quoted(kKraft) + " " + quoted(log) + " " + diagnose_options + " --json " + quoted(json));
  EXPECT_EQ(diagnosis.exit_code, 0) << diagnosis.errors;
  std::ifstream in(json);
  return nlohmann::json::parse(in);
}

// Every selected effect's fitted parameters, by name.
std::map<std::string, double> fitted_of(const nlohmann::json& diagnosis) {
  std::map<std::string, double> fitted;
  for (const auto& r : diagnosis["selected"]) {
    for (const auto& p : r["parameters"]) fitted[p["name"]] = p["value"];
  }
  return fitted;
}

// The verdict names `effect` first (a tie "A or B" counts by its first name) on `joint` alone, and
// each of `truths` is among the selected effects' parameters within 10 % of its true value.
void expect_named_on_joint_with_fits(const nlohmann::json& d, const std::string& effect, int joint,
                                     const std::map<std::string, double>& truths) {
  const std::string verdict = d["verdict"]["effect"].get<std::string>();
  EXPECT_EQ(verdict.substr(0, verdict.find(" or ")), effect) << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({joint})) << d["verdict"].dump();
  const std::map<std::string, double> fitted = fitted_of(d);
  for (const auto& [name, truth] : truths) {
    const auto it = fitted.find(name);
    if (it == fitted.end()) {
      ADD_FAILURE() << name << " is not among the selected effects' parameters: " << d["selected"].dump();
      continue;
    }
    EXPECT_NEAR(it->second, truth, 0.1 * std::abs(truth)) << name;
  }
}

// An injected per-joint effect: `effect` on `joint` (from 1), its parameter `prefix` = `value`
// (read back as prefix + joint, "fs2").
struct JointTruth {
  const char* effect;
  int joint;
  const char* prefix;
  double value;
};

// A run of `dyncc excite` (`run`) with `truths` injected, diagnosed; the first truth must be named
// first on its joint alone and every truth read within 10 %. Returns the diagnosis.
nlohmann::json expect_excited_first_named(const std::string& name, const std::vector<JointTruth>& truths,
                                          const std::string& run) {
  std::vector<std::string> entries;
  std::map<std::string, double> values;
  for (const JointTruth& t : truths) {
    entries.push_back(joint_effect(t.effect, t.joint, t.prefix, t.value));
    values[fmt::format("{}{}", t.prefix, t.joint)] = t.value;
  }
  const nlohmann::json d = diagnose_excited(name, effects_file_of(entries), run);
  expect_named_on_joint_with_fits(d, truths.front().effect, truths.front().joint, values);
  return d;
}

// An open-loop log of the model of `robot` (robots/<robot>.yaml, derived as `d`) with `effects`
// injected (as the bench makes its open-loop cases, whose seeds `options` repeats), diagnosed by
// `dyncc diagnose` against the description.
nlohmann::json diagnose_synthetic(const pipeline::Derivation& d, const std::string& robot, const std::string& name,
                                  const std::vector<diagnose::Injection>& effects,
                                  const diagnose::SyntheticOptions& options) {
  const auto log = output_path(name) / "log.csv";
  std::filesystem::create_directories(log.parent_path());
  diagnose::write_synthetic_log(d, effects, options, log);
  const auto json = log.parent_path() / "diagnosis.json";
  const DynccRun run =
      run_dyncc("diagnose " + quoted(std::filesystem::path(DYNCC_SOURCE_DIR) / "robots" / (robot + ".yaml")) + " " +
                quoted(log) + " --json " + quoted(json));
  EXPECT_EQ(run.exit_code, 0) << run.errors;
  std::ifstream in(json);
  return nlohmann::json::parse(in);
}

nlohmann::json diagnose_synthetic_puma(const std::string& name, const std::vector<diagnose::Injection>& effects,
                                       const diagnose::SyntheticOptions& options) {
  return diagnose_synthetic(puma_derivation(), "puma560", name, effects, options);
}

// Without a hidden effect the only gap is what the MuJoCo plant and the description differ by (a
// few % of the base joint's torque). Its shape once fitted a 333 N m/rad spring on joint 1 that
// gives way 0.9 mrad, under the 12-bit potentiometers' 1.5 mrad step: a shift the sensor cannot
// resolve is not taken for a transmission effect.
TEST(DiagnoseCommand, ClosedLoopKraftLogWithoutEffectsIsNone) {
  const nlohmann::json d = diagnose_excited("clean_excite", "");
  EXPECT_EQ(d["verdict"]["effect"], "none") << d["verdict"].dump();
}

// The rigid plant (the description's own arm) at 1 kHz, the blind bench's seed 71, case 0: no
// hidden effect, yet joint 1's gap (1.8 % of its torque RMS, 6.6 noise floors of the torque's
// sample-to-sample noise) was read as `unknown`. It is a broadband 2-6 Hz part of the residual that
// the potentiometers' noise puts there twice: through the model's acceleration estimate (the
// positions' noise floor, measured) and through the controller's answer to the same noise.
TEST(DiagnoseCommand, ClosedLoopRigidPlantLogAt1kHzWithoutEffectsIsNone) {
  const nlohmann::json d =
      diagnose_excited("clean_1khz", "", "--plant dyncc --trajectory fourier --rate 1000 --seed 71000");
  EXPECT_EQ(d["verdict"]["effect"], "none") << d["verdict"].dump();
  const auto& gap = d["gap"];
  // What the potentiometers' 1.5 mrad steps do to the model is the larger floor on every joint.
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_GT(gap["position_noise_floor"][j].get<double>(), 3 * gap["noise_floor"][j].get<double>()) << j + 1;
  }
}

// The same run with a rotor inertia on joint 3 and a torque gain of the same joint: the spring
// that was also selected took 11 % of the rotor inertia (0.105 for 0.118); without it both are
// within the bench's 10 %.
TEST(DiagnoseCommand, ClosedLoopRotorInertiaBesideATorqueGainOfItsJoint) {
  const double inertia = 0.11834, gain = 1.05502;
  const nlohmann::json d =
      diagnose_excited("rotor_gain_excite", effects_file_of({joint_effect("rotor_inertia", 3, "ia", inertia),
                                                             joint_effect("torque_gain", 3, "gain", gain)}));
  EXPECT_EQ(d["verdict"]["effect"], "rotor_inertia") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({3}));
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("ia3") && fitted.count("gain3")) << d["selected"].dump();
  EXPECT_NEAR(fitted["ia3"], inertia, 0.1 * inertia);
  EXPECT_NEAR(fitted["gain3"], gain, 0.1 * (gain - 1.0));
  for (const auto& [name, value] : fitted) EXPECT_EQ(name.rfind("stiffness", 0), std::string::npos) << name;
}

// Tele-operation with the dyncc plant at 1 kHz (the blind seed 43, case 18): a Coulomb friction of
// joint 1 at 5 % of its torque. The operator moves joint 1 in the first three of the five
// cross-validation folds and holds it within four potentiometer steps in the last two, where its
// friction's sign is the velocity estimate's noise: the shrink was 75-96 % away from zero
// velocity in the moving folds, but the interval over all five folds reached below zero and the
// verdict was `unknown`. A friction is judged on the folds in which its joint moves.
TEST(DiagnoseCommand, TeleoperationFrictionOfAJointThatRestsInTwoFoldsIsNamed) {
  const double fc = 0.0503055;
  const nlohmann::json d =
      diagnose_excited("teleop_coulomb", effects_file_of({joint_effect("coulomb_friction", 1, "fc", fc)}),
                       "--plant dyncc --trajectory teleop --rate 1000 --seed 43018");
  EXPECT_EQ(d["verdict"]["effect"], "coulomb_friction") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({1}));
  ASSERT_FALSE(d["selected"].empty());
  EXPECT_NEAR(d["selected"][0]["parameters"][0]["value"].get<double>(), fc, 0.1 * fc);
}

// The controller computes its torque from the positions read at a row and holds it until the next
// row, so on average it acts half a period after its time stamp. With noise-free, unquantised
// sensors (no other source of lag: the potentiometers' noise, which the controller answers, adds
// about another half period) a sensor delay of the rigid plant reads as itself once the torque is
// known to be held, and half a period long when it is taken as measured at its time stamp.
TEST(DiagnoseCommand, AHeldTorqueCommandActsHalfAPeriodAfterItsTimeStamp) {
  const double delay = 0.015, period = 1.0 / 200;
  const std::string effects =
      fmt::format(R"({{"effects": [{{"effect": "sensor_delay", "parameters": {{"delay": {}}}}}]}})", delay);
  const std::string run = "--plant dyncc --trajectory fourier --rate 200 --seed 5 --noise 0 --quantum 0";
  for (const bool held : {true, false}) {
    const nlohmann::json d =
        diagnose_excited(held ? "held_delay" : "stamped_delay", effects, run, held ? "--held-torque" : "");
    EXPECT_EQ(d["torque"], held ? "held command" : "at its time stamp");
    EXPECT_EQ(d["verdict"]["effect"], "sensor_delay") << d["verdict"].dump();
    std::map<std::string, double> fitted = fitted_of(d);
    ASSERT_TRUE(fitted.count("delay")) << d["selected"].dump();
    EXPECT_NEAR(fitted["delay"], held ? delay : delay + 0.5 * period, 0.1 * period) << (held ? "held" : "stamped");
  }
}

// At 81 Hz half a period is 6 ms: read as measured at its time stamp, the held command of an
// effect-free closed-loop run was taken for a sensor delay (7-19 ms on both plants and both
// trajectories, which kept the bench's 81 Hz Kraft logs open loop). Known to be held, it is none.
TEST(DiagnoseCommand, ClosedLoopKraftLogAt81HzWithoutEffectsIsNone) {
  const nlohmann::json d = diagnose_excited("clean_81hz", "", "--plant dyncc --trajectory fourier --rate 81 --seed 7");
  EXPECT_EQ(d["verdict"]["effect"], "none") << d["verdict"].dump();
}

// The MuJoCo plant on a Fourier reference at 200 Hz (the blind seed 47, case 39): viscous friction
// of joint 3 (20 % of the torque) beside a sensor delay. Fitted over the arm, the viscous columns
// of joints 1 and 2 took the delay as negative friction, the whole fit was implausible, and the
// delay was named first; the viscous friction of joint 3 alone is plausible and leads.
TEST(DiagnoseCommand, ViscousFrictionIsNotLostToTheDelayItsOtherJointsMimic) {
  const double fv = 0.524476, delay = 0.0415925;
  const nlohmann::json d =
      diagnose_excited("viscous_delay",
                       effects_file_of(
                           {joint_effect("viscous_friction", 3, "fv", fv),
                            fmt::format(R"({{"effect": "sensor_delay", "parameters": {{"delay": {}}}}})", delay)}),
                       "--plant mujoco --trajectory fourier --rate 200 --seed 47039");
  EXPECT_EQ(d["verdict"]["effect"], "viscous_friction") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({3}));
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("fv3") && fitted.count("delay")) << d["selected"].dump();
  EXPECT_NEAR(fitted["fv3"], fv, 0.1 * fv);
  EXPECT_NEAR(fitted["delay"], delay, 1.0 / 200);
}

// The MuJoCo plant on a Fourier reference at 1 kHz (the blind seed 443, case 39): positions
// logged 45 ms late beside a viscous friction of joint 1. Alone, the delay fits 31 ms (the
// friction's velocity column takes part of what the delay's torque lead explains, with the
// opposite sign); its secant, made there and read beside the friction, said 43.5 ms, 1.4 samples
// short. Made again at the joint fit's delay it reads 44.15 ms.
TEST(DiagnoseCommand, ALongDelayIsReadWhereItsSecantIsMadeBesideTheOtherEffects) {
  const double delay = 0.04492697710238963, fv = 0.047119147715275894;
  const nlohmann::json d =
      diagnose_excited("delay_viscous_1khz",
                       effects_file_of(
                           {fmt::format(R"({{"effect": "sensor_delay", "parameters": {{"delay": {}}}}})", delay),
                            joint_effect("viscous_friction", 1, "fv", fv)}),
                       "--plant mujoco --trajectory fourier --rate 1000 --seed 443039");
  EXPECT_EQ(d["verdict"]["effect"], "sensor_delay") << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("delay") && fitted.count("fv1")) << d["selected"].dump();
  EXPECT_NEAR(fitted["delay"], delay, 1.0 / 1000);  // the bench's goal: within one sample
  EXPECT_NEAR(fitted["fv1"], fv, 0.1 * fv);
}

// A 10 g payload on the MuJoCo plant's tele-operation log at 500 Hz (the task of the paper: on the
// hook from 17 s to about 59 s) with the bench's case seed, diagnosed; the verdict must be the
// payload, and its fitted parameters are returned.
std::map<std::string, double> teleop_payload_fit(const std::string& name, double mass, unsigned seed) {
  const nlohmann::json d =
      diagnose_excited(name,
                       fmt::format(R"({{"effects": [{{"effect": "payload", "parameters": {{"mass": {}}}}}]}})", mass),
                       fmt::format("--plant mujoco --trajectory teleop --rate 500 --seed {}", seed));
  EXPECT_EQ(d["verdict"]["effect"], "payload") << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  EXPECT_TRUE(fitted.count("mass")) << d["selected"].dump();
  return fitted;
}

// Tele-operation on the MuJoCo plant at 500 Hz (the blind seed 23, case 57): a 10 g payload on the
// hook from 17 s on (5 % of the torque). The arm rests in 75 % of the rows, and there the torque
// balance holds a static friction anywhere within +-fc, which takes up part of the load: fitted
// through those rows the mass read 22 % low (0.0081 kg). A joint whose held-out residual near zero
// velocity is larger than that away from it is fitted again without those rows.
TEST(DiagnoseCommand, TeleoperationPayloadIsFittedAwayFromTheRowsWhereTheArmRests) {
  const double mass = 0.0103858;
  std::map<std::string, double> fitted = teleop_payload_fit("teleop_payload", mass, 23057);
  EXPECT_NEAR(fitted["mass"], mass, 0.03 * mass);
}

// The same task on the blind seed 59, case 33 (a 10 g payload, 5 % of the torque): joints 2 and 3
// rest 5-7 times worse than they move and left their rows at rest out, but the base joint, 1.1
// times worse, kept them while the bar was twice, and its static friction took up part of the
// payload's coupling torques: the mass read 3.8 % low (0.01006 kg). Any excess drops them.
// Since the logged torque passes the filter twice, as the model's inertial torque does (dataset.hpp),
// this log read 10.01 g (-4.3 %): the static friction the plant holds near zero velocity spread
// through the filter into the rows around, which stayed. Left out as well (kStaticFrictionLeak):
// 10.42 g (-0.4 %).
TEST(DiagnoseCommand, TeleoperationPayloadIsNotTakenUpByTheBaseJointsStaticFriction) {
  const double mass = 0.010460572454548567;
  std::map<std::string, double> fitted = teleop_payload_fit("teleop_payload_base", mass, 59033);
  EXPECT_NEAR(fitted["mass"], mass, 0.03 * mass);
}

// The same task at 1 kHz with a torque gain of joint 3 (1.11, 10 % of the torque) beside the 10 g
// load (5 %; blind seed 443 case 9). The gain is accepted first and takes up part of the load's
// torque on joint 3; the load's window, searched once on the model's residual (which holds the
// gain's torque too), was 18.4-51.8 s, the load was dropped beside the gain as not significant,
// and the gain read 1.0763. Each later step searches the window again with the accepted
// effects' columns fitted beside the load's: 17.4-58.8 s for 17.0-58.8, and both read right. Since
// the logged torque passes the filter twice (see the test above) the mass read 9.96 g (-4.3 %), and
// since the rows a static friction spreads into are left out too, 10.40 g (+0.02 %).
TEST(DiagnoseCommand, APayloadBesideAGainOfItsJointIsPlacedBesideTheGain) {
  const double gain = 1.1098245094324728, mass = 0.010402026200646633;
  const nlohmann::json d =
      diagnose_excited("teleop_gain_payload",
                       effects_file_of({joint_effect("torque_gain", 3, "gain", gain),
                                        fmt::format(R"({{"effect": "payload", "parameters": {{"mass": {}}}}})", mass)}),
                       "--plant mujoco --trajectory teleop --rate 1000 --seed 443009");
  EXPECT_EQ(d["verdict"]["effect"], "torque_gain") << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("gain3") && fitted.count("mass")) << d["selected"].dump();
  EXPECT_NEAR(fitted["gain3"], gain, 0.1 * (gain - 1));
  EXPECT_NEAR(fitted["mass"], mass, 0.03 * mass);
  EXPECT_NEAR(fitted["picked_up_at"], 17.0, 1.0);
}

// The same task on the blind seed 97, case 57 (on the hook from 17.000 s to 58.866 s): the arm
// holds still from 8 s to 16 s before the pick-up, and static friction keeps an offset there that
// the model does not have. The window chosen by what its fit explains in sample took that hold
// in: picked up at 6.8 s, the mass 26 % low (0.0077 kg). Chosen by what it explains held out, the
// pick-up is found within a second (17.45 s: the arm is still until then). The mass read 4.6 %
// low, then 8.6 % once the logged torque passed the filter twice, and within the bench's 3 % (-2.0 %)
// since the rows a static friction spreads into are left out of the fit (kStaticFrictionLeak).
TEST(DiagnoseCommand, TeleoperationPayloadWindowDoesNotTakeInTheHoldBeforeThePickUp) {
  const double mass = 0.010418162701672565;
  std::map<std::string, double> fitted = teleop_payload_fit("teleop_payload_hold", mass, 97057);
  ASSERT_TRUE(fitted.count("picked_up_at"));
  EXPECT_NEAR(fitted["picked_up_at"], 17.0, 1.0);
  EXPECT_NEAR(fitted["mass"], mass, 0.03 * mass);
}

// The verdict is a Stribeck friction of `joint` (from 1) alone, its excess within 10 % of
// `excess`, and (where `scale` is not 0) read at the velocity scale `scale`.
void expect_stribeck(const nlohmann::json& d, int joint, double excess, double scale = 0) {
  EXPECT_EQ(d["verdict"]["effect"], "stribeck_friction") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({joint})) << d["verdict"].dump();
  ASSERT_FALSE(d["selected"].empty());
  if (scale > 0) {
    EXPECT_DOUBLE_EQ(d["selected"][0]["velocity_scale"].get<double>(), scale);
  }
  std::map<std::string, double> fitted = fitted_of(d);
  const std::string name = fmt::format("fs{}", joint);
  ASSERT_TRUE(fitted.count(name)) << d["selected"].dump();
  EXPECT_NEAR(fitted[name], excess, 0.1 * excess);
}

// Blind bench seed 61, case 18: a Stribeck excess of joint 1 at 5 % of the torque RMS on the rigid
// plant's tele-operation log (1 kHz). The first step chooses the plant's velocity scale (0.1 rad/s);
// narrowed to joint 1, a wider scale fits the rows away from zero velocity a little better, within
// the folds' spread, and took over (fs1 read 0.054, 23 % low).
TEST(DiagnoseCommand, TeleoperationStribeckScaleStaysTheStepsWhenNarrowingGainsNothingClear) {
  const double excess = 0.07046631934537236;
  const nlohmann::json d =
      diagnose_excited("teleop_stribeck", effects_file_of({joint_effect("stribeck_friction", 1, "fs", excess)}),
                       "--plant dyncc --trajectory teleop --rate 1000 --seed 61018");
  expect_stribeck(d, 1, excess, 0.1);  // dyncc-sim's own scale
}

// Blind bench seed 79, case 33: a Stribeck excess of joint 1 at 10 % of the torque RMS on the
// MuJoCo plant's tele-operation log (1 kHz). The plant sticks in a hold up to the whole static
// level, and with the sensor's noise driving the controller the holds' residual has no steady sign
// against the velocity estimate's; the scale was chosen by the rows away from zero velocity, but
// from a fit over every row, which those holds pulled: 0.065 rad/s, fs1 0.248 (+49 %). The final
// fit fits friction away from zero only; so does the choice now (0.1 rad/s, the plant's own).
TEST(DiagnoseCommand, TeleoperationStribeckScaleIsChosenByAFitWhereTheJointMoves) {
  const double excess = 0.16629863455508062;
  const nlohmann::json d =
      diagnose_excited("teleop_stribeck_mujoco", effects_file_of({joint_effect("stribeck_friction", 1, "fs", excess)}),
                       "--plant mujoco --trajectory teleop --rate 1000 --seed 79033");
  expect_stribeck(d, 1, excess, 0.1);  // the plant's own scale
}

// Blind bench seed 107, case 21: a Stribeck excess of joint 3 (21 % of the torque) on the MuJoCo
// plant's tele-operation log at 200 Hz. The plant sticks in its holds, where the torque is anywhere
// within the static friction's band (+0.17 to +0.20 N m in the holds after the joint rose, +0.02
// in a 26 s hold after it fell); a contact and the inertial parameters fitted those holds' levels,
// and a contact was named. Once a friction is evident where a joint moves and its holds stay worse
// than its motion, the selection does not score those holds.
TEST(DiagnoseCommand, HoldsThatKeepAStaticFrictionDoNotChooseTheEffect) {
  const double excess = 0.2091264189568471;
  const nlohmann::json d =
      diagnose_excited("teleop_stribeck_holds", effects_file_of({joint_effect("stribeck_friction", 3, "fs", excess)}),
                       "--plant mujoco --trajectory teleop --rate 200 --seed 107021");
  expect_stribeck(d, 3, excess);
}

// Blind bench seed 157, case 42: a torque gain of 1.055 on the Kraft's base joint, the rigid plant's
// tele-operation log at 1 kHz. That joint's torque is nearly all its inertia's, so the gain's column
// there is within 5 % of a rotor inertia's and each explains what the other does (57.5 and 57.3 %);
// until the twenty-fourth session it was named "torque_gain or rotor_inertia" (and before that,
// "rotor_inertia" alone). Where the joint moves they differ by what the gain also scales, the
// joint's Coriolis and friction torques: there the rotor inertia leaves more in every fold, and the
// gain is named alone.
TEST(DiagnoseCommand, KraftBaseJointGainIsToldFromARotorInertiaWhereTheJointMoves) {
  const double gain = 1.055031771868559;
  const nlohmann::json d =
      diagnose_excited("teleop_base_gain", effects_file_of({joint_effect("torque_gain", 1, "gain", gain)}),
                       "--plant dyncc --trajectory teleop --rate 1000 --seed 157042");
  EXPECT_EQ(d["verdict"]["effect"].get<std::string>(), "torque_gain") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({1})) << d["verdict"].dump();
  const std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("gain1")) << d["selected"].dump();
  EXPECT_NEAR(fitted.at("gain1"), gain, 0.1 * (gain - 1.0));
}

// Blind bench seed 281, case 54: a torque gain of 1.11 on the Kraft's base joint beside a viscous
// friction of that joint, the rigid plant's tele-operation log at 500 Hz. A gain above one makes the
// joint look lighter, and a rotor inertia of -0.060 (the description's reflected inertia is 0.041)
// explained as much; where the joint moves the friction, not yet fitted, is what is left, and that
// rotor inertia left less of it than the gain in every fold, so the verdict was `rotor_inertia`
// alone. A rotor inertia that reads a negative inertia is not named over the gain: the gain comes
// first, the rotor inertia stays its alternative, and both effects are read within the goals.
TEST(DiagnoseCommand, ARotorInertiaThatReadsNegativeIsNotNamedOverAGain) {
  const double gain = 1.1100682115663905, fv = 0.10287944385495627;
  const nlohmann::json d = diagnose_excited("teleop_gain_viscous",
                                            effects_file_of({joint_effect("torque_gain", 1, "gain", gain),
                                                             joint_effect("viscous_friction", 1, "fv", fv)}),
                                            "--plant dyncc --trajectory teleop --rate 500 --seed 281054");
  EXPECT_EQ(d["verdict"]["effect"].get<std::string>().substr(0, 11), "torque_gain") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({1})) << d["verdict"].dump();
  const std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("gain1") && fitted.count("fv1")) << d["selected"].dump();
  EXPECT_NEAR(fitted.at("gain1"), gain, 0.1 * (gain - 1.0));
  EXPECT_NEAR(fitted.at("fv1"), fv, 0.1 * fv);
  EXPECT_EQ(fitted.count("ia1"), 0U) << d["selected"].dump();
}

// A rotor inertia of 0.03 on the Kraft's base joint, MuJoCo's tele-operation log at 200 Hz (seed
// 903). A spring of joints 1 and 2 explained more at the first step (51.7 % against 46.7 %), and
// the rotor inertia, acting on joint 1 only, was no alternative on the spring's joints; the joint
// fit then narrowed the spring to joint 1, and the verdict was the spring alone. Judged again on
// joint 1, the rotor inertia is named beside it and, fitted in its place, reads the injected value.
// (Since the torque passes the filter twice as the model's inertial torque does, the rotor inertia
// leads the first step, 52.7 % against the spring's 32.7 %, and is named alone.)
TEST(DiagnoseCommand, AnAlternativeOnTheJointsAnEffectIsNarrowedToIsNamed) {
  const double inertia = 0.03;
  const nlohmann::json d =
      diagnose_excited("teleop_rotor_spring", effects_file_of({joint_effect("rotor_inertia", 1, "ia", inertia)}),
                       "--plant mujoco --trajectory teleop --rate 200 --seed 903");
  ASSERT_FALSE(d["selected"].empty()) << d["verdict"].dump();
  const nlohmann::json& first = d["selected"][0];
  EXPECT_EQ(first["joints"], nlohmann::json::array({1})) << first.dump();
  const std::string named = first["effect"].get<std::string>();
  EXPECT_NE(named.find("rotor_inertia"), std::string::npos) << named;
  std::map<std::string, double> read;
  if (first.contains("alternatives")) {
    for (const auto& a : first["alternatives"]) {
      for (const auto& p : a["parameters"]) read[p["name"]] = p["value"];
    }
  }
  if (first["effect"].get<std::string>().rfind("rotor_inertia", 0) == 0) read = fitted_of(d);
  ASSERT_TRUE(read.count("ia1")) << first.dump();
  EXPECT_NEAR(read.at("ia1"), inertia, 0.1 * inertia);
}

// Blind bench seed 173, case 54: a Coulomb friction of the Kraft's joint 2 (10 % of the torque)
// beside a viscous friction of joint 1, half as large, the rigid plant's tele-operation log at
// 1 kHz. Viscous columns of joints 1 and 2 led (62 %: on joint 2 they mimic part of the Coulomb
// friction); narrowed to joint 1 they explain 33 %, the Coulomb friction 56 %, but joint 1 moves
// in one fold only, so the narrowed friction's interval spans 90 points and the Coulomb friction
// was not "clearly above" it. What each explains on its own joints orders the steps.
TEST(DiagnoseCommand, ANarrowedLeaderExplainingLessThanTheNextGivesWay) {
  expect_excited_first_named("teleop_coulomb_viscous",
                             {{"coulomb_friction", 2, "fc", 0.08073969769724906},
                              {"viscous_friction", 1, "fv", 0.10282814068018863}},
                             "--plant dyncc --trajectory teleop --rate 1000 --seed 173054");
}

// Blind bench seed 811, case 39: a Stribeck excess of the Kraft's joint 1 (20 % of the torque)
// beside a viscous friction of that joint half as large, the MuJoCo plant's Fourier log at 500 Hz.
// Beside the excess, the viscous friction removes 30 % of the error where the joint moves but
// 2.4 % over all rows, whose rest near zero velocity is how MuJoCo's friction turns over; judged
// by all rows it was left out, and the excess took up its torque (fs1 0.673). A friction may
// remove its share where its joints move.
TEST(DiagnoseCommand, AFrictionBesideAnotherOfItsJointIsJudgedWhereTheJointMoves) {
  expect_excited_first_named("fourier_stribeck_viscous",
                             {{"stribeck_friction", 1, "fs", 0.3620606685572699},
                              {"viscous_friction", 1, "fv", 0.09414450727956884}},
                             "--plant mujoco --trajectory fourier --rate 500 --seed 811039");
}

// Blind bench seed 881, case 24: a Stribeck excess of the Kraft's joint 2 (10 % of the torque)
// beside a viscous friction of joint 1 half as large, the rigid plant's Fourier log at 200 Hz.
// The excess was accepted at 0.1 rad/s and a viscous friction of joints 1 and 2 after it; chosen
// again beside it, the excess's scale went to 0.33 rad/s, where the joint fit read fv2 -0.47 N m
// s/rad (a friction falling as the joint speeds up) and no excess, and the verdict was a Coulomb
// friction. A scale is chosen again only where every friction reads plausibly.
TEST(DiagnoseCommand, AStribeckScaleIsNotChosenAgainWhereAFrictionReadsNegative) {
  const nlohmann::json d = expect_excited_first_named("fourier_stribeck_beside_viscous",
                                                      {{"stribeck_friction", 2, "fs", 0.17273936566698078},
                                                       {"viscous_friction", 1, "fv", 0.040124740973268305}},
                                                      "--plant dyncc --trajectory fourier --rate 200 --seed 881024");
  EXPECT_FALSE(fitted_of(d).count("fv2")) << d["selected"].dump();
}

// Blind seed 1033, case 9: a rotor inertia of the Kraft's base joint (10 % of the torque) beside
// a 0.184 rad offset of joint 2, the MuJoCo plant's tele-operation log at 200 Hz. A torque gain of
// joints 1 and 2 led the first step (its joint 2 standing in for the offset, found next); the
// rotor inertia, alone beside no offset, was not significant there. Narrowed to joint 1 by the
// joint fit, the gain read 0.907: the step is chosen again on the joints it keeps, where the rotor
// inertia removes more beside the offset.
TEST(DiagnoseCommand, ANarrowedStepIsChosenAgainOnTheJointsItKeeps) {
  expect_excited_first_named("teleop_rotor_beside_offset",
                             {{"rotor_inertia", 1, "ia", 0.06041633994287962},
                              {"position_offset", 2, "offset", 0.18436271905368615}},
                             "--plant mujoco --trajectory teleop --rate 200 --seed 1033009");
}

// Blind bench seed 83, case 24: a Stribeck excess of joint 2 (10 % of the torque) beside a table
// touched by the hook, the rigid plant's Fourier log at 200 Hz. Joint 2 barely moves in two of the
// five folds, so the Stribeck friction's interval where it moves is wide (its shrink there 92, 85,
// 26, 91 and 93 % fold by fold), and by that interval a Coulomb friction (54, 28, 19, 56, 51 %)
// was as good and, simpler, was named. Clearly worse in every fold, it is not as good. (Since the
// twenty-first session's contact grid reaches the hook, the table is found too, and named first:
// the injected contact is the larger effect.)
TEST(DiagnoseCommand, CoulombFrictionClearlyWorseWhereTheJointMovesIsNotAsGoodAsStribeck) {
  const double excess = 0.056539506133563615, height = -0.3068371720914372;  // 4.1 mm above the lowest hook point
  const std::string effects =
      effects_file_of({fmt::format(R"({{"effect": "contact", "parameters": {{"height": {}}}}})", height),
                       joint_effect("stribeck_friction", 2, "fs", excess)});
  const nlohmann::json d = diagnose_excited("fourier_stribeck_contact", effects,
                                            "--plant dyncc --trajectory fourier --rate 200 --seed 83024");
  EXPECT_EQ(d["verdict"]["effect"], "contact") << d["verdict"].dump();
  bool stribeck_of_joint_2 = false;
  for (const auto& r : d["selected"]) {
    if (r["effect"] == "stribeck_friction" && r["joints"] == nlohmann::json::array({2})) stribeck_of_joint_2 = true;
  }
  EXPECT_TRUE(stribeck_of_joint_2) << d["selected"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("fs2")) << d["selected"].dump();
  EXPECT_NEAR(fitted["fs2"], excess, 0.1 * excess);
}

// Blind seed 941, case 12: a table 2.6 mm above the lowest point of the Kraft's hook, touched
// three times in the rigid plant's Fourier log at 1 kHz. The best contacts remove 94 % of the
// held-out error ([34, 154] %) with a stiffness of 1.4e4 N/m and a push at the fitted surface of
// -0.56 +- 0.25 N: the plant's damper lets the hook go before it leaves the table, and the linear
// fit reads that as a surface 40 um above where the push starts. Judged by that push every fit
// that explained the touches was implausible, and the verdict `unknown`. The force is read at the
// mean depth of the touches, where a table that pushes reads above zero; of the points whose
// interval is above zero, one whose push at the surface is not clearly below zero is preferred.
TEST(DiagnoseCommand, ATableTouchedByADampedContactIsJudgedByItsPushWhereTouched) {
  const nlohmann::json d =
      diagnose_excited("fourier_damped_touches",
                       effects_file_of({R"({"effect": "contact", "parameters": {"depth": 0.0026461130488934607}})"}),
                       "--plant dyncc --trajectory fourier --rate 1000 --seed 941012");
  EXPECT_EQ(d["verdict"]["effect"], "contact") << d["verdict"].dump();
  ASSERT_FALSE(d["selected"].empty());
  EXPECT_TRUE(d["selected"][0]["plausible"].get<bool>()) << d["selected"][0].dump();
}

// Blind bench seed 181, case 48: the hook touches a table 9.5 mm above the reference's lowest hook
// point, the rigid plant's Fourier log at 500 Hz: in 1 % of the rows, at 49 s and 57 s, both in
// the last of five even blocks. A fit on the other blocks had no touch to learn from, so no contact
// was confirmed held out (`unknown`: the best point 41.5 %, interval [-193, 276] %). The blocks'
// edge moves between the two touches, and each predicts the other.
TEST(DiagnoseCommand, TouchesInOneEvenBlockAreHeldOutInTwo) {
  const nlohmann::json d =
      diagnose_excited("fourier_two_touches",
                       effects_file_of({R"({"effect": "contact", "parameters": {"height": -0.3100545843500723}})"}),
                       "--plant dyncc --trajectory fourier --rate 500 --seed 181048");
  EXPECT_FALSE(d["heldout_blocks"]["even"].get<bool>());
  EXPECT_EQ(d["verdict"]["effect"], "contact") << d["verdict"].dump();
  ASSERT_FALSE(d["selected"].empty());
  EXPECT_GT(d["selected"][0]["shrink_interval"][0].get<double>(), 0.0) << d["selected"][0].dump();
}

// Blind bench seed 37, case 9: a Stribeck excess of joint 3 (20 % of the torque) beside a 26.6 ms
// sensor delay, the MuJoCo plant's tele-operation task at 500 Hz. The inertial parameters (first)
// and the delay were accepted; in the joint refit each explained all the other did, and judged
// together against the joint fit both were dropped, leaving no effect at all. Judged one at a
// time, in the order accepted, the inertial parameters go and the delay stays.
TEST(DiagnoseCommand, OfTwoArmEffectsThatExplainTheSameOneStays) {
  const double excess = 0.21777838961485388, delay = 0.026569486537544193;
  const std::string effects =
      effects_file_of({joint_effect("stribeck_friction", 3, "fs", excess),
                       fmt::format(R"({{"effect": "sensor_delay", "parameters": {{"delay": {}}}}})", delay)});
  const nlohmann::json d =
      diagnose_excited("teleop_stribeck_delay", effects, "--plant mujoco --trajectory teleop --rate 500 --seed 37009");
  ASSERT_FALSE(d["selected"].empty()) << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("delay")) << d["selected"].dump();
  EXPECT_NEAR(fitted["delay"], delay, 1.0 / 500);
}

// Blind bench seed 211, case 54: a Coulomb friction of joint 1 (5 % of the torque) beside a 1.03
// gain of that joint, the rigid plant's tele-operation log at 500 Hz. Alone in the selection, a
// Stribeck friction tied with it and was named first, its excess fs1 0.0049 +- 0.013: within its
// stated error of zero, and the rule that reads such a friction as its Coulomb friction ran only
// beside another effect, against the folds' error alone. It is the Coulomb friction.
TEST(DiagnoseCommand, AStribeckExcessWithinItsStatedErrorOfZeroIsACoulombFriction) {
  const double fc = 0.04989331040305657;
  const nlohmann::json d =
      diagnose_excited("teleop_coulomb_gain",
                       effects_file_of({joint_effect("coulomb_friction", 1, "fc", fc),
                                        joint_effect("torque_gain", 1, "gain", 1.0275165137458597)}),
                       "--plant dyncc --trajectory teleop --rate 500 --seed 211054");
  EXPECT_EQ(d["verdict"]["effect"].get<std::string>().substr(0, 16), "coulomb_friction") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({1})) << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  EXPECT_FALSE(fitted.count("fs1")) << d["selected"].dump();
  ASSERT_TRUE(fitted.count("fc1")) << d["selected"].dump();
  EXPECT_NEAR(fitted["fc1"], fc, 0.1 * fc);
}

// Case 19 of the blind seed 433: a PUMA 560 open-loop log at 200 Hz with a contact on its fifth
// link (0.954 N at its peak) and a viscous friction of joint 5. Beside the viscous friction the
// joint fit read the contact's force as -0.21 N, and the contact was said to be implausible, a
// surface pulling the arm down; but that force was the push at the fitted surface itself, the
// constant beside a spring, which a surface placed a little high reads below zero however firmly
// the table pushes where it is touched. The force is read at the mean depth of the touches (0.47
// N here) and the friction judged by its coefficient (-0.009 +- 0.011; its force, -2.2 +- 0.7 mN,
// is a frictionless table's): the contact is plausible.
TEST(DiagnoseCommand, AContactsForceIsReadAtTheMeanDepthOfItsTouches) {
  diagnose::SyntheticOptions options;
  options.rate = 200;
  options.seed = 433019;
  const nlohmann::json d =
      diagnose_synthetic_puma("contact_mean_push",
                              {{.effect = "contact", .joint = 4, .size = 0.9544207937674577},
                               {.effect = "viscous_friction", .joint = 4, .size = 0.2608143282636239}},
                              options);
  bool found = false;
  for (const auto& r : d["selected"]) {
    if (r["effect"].get<std::string>().rfind("contact", 0) != 0) continue;
    found = true;
    for (const auto& p : r["parameters"]) {
      if (p["name"] == "force") {
        EXPECT_GT(p["value"].get<double>(), 2.0 * p["error"].get<double>()) << r.dump();
      }
    }
    EXPECT_TRUE(r["plausible"].get<bool>()) << r.dump();
  }
  EXPECT_TRUE(found) << d["selected"].dump();
}

// Blind seed 887, case 9: a MuJoCo tele-operation log at 500 Hz with a Coulomb friction of the
// Kraft's joint 2 and an offset of joint 3 (0.058 rad). The offset's step names `payload or
// position_offset`: the load, accepted at its step, is read in the joint fit as 1.4 g at 4.5 m
// from its link, which no load is. The selection keeps it and says it is implausible as the joint
// fit reads it (and the offset in its place reads 0.0580 rad).
TEST(DiagnoseCommand, ASelectedEffectImplausibleInTheJointFitIsSaidToBe) {
  const nlohmann::json d =
      diagnose_excited("teleop_offset_read_as_load",
                       effects_file_of({joint_effect("coulomb_friction", 2, "fc", 0.21372995675646655),
                                        joint_effect("position_offset", 3, "offset", 0.05814120376856566)}),
                       "--plant mujoco --trajectory teleop --rate 500 --seed 887009");
  bool found = false;
  for (const auto& r : d["selected"]) {
    if (r["effect"].get<std::string>().rfind("payload", 0) != 0) continue;
    found = true;
    EXPECT_FALSE(r["plausible"].get<bool>()) << r.dump();
  }
  EXPECT_TRUE(found) << d["selected"].dump();
}

// Case 1 of the blind seed 457: a PUMA 560 open-loop Fourier log at 1 kHz whose joint 5 has a
// torque gain of 1.11. That joint's torque is mostly its drive's 0.85 N m Coulomb friction, so
// over all rows a Stribeck friction at its smallest velocity scale explained more of the joint
// (88 %) than the gain (81 %), by fitting how the model's friction turns over at reversals; a
// Coulomb friction took the joint from that Stribeck friction, the Stribeck friction from the
// Coulomb friction, and nothing was named (`unknown`). Where the joint moves the gain leaves a
// sixteenth of what the friction does, and it keeps the joint.
TEST(DiagnoseCommand, AGainOfAJointWhoseTorqueIsMostlyFrictionIsNamedByWhereTheJointMoves) {
  diagnose::SyntheticOptions options;
  options.rate = 1000;
  options.seed = 457001;
  const double gain = 1.11;
  const nlohmann::json d = diagnose_synthetic_puma("gain_of_a_friction_joint",
                                                   {{.effect = "torque_gain", .joint = 4, .size = gain}}, options);
  EXPECT_EQ(d["verdict"]["effect"].get<std::string>().substr(0, 11), "torque_gain") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({5})) << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("gain5")) << d["selected"].dump();
  EXPECT_NEAR(fitted["gain5"], gain, 0.1 * (gain - 1.0));
}

// Case 4 of the blind seed 353: a PUMA 560 open-loop Fourier log at 500 Hz with a Coulomb
// friction of joint 5 (0.204 N m) and a 0.28 kg payload picked up at 8.6 s. The first step names
// a gain of joints 2, 3 and 5 that stands in for the friction, the second the payload; at the
// third, what is left of the friction is at the reversals. Kept by where the joint moves there, a
// rotor inertia of joint 5 was accepted beside them and the joint fit read a gain of 0.84 and a
// negative rotor inertia instead of the friction: a joint is kept that way at the first step only.
TEST(DiagnoseCommand, AJointIsNotKeptByWhereItMovesBesideAcceptedEffects) {
  diagnose::SyntheticOptions options;
  options.rate = 500;
  options.seed = 353004;
  options.payload_on = 8.575436485072947;
  const double fc = 0.20378649938011392;
  const nlohmann::json d = diagnose_synthetic_puma("friction_beside_a_payload",
                                                   {{.effect = "coulomb_friction", .joint = 4, .size = fc},
                                                    {.effect = "payload", .joint = 4, .size = 0.28133894619224553}},
                                                   options);
  EXPECT_EQ(d["verdict"]["effect"], "coulomb_friction") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({5})) << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  EXPECT_FALSE(fitted.count("ia5")) << d["selected"].dump();
  ASSERT_TRUE(fitted.count("fc5")) << d["selected"].dump();
  EXPECT_NEAR(fitted["fc5"], fc, 0.1 * fc);
}

// Case 34 of the blind seed 463: a PUMA 560 open-loop Fourier log at 500 Hz with a Coulomb
// friction of joint 4 (0.119 N m) and a torque gain of 1.055 on joint 6. Both joints' torques are
// mostly their drives' friction, so one gain of joints 4 and 6 led the first step (97.3 % held
// out, gain4 0.911 standing in for the friction), and on joint 4 the Coulomb friction, as good
// there (72.4 % to 70.9 %) but not better by the margin, did not take the joint. Where joint 4
// moves the friction leaves clearly less than the gain in every fold: it takes the joint, and the
// gain is named on joint 6 at the next step.
TEST(DiagnoseCommand, AFrictionAsGoodAsAGainTakesTheJointWhereItLeavesLessWhereItMoves) {
  diagnose::SyntheticOptions options;
  options.rate = 500;
  options.seed = 463034;
  const double fc = 0.11930452726275238, gain = 1.055;
  const nlohmann::json d = diagnose_synthetic_puma("friction_beside_a_gain",
                                                   {{.effect = "coulomb_friction", .joint = 3, .size = fc},
                                                    {.effect = "torque_gain", .joint = 5, .size = gain}},
                                                   options);
  EXPECT_EQ(d["verdict"]["effect"], "coulomb_friction") << d["verdict"].dump();
  EXPECT_EQ(d["verdict"]["joints"], nlohmann::json::array({4})) << d["verdict"].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  EXPECT_FALSE(fitted.count("gain4")) << d["selected"].dump();
  ASSERT_TRUE(fitted.count("fc4") && fitted.count("gain6")) << d["selected"].dump();
  EXPECT_NEAR(fitted["fc4"], fc, 0.1 * fc);
  EXPECT_NEAR(fitted["gain6"], gain, 0.1 * (gain - 1.0));
}

// Blind seed 907, case 29: a Panda spring of joint 4 (189.7 N m/rad) beside a torque gain of 1.055
// on that joint, open loop at 81 Hz, read 170.7 N m/rad: the spring's compliance scaled by the
// gain twice, its column being made from the logged torque (1/g of what the spring carries) and
// its coefficient scaled to applied torque as a torque's is. A shift of the positions is no
// torque: its rows are put in logged torque, and a spring's compliance is its coefficient over the
// gain. Here with a gain of 1.11, so that reading it twice would be 20 % of the stiffness.
TEST(DiagnoseCommand, ASpringBesideAGainOfItsJointIsReadInAppliedTorqueOnce) {
  diagnose::SyntheticOptions options;
  options.rate = 81;
  options.seed = 907029;
  const double stiffness = 189.7, gain = 1.11;
  const nlohmann::json d = diagnose_synthetic(panda_derivation(), "panda", "spring_beside_a_gain",
                                              {{.effect = "joint_elasticity", .joint = 3, .size = stiffness},
                                               {.effect = "torque_gain", .joint = 3, .size = gain}},
                                              options);
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("stiffness4") && fitted.count("gain4")) << d["selected"].dump();
  EXPECT_NEAR(fitted["stiffness4"], stiffness, 0.03 * stiffness);
  EXPECT_NEAR(fitted["gain4"], gain, 0.05 * (gain - 1.0));
}

// Blind seed 1051, case 14: a 100 g load carried by the Panda from 15.2 to 32.3 s beside a 0.177
// rad offset of joint 6, open loop at 1 kHz. The load, accepted first, was placed against a
// residual that still held the offset: as a load over the whole log, which beside the offset then
// explained nothing more and was dropped; the offset alone read 0.136. Placed again beside the
// offset, the load is found while carried.
TEST(DiagnoseCommand, ALoadAcceptedBeforeAnotherEffectIsPlacedAgainBesideIt) {
  diagnose::SyntheticOptions options;
  options.rate = 1000;
  options.seed = 1051014;
  options.payload_on = 15.194764909741503;
  options.payload_off = 32.252253332046045;
  const double offset = 0.1773425274907022, mass = 0.09998392772632175;
  const nlohmann::json d = diagnose_synthetic(panda_derivation(), "panda", "offset_beside_a_carried_load",
                                              {{.effect = "position_offset", .joint = 5, .size = offset},
                                               {.effect = "payload", .joint = 5, .size = mass}},
                                              options);
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("offset6") && fitted.count("mass") && fitted.count("picked_up_at")) << d["selected"].dump();
  EXPECT_NEAR(fitted["offset6"], offset, 0.03 * offset);
  EXPECT_NEAR(fitted["mass"], mass, 0.03 * mass);
  EXPECT_NEAR(fitted["picked_up_at"], options.payload_on, 0.1);
  EXPECT_NEAR(fitted["put_down_at"], options.payload_off, 0.1);
}

// A table at `height` m (base frame) in a run of dyncc excite, diagnosed; the verdict must be the
// contact.
nlohmann::json diagnosed_contact(const std::string& name, double height, const std::string& run) {
  const nlohmann::json d = diagnose_excited(
      name, fmt::format(R"({{"effects": [{{"effect": "contact", "parameters": {{"height": {}}}}}]}})", height), run);
  EXPECT_EQ(d["verdict"]["effect"], "contact") << d["verdict"].dump();
  return d;
}

// The blind seed 107, case 3: a table 5.2 mm above the lowest point of the Kraft's hook, touched
// in 0.2 % of the rows of the MuJoCo plant's Fourier log at 1 kHz (four touches, up to 105 N). The
// hook sits 0.40 m along the forearm, beyond the contact grid's farthest point (0.26 m): gated on
// the grid's points, whose lowest rows are not the touches, the contact explained 2.5 % and the
// verdict was `unknown`. The local search from the grid's best points reaches the hook.
TEST(DiagnoseCommand, BriefTouchesOfATableOffTheContactGridAreAContact) {
  const nlohmann::json d = diagnosed_contact("mujoco_touch", -0.2645772766861086,
                                             "--plant mujoco --trajectory fourier --rate 1000 --seed 107003");
  ASSERT_FALSE(d["selected"].empty());
  EXPECT_GT(d["selected"][0]["shrink"].get<double>(), 0.3) << d["selected"][0].dump();
}

// The blind seed 107, case 48: a table 10.8 mm above the lowest point of the Kraft's hook, the
// rigid plant's Fourier log at 200 Hz, touched near 3 s and 55 s (1.2 % of the rows). The grid
// reached 1.5 times the arm's scale (0.26 m on the Kraft), the hook is 0.40 m along the forearm:
// no grid point's gate held the touches, the best explained 4.1 %, below what starts the local
// search, and the verdict was `unknown`. The grid now reaches 2.5 times the scale; the contact is
// found at the hook and the table's height (z = -0.266 m in the run).
TEST(DiagnoseCommand, TouchesOfAHookFarAlongTheLastLinkAreAContact) {
  const nlohmann::json d = diagnosed_contact("rigid_far_hook", -0.26595683814038623,
                                             "--plant dyncc --trajectory fourier --rate 200 --seed 107048");
  ASSERT_FALSE(d["selected"].empty());
  EXPECT_GT(d["selected"][0]["shrink_interval"][0].get<double>(), 0.0) << d["selected"][0].dump();
  std::map<std::string, double> fitted = fitted_of(d);
  EXPECT_NEAR(fitted["point_x"], 0.40, 0.03) << d["selected"][0].dump();
  EXPECT_NEAR(fitted["surface_height"], -0.266, 0.01) << d["selected"][0].dump();
}

// The blind seed 41, case 33: a table 2.6 mm above the lowest point of the Kraft's hook in the
// MuJoCo plant's tele-operation task at 200 Hz; the operator puts the hook down on it for about
// 11 s (17 % of the rows), and the controller holds it there with whatever force its position
// error asks. Read as a pressed contact (a spring and kinetic friction) the force sat 15-100 m off
// the link and the verdict was `unknown`; a held contact (a push at the hook's searched point) is
// the verdict, its push determined with its rows at rest kept in the final fit (with holds beside
// it and without those rows: -4.9 N +- 1e12).
TEST(DiagnoseCommand, AHookHeldOnATableIsAHeldContact) {
  const nlohmann::json d = diagnosed_contact("mujoco_held", 0.002576444469301687,
                                             "--plant mujoco --trajectory teleop --rate 200 --seed 41033");
  std::map<std::string, double> fitted = fitted_of(d);
  ASSERT_TRUE(fitted.count("force") && !fitted.count("moment_x")) << d["selected"].dump();
  double push_error = 0;
  for (const auto& p : d["selected"][0]["parameters"]) {
    if (p["name"] == "force") push_error = p["error"];
  }
  EXPECT_GT(fitted["force"], 2 * push_error) << d["selected"][0].dump();
}

}  // namespace
}  // namespace dyncc::test
