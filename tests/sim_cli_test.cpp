// `dyncc simulate` and `dyncc report` from the command line: what a run writes, the replay of a
// recorded master trajectory, and every kind of bad input (exit code 2 and a message naming the
// field or the file, line and column).
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

TEST(SimulateCommand, WritesTheLogFiguresAndSummary) {
  const auto out = output_path("run");
  const DynccRun run = run_dyncc("simulate --scenario paper-0.5kg --adaptation off --duration 3 --out " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  const Csv log = read_csv(out / "log.csv");
  EXPECT_EQ(log.rows.size(), 3U * 81U + 1U) << "one row per 81 Hz control period";
  for (const char* name :
       {"t", "master_q1", "slave_q3", "s1", "s2", "s3", "tau2", "p_MX3R", "p_FV3", "contact", "payload"}) {
    EXPECT_GE(log.column(name), 0) << name;
  }
  const int p = log.column("p_MX3R");
  EXPECT_EQ(log.rows.front()[static_cast<std::size_t>(p)], log.rows.back()[static_cast<std::size_t>(p)])
      << "the fixed model does not adapt";
  for (const char* figure : {"angles", "errors", "estimates"}) {
    for (const char* ext : {".png", ".svg"})
      EXPECT_GT(std::filesystem::file_size(out / (std::string(figure) + ext)), 1000U);
  }
  EXPECT_NE(read_text(out / "summary.txt").find("paper-0.5kg"), std::string::npos);
}

// The master side replayed from a recording: the master's logged angles are the recording's.
TEST(SimulateCommand, ReplaysARecordedMasterTrajectory) {
  std::string text = "time_s,q1,q2,q3,ignored\n";
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.01 * i;
    text += std::to_string(t) + "," + std::to_string(0.2 * std::sin(t)) + "," + std::to_string(-0.3 + 0.1 * t) + "," +
            std::to_string(0.5) + ",7\n";
  }
  // `time_s` is not a known time column: the loader must say so; `t` works.
  const auto bad_header = write_text("bad_header.csv", text);
  DynccRun run = run_dyncc("simulate --scenario paper-unloaded --master-csv " + quoted(bad_header));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.errors.find("no column t"), std::string::npos) << run.errors;
  text.replace(0, 6, "t");
  const auto recording = write_text("master.csv", text);
  const auto out = output_path("replay");
  run = run_dyncc("simulate --scenario paper-unloaded --master-csv " + quoted(recording) + " --out " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  const Csv log = read_csv(out / "log.csv");
  EXPECT_NEAR(log.rows.back()[0], 4.0, 1.0 / 81) << "the run lasts as long as the recording";
  const int t = log.column("t"), q1 = log.column("master_q1"), q2 = log.column("master_q2"), s1 = log.column("s1");
  double worst = 0, tracking = 0;
  for (const auto& row : log.rows) {
    const double time = row[static_cast<std::size_t>(t)];
    worst = std::max(worst, std::abs(row[static_cast<std::size_t>(q1)] - 0.2 * std::sin(time + 0.1 / 81)));
    worst = std::max(worst, std::abs(row[static_cast<std::size_t>(q2)] - (-0.3 + 0.1 * (time + 0.1 / 81))));
    if (time > 2.0) tracking = std::max(tracking, std::abs(row[static_cast<std::size_t>(s1)]));
  }
  EXPECT_LT(worst, 2e-3);
  EXPECT_LT(tracking, 0.1) << "the slave follows the replayed master";
}

TEST(SimulateCommand, BadInputExitsTwoWithAMessage) {
  struct Case {
    std::string arguments, expected;
  };
  const std::string header = "t,q1,q2,q3\n";
  const auto not_number = write_text("not_number.csv", header + "0,0,0,0\n0.1,0,abc,0\n0.2,0,0,0\n");
  const auto not_finite = write_text("not_finite.csv", header + "0,0,0,0\n0.1,0,0,nan\n0.2,0,0,0\n");
  const auto backwards = write_text("backwards.csv", header + "0,0,0,0\n0.2,0,0,0\n0.1,0,0,0\n");
  const auto short_row = write_text("short.csv", header + "0,0,0,0\n0.1,0\n0.2,0,0,0\n");
  const auto missing = write_text("missing.csv", "t,q1,q3\n0,0,0\n");
  const auto tiny = write_text("tiny.csv", header + "0,0,0,0\n");
  const Case cases[] = {
      {"simulate --scenario nope", "scenario"},
      {"simulate --adaptation on", "--scenario is required"},
      {"simulate --scenario paper-1kg --adaptation maybe", "adaptation"},
      {"simulate --scenario paper-1kg --plant bullet", "plant"},
      {"simulate --scenario paper-1kg --payload -1", "payload"},
      {"simulate --scenario paper-1kg --master-csv /nonexistent.csv", "/nonexistent.csv: cannot open"},
      {"simulate --scenario paper-1kg --master-csv " + quoted(not_number), "not_number.csv:3:7: field q2"},
      {"simulate --scenario paper-1kg --master-csv " + quoted(not_finite), "not_finite.csv:3:9: field q3"},
      {"simulate --scenario paper-1kg --master-csv " + quoted(backwards),
       "backwards.csv:4:1: field t: time must increase"},
      {"simulate --scenario paper-1kg --master-csv " + quoted(short_row), "short.csv:3:"},
      {"simulate --scenario paper-1kg --master-csv " + quoted(missing), "missing.csv:1:1: header has no column q2"},
      {"simulate --scenario paper-1kg --master-csv " + quoted(tiny), "at least three samples"},
      {"simulate --scenario paper-1kg --plant mujoco --mjcf /nonexistent.xml", "/nonexistent.xml"},
      {"simulate --scenario paper-1kg --duration 1 --out /proc/forbidden", "/proc/forbidden"},
      {"report --plant bullet", "plant"},
  };
  for (const Case& c : cases) {
    const DynccRun run = run_dyncc(c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.errors;
    EXPECT_NE(run.errors.find(c.expected), std::string::npos) << c.arguments << "\n" << run.errors;
  }
}

}  // namespace
}  // namespace dyncc::test
