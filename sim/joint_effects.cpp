#include "joint_effects.hpp"

#include <algorithm>
#include <cmath>

namespace dyncc::sim {
namespace {

double stiffness_of(const Transmission& t) { return t.stiffness > 0.0 ? t.stiffness : kBacklashStiffness; }

}  // namespace

double stribeck_excess(const JointEffects& e, int joint, double velocity) {
  const auto k = static_cast<std::size_t>(joint);
  if (e.stribeck[k] <= 0.0) return 0.0;
  const double v = velocity / e.stribeck_velocity[k];
  return e.stribeck[k] * std::exp(-v * v);
}

double transmission_torque(const Transmission& t, double rotor, double deflection, double rate) {
  const double k = stiffness_of(t);
  const double c = t.damping > 0.0 ? t.damping : 2.0 * kTransmissionDampingRatio * std::sqrt(k * rotor);
  if (t.width <= 0.0) return k * deflection + c * rate;  // a series spring: always engaged
  const double half = 0.5 * t.width;
  if (std::abs(deflection) <= half) return 0.0;  // in the dead band: motor and link are apart
  const double side = deflection > 0.0 ? 1.0 : -1.0;
  const double pushed = k * (std::abs(deflection) - half) + c * side * rate;
  return side * std::max(0.0, pushed);  // teeth push, they do not pull
}

double transmission_deflection(const Transmission& t, double torque) {
  if (torque == 0.0) return 0.0;
  const double side = torque > 0.0 ? 1.0 : -1.0;
  return side * (0.5 * t.width + std::abs(torque) / stiffness_of(t));
}

}  // namespace dyncc::sim
