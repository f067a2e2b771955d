// The torque a fitted friction effect adds on a joint as a function of the joint's velocity: the
// curve the report draws over the residual plotted against velocity.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "diagnose/residuals.hpp"

namespace dyncc::diagnose {

/// Whether the effect is a function of a joint's velocity alone (Coulomb, viscous, Stribeck).
bool has_velocity_curve(const std::string& effect);

/// The effect's torque on `joint` (0-based) at `velocity`, from its fitted values; the same
/// shapes as its columns in effects.cpp (the sign smoothed over kSignVelocity, Stribeck's excess
/// fading over the fitted scale). 0 for an effect without a velocity curve.
double velocity_curve(const EffectFit& fit, Eigen::Index joint, double velocity);

}  // namespace dyncc::diagnose
