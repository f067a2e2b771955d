// What the joint sensors of an excitation log report: the sensor-side angles (the link's, or the
// motor's behind a non-rigid transmission) as they were `delay` seconds ago, plus a constant
// offset, read by the potentiometers (noise, quantisation). The plant's angles are recorded at
// every integration step, so a delay needs not be a whole number of control periods: the reading
// is interpolated between the two recorded steps around t - delay (linear: at >= 2 kHz the error
// is below 1e-6 rad, far under the quantum).
#pragma once

#include <deque>

#include "arm.hpp"
#include "potentiometers.hpp"

namespace dyncc::sim {

class JointSensors {
 public:
  JointSensors(double delay, const Joints& offset, Potentiometers potentiometers)
      : delay_(delay), offset_(offset), potentiometers_(potentiometers) {}

  /// The sensor-side angles at time t (times must increase); before the first record the arm is
  /// taken to have rested where it started.
  void record(double t, const Joints& sensor_q);

  /// The true angles the sensors see at t (delayed and offset, before noise and quantisation).
  [[nodiscard]] Joints seen(double t) const;

  /// The reading at t: seen(t) through the potentiometers. Forgets records older than needed.
  Joints read(double t);

 private:
  struct Record {
    double t;
    Joints q;
  };
  double delay_;
  Joints offset_;
  Potentiometers potentiometers_;
  std::deque<Record> history_;
};

}  // namespace dyncc::sim
