// The human side of the tele-operation: the paper's task script (section 4: reach the payload on
// the table, press on it, lift it, sweep joints 1, 2 and 3 back and forth, put it back) as a
// smooth desired trajectory for the operator's hand, and a recorded master trajectory (CSV) that
// can replace the simulated master.
#pragma once

#include <string>
#include <vector>

#include "arm.hpp"

namespace dyncc::sim {

struct TrajectoryPoint {
  Joints q{}, qd{}, qdd{};
};

/// The task as timed segments; every segment starts and ends at rest (minimum-jerk moves,
/// sin^3 sweeps), so the hand's trajectory is twice continuously differentiable.
class TaskScript {
 public:
  struct Segment {
    double start = 0, end = 0;
    Joints from{}, to{};
    int sweep_joint = -1;  // >= 0: back and forth about `from` on this joint (to unused)
    double amplitude = 0, period = 1;
  };

  /// The paper's task (Fig. 5's timeline: contact at ~7 s, lift 17-20 s, sweeps of joints 1, 2,
  /// 3 from 23, 35 and 45 s, put-down at ~57 s).
  static TaskScript paper();

  [[nodiscard]] TrajectoryPoint at(double t) const;
  [[nodiscard]] double duration() const { return segments_.empty() ? 0.0 : segments_.back().end; }
  [[nodiscard]] const std::vector<Segment>& segments() const { return segments_; }

  // Milestones the scenario uses (s).
  double pick_up = 17.0;       // the hook takes the payload as the lift starts
  double lift_end = 20.0;      // the operator's lift is over (the payload is clear in the paper)
  double put_down = 57.0;      // the operator starts lowering it onto the table
  double release_after = 0.5;  // payload left on the table once it has rested this long

 private:
  std::vector<Segment> segments_;
};

/// A master trajectory recorded as CSV: a header with `t` and `q1`..`q3` (or `master_q1`..),
/// other columns ignored. Velocity and acceleration by central differences of the samples.
class RecordedMaster {
 public:
  /// Throws std::runtime_error naming the file, line and column for malformed input.
  static RecordedMaster load(const std::string& path);
  [[nodiscard]] TrajectoryPoint at(double t) const;  // linear interpolation, clamped at the ends
  [[nodiscard]] double duration() const { return t_.empty() ? 0.0 : t_.back(); }

 private:
  std::vector<double> t_;
  std::vector<Joints> q_;
};

}  // namespace dyncc::sim
