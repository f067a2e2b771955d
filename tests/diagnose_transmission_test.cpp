// A transmission between the position sensor and the link (gen/diagnose/shifted_positions): the
// positions are read on the motor side of an elastic joint or of a backlash, so they are off the
// link's by the torque over the stiffness, or by half the width on the side the torque pushes.
// Open-loop logs of 6- and 7-joint arms (the Kraft arm's torques are too small to show a plausible
// spring or dead band), the diagnosis on the CSV alone: it must name the effect and its joint and
// fit its size within the bench's 10 %. Tens of seconds each under the sanitizers, so the
// sanitizer run leaves this suite out (the same columns serve position_offset in
// diagnose_effect_test, which it runs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/diagnosis_output.hpp"
#include "diagnose/shifted_positions.hpp"
#include "diagnose/synthetic_log.hpp"
#include "dynamics_support.hpp"
#include "temp_path.hpp"

namespace dyncc::test {
namespace {

using diagnose::Injection;

const pipeline::Derivation& arm(const std::string& name) {
  static std::map<std::string, std::unique_ptr<pipeline::Derivation>> derived;
  auto& d = derived[name];
  if (!d) d = derive_file(std::filesystem::path(DYNCC_SOURCE_DIR) / "robots" / (name + ".yaml"));
  return *d;
}

// The diagnosis of an open-loop log with one injected effect; the fitted value of `parameter` in
// the first selected effect, which must be `effect` on `joint` (1-based) alone.
double named_and_fitted(const std::string& robot, const Injection& injected, const std::string& parameter, double rate,
                        unsigned seed) {
  const pipeline::Derivation& d = arm(robot);
  diagnose::SyntheticOptions options;
  options.rate = rate;
  options.seed = seed;
  options.duration = 30;
  const auto path = temp_path(injected.effect + ".csv");
  diagnose::write_synthetic_log(d, {injected}, options, path);
  const auto n = static_cast<Eigen::Index>(d.robot.coordinates.size());
  const diagnose::Dataset data = diagnose::build_dataset({diagnose::read_joint_log(path.string(), n)}, d);
  const diagnose::Diagnosis result = diagnose::diagnose(data, d);
  SCOPED_TRACE(diagnose::diagnosis_text(data, result));
  EXPECT_EQ(result.verdict.effect.substr(0, injected.effect.size()), injected.effect);
  if (result.selected.empty()) {
    ADD_FAILURE() << "nothing selected";
    return 0;
  }
  const auto& first = result.selected.front();
  EXPECT_EQ(first.joints, std::vector<int>{injected.joint + 1});
  for (const auto& p : first.parameters) {
    if (p.name == parameter) return p.value;
  }
  ADD_FAILURE() << parameter << " not fitted";
  return 0;
}

// The PUMA's shoulder read behind a spring: a stiffness of 600 N m/rad deflects it by up to 0.1 rad
// under the arm's weight. The residual is the model's change along the whole deflected trajectory
// (position, and the acceleration the swinging torque adds), not the positions' alone.
TEST(TransmissionEffect, ElasticShoulderOfThePumaIsNamedAndItsStiffnessFitted) {
  const Injection spring{.effect = "joint_elasticity", .joint = 1, .size = 600.0};
  EXPECT_NEAR(named_and_fitted("puma560", spring, "stiffness2", 200, 61), 600.0, 60.0);
}

// A dead band of 0.05 rad on the Panda's joint 3, whose torque turns over with the motion (a
// backlash on a joint whose torque keeps its sign is an offset, and the bench does not draw it).
TEST(TransmissionEffect, BacklashOfThePandaIsNamedAndItsWidthFitted) {
  const Injection band{.effect = "backlash", .joint = 2, .size = 0.05};
  EXPECT_NEAR(named_and_fitted("panda", band, "width3", 500, 62), 0.05, 0.005);
}

// A column of the analysis rows advanced in time (a sensor delay lags the other effects' torque as
// it lags the model's: settle.cpp) is the same signal later, within each log: checked on a sine of
// 0.7 Hz sampled at the analysis rows of two Kraft logs at different rates, against the sine at the
// later time, a lead of 13 ms either way. A row whose later time falls outside its log keeps its
// value. Cheap (two short effect-free logs), so the sanitizer run keeps it.
TEST(AdvancedInTime, AColumnIsTheSameSignalLaterWithinEachLog) {
  const pipeline::Derivation& d = arm("kraft");
  const auto n = static_cast<Eigen::Index>(d.robot.coordinates.size());
  std::vector<diagnose::JointLog> logs;
  for (const double rate : {200.0, 500.0}) {
    diagnose::SyntheticOptions options;
    options.rate = rate;
    options.duration = 12;
    const auto path = temp_path("advanced_" + std::to_string(static_cast<int>(rate)) + ".csv");
    diagnose::write_synthetic_log(d, {}, options, path);
    logs.push_back(diagnose::read_joint_log(path.string(), n));
  }
  const diagnose::Dataset data = diagnose::build_dataset(logs, d);
  const double omega = 2 * std::numbers::pi * 0.7;
  auto signal = [&](double t, Eigen::Index j) { return std::sin(omega * t + static_cast<double>(j)); };
  const Eigen::Index rows = data.rows();
  Eigen::VectorXd column(rows * n);
  for (Eigen::Index a = 0; a < rows; ++a) {
    for (Eigen::Index j = 0; j < n; ++j) column[a * n + j] = signal(data.analysis_t[a], j);
  }
  for (const double lead : {0.013, -0.013}) {
    const Eigen::VectorXd later = diagnose::advanced_in_time(data, column, lead);
    int inside = 0;
    for (Eigen::Index a = 0; a < rows; ++a) {
      const int log = data.analysis_log[static_cast<std::size_t>(a)];
      double first = 1e300, last = -1e300;
      for (Eigen::Index b = 0; b < rows; ++b) {
        if (data.analysis_log[static_cast<std::size_t>(b)] != log) continue;
        first = std::min(first, data.analysis_t[b]);
        last = std::max(last, data.analysis_t[b]);
      }
      const double t = data.analysis_t[a] + lead;
      const bool within = t >= first && t <= last;
      inside += within ? 1 : 0;
      for (Eigen::Index j = 0; j < n; ++j) {
        const double expected = within ? signal(t, j) : column[a * n + j];
        EXPECT_NEAR(later[a * n + j], expected, 2e-3) << "row " << a << " joint " << j << " lead " << lead;
      }
    }
    EXPECT_GT(inside, rows - 4);  // one row at an end of each log
  }
}

}  // namespace
}  // namespace dyncc::test
