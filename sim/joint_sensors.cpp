#include "joint_sensors.hpp"

#include <stdexcept>

namespace dyncc::sim {

void JointSensors::record(double t, const Joints& sensor_q) {
  if (!history_.empty() && !(t > history_.back().t)) throw std::logic_error("joint sensors: times must increase");
  history_.push_back({t, sensor_q});
}

Joints JointSensors::seen(double t) const {
  if (history_.empty()) throw std::logic_error("joint sensors: nothing recorded yet");
  const double at = t - delay_;
  Joints q = history_.front().q;
  if (at >= history_.back().t) {
    q = history_.back().q;
  } else if (at > history_.front().t) {
    std::size_t i = history_.size() - 1;
    while (history_[i - 1].t > at) --i;  // [i-1, i] brackets `at`; short walk: read() forgets the old
    const Record &a = history_[i - 1], &b = history_[i];
    const double u = (at - a.t) / (b.t - a.t);
    for (int k = 0; k < kDof; ++k) q[k] = a.q[k] + u * (b.q[k] - a.q[k]);
  }
  for (int k = 0; k < kDof; ++k) q[k] += offset_[k];
  return q;
}

Joints JointSensors::read(double t) {
  const Joints q = seen(t);
  // Keep one record at or before t - delay: later readings are later still.
  while (history_.size() > 2 && history_[1].t <= t - delay_) history_.pop_front();
  return potentiometers_.read(q);
}

}  // namespace dyncc::sim
