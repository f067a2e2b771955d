// Reading logs for the diagnosis: every kind of malformed or inconsistent log is refused with
// file:line:column and what was expected; the column map renames foreign logs; the audit reads
// the rate, the jitter and the quantisation step off the log itself.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>

#include "cli_support.hpp"
#include "diagnose/column_filter.hpp"
#include "diagnose/joint_log.hpp"
#include "diagnose/long_rests.hpp"
#include "diagnose/signals.hpp"

namespace dyncc::test {
namespace {

std::string rows(int count, double dt = 0.01, double quantum = 0.0) {
  std::string s;
  for (int i = 0; i < count; ++i) {
    const double t = i * dt, q = 0.3 * std::sin(t);
    const double qq = quantum > 0 ? quantum * std::round(q / quantum) : q;
    s += std::to_string(t) + "," + std::to_string(qq) + "," + std::to_string(0.5 * q) + ",1.0,2.0\n";
  }
  return s;
}

TEST(DiagnoseLog, ReadsAndMapsColumns) {
  const auto path = write_text(
      "ok.csv", "time,pos1,pos2,tau1,tau2,comment\n" + [] {
        std::string s;
        for (int i = 0; i < 60; ++i) s += std::to_string(0.01 * i) + ",0.1,0.2,1,2,hello\n";
        return s;
      }());
  const auto log = diagnose::read_joint_log(path.string(), 2, diagnose::parse_column_map("time=t,pos1=q1,pos2=q2"));
  EXPECT_EQ(log.samples(), 60);
  EXPECT_EQ(log.joints(), 2);
  EXPECT_DOUBLE_EQ(log.q(5, 1), 0.2);
  EXPECT_DOUBLE_EQ(log.tau(5, 0), 1.0);
  EXPECT_FALSE(log.qd.has_value());
}

TEST(DiagnoseLog, RefusesMalformedLogsWithAPlace) {
  const std::string header = "t,q1,q2,tau1,tau2\n";
  struct Case {
    std::string name, text, expected;
    int joints = 2;
  };
  std::string backwards = header + rows(60);
  backwards += "0.2,0,0,0,0\n";
  std::string nan = header + rows(10) + "0.5,0,nan,0,0\n" + rows(60).substr(0);
  const Case cases[] = {
      {"empty.csv", "", "empty.csv:1:1: error: empty file"},
      {"no_tau.csv", "t,q1,q2,tau1\n" + rows(60), "no_tau.csv:1:1: error: missing column 'tau2'"},
      {"no_time.csv", "time,q1,q2,tau1,tau2\n" + rows(60), "no_time.csv:1:1: error: missing column 't'"},
      {"more_joints.csv", "t,q1,q2,q3,tau1,tau2\n" + rows(60), "more_joints.csv:1:9: error: column 'q3'"},
      {"backwards.csv", backwards, "backwards.csv:62:1: error: column 't': time must increase"},
      {"nan.csv", nan, "nan.csv:12:"},
      {"text.csv", header + "0,abc,0,0,0\n", "text.csv:2:3: error: column 'q1': expected a finite number, got 'abc'"},
      {"short_row.csv", header + "0,1,2\n", "short_row.csv:2:6: error: 3 fields, the header has 5"},
      {"few.csv", header + rows(20), "few.csv:21:1: error: 20 samples; the diagnosis needs at least 50"},
      {"twice.csv", "t,q1,q1,tau1,tau2\n" + rows(60), "twice.csv:1:6: error: column 'q1' appears twice"},
      {"partial_rates.csv", "t,q1,q2,tau1,tau2,qd1\n" + rows(60), "partial_rates.csv:1:1: error: optional qd columns"},
  };
  for (const Case& c : cases) {
    const auto path = write_text(c.name, c.text);
    try {
      diagnose::read_joint_log(path.string(), c.joints);
      ADD_FAILURE() << c.name << " was accepted";
    } catch (const diagnose::LogError& e) {
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(diagnose::read_joint_log("/nonexistent.csv", 2), diagnose::LogError);
  EXPECT_THROW(diagnose::parse_column_map("time"), diagnose::LogError);
  EXPECT_THROW(diagnose::parse_column_map("=t"), diagnose::LogError);
}

TEST(DiagnoseAudit, ReadsRateJitterAndQuantum) {
  const auto path = write_text("audit.csv", "t,q1,q2,tau1,tau2\n" + rows(400, 1.0 / 81, 1.5e-3));
  const auto log = diagnose::read_joint_log(path.string(), 2);
  const diagnose::Audit a = diagnose::audit_log(log);
  EXPECT_NEAR(a.rate, 81.0, 0.5);  // std::to_string keeps 6 decimals of the time stamps
  EXPECT_LT(a.jitter, 0.01);
  EXPECT_NEAR(a.joints[0].quantum, 1.5e-3, 1e-6);
  EXPECT_EQ(a.joints[1].quantum, 0.0) << "joint 2 is not quantised";
}

// The zero-phase filter: no delay (a sine below the cut-off comes through in phase) and a ramp
// passes unchanged to the ends (odd reflection at the edges).
TEST(DiagnoseSignals, ZeroPhaseLowpass) {
  const double rate = 200, f = 0.5;
  Eigen::VectorXd x(2000), ramp(2000);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    x[i] = std::sin(2 * 3.141592653589793 * f * static_cast<double>(i) / rate);
    ramp[i] = 0.01 * static_cast<double>(i);
  }
  const Eigen::VectorXd y = diagnose::zero_phase_lowpass(x, 5.0, rate);
  EXPECT_LT((y - x).segment(200, 1600).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_LT((diagnose::zero_phase_lowpass(ramp, 5.0, rate) - ramp).cwiseAbs().maxCoeff(), 1e-6);
}

// Columns filtered side by side (Dataset::condition) are each what the filter makes of it alone,
// to the last bit, and the filter is a Butterworth one run twice: a sine at the cut-off comes
// through at half its amplitude (|H|^2 = 1/2 with the prewarped cut-off), one at a tenth of it
// whole, one at five times it at 1 / (1 + r^4), r the ratio of the prewarped frequencies
// (tan(pi f / rate) over that of the cut-off: 5.03 here; 5 in continuous time).
TEST(DiagnoseSignals, ColumnsFilteredTogetherAreEachFilteredAlone) {
  const double rate = 500, cutoff = 4;
  const Eigen::Index samples = 5000;
  diagnose::RowMatrix x(samples, 4);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.1);
  for (Eigen::Index i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / rate;
    x(i, 0) = std::sin(2 * std::numbers::pi * cutoff * t);
    x(i, 1) = std::sin(2 * std::numbers::pi * 0.1 * cutoff * t);
    x(i, 2) = std::sin(2 * std::numbers::pi * 5 * cutoff * t);
    x(i, 3) = (i > samples / 2 ? 1.0 : 0.0) + noise(random);  // a step in noise
  }
  diagnose::RowMatrix together = x;
  diagnose::zero_phase_lowpass_rows(together, cutoff, rate);
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const Eigen::VectorXd alone = diagnose::zero_phase_lowpass(x.col(c), cutoff, rate);
    for (Eigen::Index i = 0; i < samples; ++i) ASSERT_EQ(together(i, c), alone[i]) << "column " << c << " row " << i;
  }
  const auto amplitude = [&](Eigen::Index c) { return together.col(c).segment(1000, 3000).cwiseAbs().maxCoeff(); };
  EXPECT_NEAR(amplitude(0), 0.5, 0.005);
  EXPECT_NEAR(amplitude(1), 1.0, 0.005);
  const double r = std::tan(std::numbers::pi * 5 * cutoff / rate) / std::tan(std::numbers::pi * cutoff / rate);
  EXPECT_NEAR(amplitude(2), 1.0 / (1.0 + std::pow(r, 4)), 0.02 / (1.0 + std::pow(r, 4)));  // 25 samples a period
}

// A hold is a stretch near zero velocity of at least kLongRest within one log: a reversal's pass
// through zero is not, nor two short stretches that meet only across the end of a log.
TEST(DiagnoseSignals, LongRestsAreHoldsOfASecondOrMoreWithinOneLog) {
  diagnose::Dataset d;
  d.n = 2;
  d.step = 0.1;
  constexpr int kRows = 100;  // two logs of 5 s each, 10 rows a second
  d.analysis_t.resize(kRows);
  for (int r = 0; r < kRows; ++r) {
    d.analysis_t[r] = (r % 50) * d.step;
    d.analysis_log.push_back(r / 50);
  }
  Eigen::VectorXd away = Eigen::VectorXd::Ones(kRows * d.n);
  auto rest = [&](int joint, int begin, int end) {
    for (int r = begin; r < end; ++r) away[r * d.n + joint] = 0;
  };
  rest(0, 10, 22);  // joint 1: a hold of 1.2 s
  rest(0, 30, 33);  // ... a reversal of 0.3 s
  rest(0, 44, 56);  // ... 0.6 s at the end of log 1 and 0.6 s at the start of log 2
  rest(1, 60, 70);  // joint 2: exactly 1 s (ten rows of 0.1 s)
  rest(1, 80, 89);  // ... 0.9 s
  const Eigen::VectorXd rests = diagnose::in_long_rests(d, away);
  for (int r = 0; r < kRows; ++r) {
    EXPECT_EQ(rests[r * d.n], r >= 10 && r < 22 ? 1.0 : 0.0) << "joint 1, row " << r;
    EXPECT_EQ(rests[r * d.n + 1], r >= 60 && r < 70 ? 1.0 : 0.0) << "joint 2, row " << r;
  }
}

}  // namespace
}  // namespace dyncc::test
