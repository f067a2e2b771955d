// Effects hidden inside the arm's joints, which the controller's model (the description's nominal
// parameters) does not know: friction beyond the description's, reflected inertia beyond its
// rotor inertias, and a transmission between motor and link that is not rigid (backlash, a series
// spring). The plants add them to the true arm; `dyncc-sim excite` logs the arm with them so the
// diagnosis can be checked on logs whose cause is known. All zero: the description's arm.
#pragma once

#include "arm.hpp"

namespace dyncc::sim {

/// A transmission between the motor and the link of one joint. width = 0 and stiffness = 0: rigid
/// (the motor and the link are one body). Otherwise the motor is its own body carrying the joint's
/// reflected rotor inertia, and the coupling torque is stiffness * (the deflection beyond the dead
/// band of half-width width/2) plus damping * the deflection rate while engaged.
struct Transmission {
  double width = 0.0;      // rad, dead band (backlash) between motor and link
  double stiffness = 0.0;  // N m/rad, 0 with a dead band: kBacklashStiffness
  double damping = 0.0;    // N m s/rad while engaged; 0: kTransmissionDampingRatio of critical
  [[nodiscard]] bool rigid() const { return width <= 0.0 && stiffness <= 0.0; }
};

/// Gear-tooth contact once the backlash is taken up: stiff enough that the deflection under the
/// Kraft's largest torques (12 N m) stays near 1 mrad, so the dead band dominates; soft enough that
/// the motor-on-link mode (sqrt(k / jm) <= 500 rad/s) stays resolved by RK4 at 2 kHz.
inline constexpr double kBacklashStiffness = 1.0e4;
/// Default damping of a transmission: this fraction of the critical damping of the motor inertia on
/// the spring, the few per cent of structural damping that keep its mode from ringing for ever.
inline constexpr double kTransmissionDampingRatio = 0.1;

struct JointEffects {
  Joints coulomb{};                         // N m, extra Coulomb friction (a regularised sign on the rigid plant)
  Joints viscous{};                         // N m s/rad, extra viscous friction
  Joints stribeck{};                        // N m, extra static friction fs exp(-(qd/vs)^2) sign(qd)
  Joints stribeck_velocity{0.1, 0.1, 0.1};  // rad/s, vs
  Joints rotor_inertia{};                   // kg m^2, extra reflected inertia on the diagonal
  std::array<Transmission, kDof> transmission{};

  [[nodiscard]] bool all_rigid() const {
    for (const Transmission& t : transmission) {
      if (!t.rigid()) return false;
    }
    return true;
  }
};

/// The Stribeck excess fs exp(-(v/vs)^2) without its sign (N m, >= 0).
double stribeck_excess(const JointEffects& e, int joint, double velocity);

/// The torque the transmission of a non-rigid joint passes from motor to link, for the deflection
/// motor - link (rad) and its rate; `rotor` is the motor-side inertia (for the default damping).
/// With a dead band: zero inside it, and the teeth push but never pull (a unilateral contact on
/// each side); without one, a spring-damper.
double transmission_torque(const Transmission& t, double rotor, double deflection, double rate);

/// The deflection motor - link at which the transmission passes `torque` at rest (the inverse of
/// transmission_torque at zero rate; the middle of the dead band for zero torque).
double transmission_deflection(const Transmission& t, double torque);

}  // namespace dyncc::sim
