// `dyncc diagnose` and `dyncc sim2real-bench` from the command line: exit codes, the JSON the
// issue specifies, bad input, and a bench whose truth stays in files of their own.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

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
// the keys, and a log without effects is not diagnosed with one.
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

}  // namespace
}  // namespace dyncc::test
