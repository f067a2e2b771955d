// `dyncc excite` (dyncc-sim excite) from the command line: the log has the rows, rate and columns
// asked for, positions are whole multiples of the quantum, the effects file is applied, and every
// bad effects file exits 2 with a message naming the file and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

namespace dyncc::test {
namespace {

TEST(ExciteCommand, WritesOneRowPerControlStepWithQuantisedPositions) {
  const double quantum = 2 * 3.14159265358979323846 / 4096;
  for (const int rate : {81, 1000}) {
    const auto out = output_path("log" + std::to_string(rate) + ".csv");
    const DynccRun run =
        run_dyncc("excite --rate " + std::to_string(rate) + " --duration 2 --seed 3 --noise 0 --out " + quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.errors;
    const Csv log = read_csv(out);
    EXPECT_EQ(log.header, (std::vector<std::string>{"t", "q1", "q2", "q3", "tau1", "tau2", "tau3"}));
    ASSERT_EQ(log.rows.size(), static_cast<std::size_t>(2 * rate));
    for (std::size_t i = 0; i < log.rows.size(); ++i) {
      const auto& row = log.rows[i];
      ASSERT_EQ(row.size(), 7U);
      EXPECT_NEAR(row[0], static_cast<double>(i) / rate, 1e-9) << "row " << i;
      for (int k = 1; k <= 3; ++k) {
        const double counts = row[static_cast<std::size_t>(k)] / quantum;
        EXPECT_NEAR(counts, std::round(counts), 1e-6) << "row " << i << " q" << k;
      }
    }
  }
}

// The same run with the effect-free file, and with a torque gain of 2 on joint 2: the command on
// joint 2 halves (the arm barely moves differently), the others stay.
TEST(ExciteCommand, AppliesTheEffectsFile) {
  const auto none = write_text("none.json", R"({"effects": []})");
  const auto gain =
      write_text("gain.json",
                 R"({"effects": [{"effect": "torque_gain", "joints": [2], "parameters": {"gain": [2.0]}}]})");
  const auto a = output_path("none.csv"), b = output_path("gain.csv");
  const std::string common = "excite --trajectory fourier --rate 200 --duration 6 --noise 0 --effects ";
  ASSERT_EQ(run_dyncc(common + quoted(none) + " --out " + quoted(a)).exit_code, 0);
  ASSERT_EQ(run_dyncc(common + quoted(gain) + " --out " + quoted(b)).exit_code, 0);
  const Csv free = read_csv(a), gained = read_csv(b);
  ASSERT_EQ(free.rows.size(), gained.rows.size());
  double ratio_num = 0, ratio_den = 0;
  for (std::size_t i = 600; i < free.rows.size(); ++i) {
    ratio_num += gained.rows[i][5] * free.rows[i][5];
    ratio_den += free.rows[i][5] * free.rows[i][5];
  }
  EXPECT_NEAR(ratio_num / ratio_den, 0.5, 0.02);
}

TEST(ExciteCommand, BadEffectFilesExitTwoNamingTheFileAndField) {
  struct Case {
    std::string name, text, expected;
  };
  const Case cases[] = {
      {"malformed.json", R"({"effects": [)", "malformed JSON"},
      {"unknown.json", R"({"effects": [{"effect": "friction", "joints": [1], "parameters": {}}]})",
       "effects[0].effect: unknown effect 'friction'"},
      {"joint.json", R"({"effects": [{"effect": "coulomb_friction", "joints": [4], "parameters": {"fc": [0.1]}}]})",
       "effects[0].joints[0]: 4 is not a joint"},
      {"missing.json", R"({"effects": [{"effect": "viscous_friction", "joints": [1], "parameters": {}}]})",
       "effects[0].parameters.fv: missing"},
      {"count.json", R"({"effects": [{"effect": "rotor_inertia", "joints": [1, 2], "parameters": {"ia": [0.1]}}]})",
       "effects[0].parameters.ia: expected an array of 2"},
      {"range.json", R"({"effects": [{"effect": "torque_gain", "joints": [3], "parameters": {"gain": [-1]}}]})",
       "effects[0].parameters.gain[0]: -1 is outside"},
      {"typo.json", R"({"effects": [{"effect": "payload", "parameters": {"mass": 0.5, "mas": 1}}]})",
       "effects[0].parameters.mas: payload has no such parameter"},
      {"top.json", R"({"effect": []})", "effect: unknown field"},
  };
  for (const Case& c : cases) {
    const auto file = write_text(c.name, c.text);
    const DynccRun run =
        run_dyncc("excite --duration 1 --effects " + quoted(file) + " --out " + quoted(output_path("x.csv")));
    EXPECT_EQ(run.exit_code, 2) << c.name << "\n" << run.errors;
    EXPECT_NE(run.errors.find(c.name), std::string::npos) << "names the file\n" << run.errors;
    EXPECT_NE(run.errors.find(c.expected), std::string::npos) << c.name << "\n" << run.errors;
  }
  // A file the MuJoCo plant cannot play, and options out of range.
  const auto backlash =
      write_text("backlash.json",
                 R"({"effects": [{"effect": "backlash", "joints": [1], "parameters": {"width": [0.01]}}]})");
  DynccRun run = run_dyncc("excite --plant mujoco --duration 1 --effects " + quoted(backlash) + " --out " +
                           quoted(output_path("y.csv")));
  EXPECT_EQ(run.exit_code, 2) << run.errors;
  EXPECT_NE(run.errors.find("backlash.json: effects[0]: backlash is not possible on the MuJoCo plant"),
            std::string::npos)
      << run.errors;
  for (const std::string arguments : {"excite --rate 50 --out x.csv", "excite --rate 2000 --out x.csv",
                                      "excite --plant bullet --out x.csv", "excite --trajectory random --out x.csv",
                                      "excite --duration 1", "excite --effects /nonexistent.json --out x.csv"}) {
    run = run_dyncc(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.errors;
  }
}

}  // namespace
}  // namespace dyncc::test
