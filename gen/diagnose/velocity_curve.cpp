#include "diagnose/velocity_curve.hpp"

namespace dyncc::diagnose {

bool has_velocity_curve(const std::string& effect) {
  return effect == "coulomb_friction" || effect == "viscous_friction" || effect == "stribeck_friction";
}

double velocity_curve(const EffectFit& fit, Eigen::Index joint, double velocity) {
  if (!has_velocity_curve(fit.effect)) return 0;
  const double sign =
      joint < fit.sign_velocity.size() ? smooth_sign(velocity, fit.sign_velocity[joint]) : smooth_sign(velocity);
  double torque = 0;
  for (std::size_t k = 0; k < fit.parameters.size(); ++k) {
    if (fit.joint_of[k] != joint) continue;
    // The column's kind is the parameter's prefix: fc (Coulomb), fv (viscous), fs (static excess).
    const std::string kind = fit.parameters[k].substr(0, 2);
    const double value = fit.values[static_cast<Eigen::Index>(k)];
    if (kind == "fc") torque += value * sign;
    if (kind == "fv") torque += value * velocity;
    if (kind == "fs" && fit.profile > 0) torque += value * stribeck_fade(velocity, fit.profile) * sign;
  }
  return torque;
}

}  // namespace dyncc::diagnose
