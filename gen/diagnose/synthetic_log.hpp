// Synthetic logs with hidden effects, for checking the diagnosis blind (`dyncc sim2real-bench`
// and the tests): an exciting trajectory (a Fourier series per joint, exact rates), the torque of
// the description's model with the effects injected, positions quantised and torques noisy,
// written as the CSV `dyncc diagnose` reads. The truth stays with the caller.
#pragma once

#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/derivation.hpp"

namespace dyncc::diagnose {

struct Injection {
  std::string effect = "none";  // coulomb_friction, viscous_friction, stribeck_friction, payload, torque_gain,
                                // sensor_delay, position_offset, rotor_inertia, contact,
                                // joint_elasticity, backlash
  int joint = 0;                // 0-based, for per-joint effects
  double size = 0;  // fc / excess (N m), fv (N m s), mass (kg), gain, delay (s), offset (rad), inertia (kg m^2),
                    // peak contact force (N), stiffness (N m/rad), backlash width (rad)
};

struct SyntheticOptions {
  double rate = 200;           // Hz
  double duration = 40;        // s
  double quantum = 2e-4;       // rad
  double torque_noise = 0.01;  // N m
  double amplitude = 1.0;      // scale of the excitation
  unsigned seed = 1;
  // A payload is carried from payload_on to payload_off (s; the whole log by default): picked up
  // and put down during the log.
  double payload_on = 0;
  double payload_off = 1e300;
};

/// The effects the generator can inject.
std::vector<std::string> injectable_effects();

/// Whether an effect acts on one joint (friction, gain, offset, rotor) or on the arm (payload, delay,
/// contact).
bool acts_on_one_joint(const std::string& effect);

/// Per-joint RMS of the torque the effects add (or, for gain/delay/offset, change), and of the
/// clean model torque, over the trajectory (no noise, no quantisation), through the diagnosis'
/// low-pass: as the diagnosis sees them.
struct EffectSize {
  Eigen::VectorXd clean_rms, effect_rms;
  Eigen::VectorXd reversing;  // per joint, the share of the time the torque its transmission carries has its
                              // less common sign
};

EffectSize effect_size(const pipeline::Derivation& d, const std::vector<Injection>& effects, const SyntheticOptions& o);

/// Writes the log; throws std::runtime_error when it cannot.
void write_synthetic_log(const pipeline::Derivation& d, const std::vector<Injection>& effects,
                         const SyntheticOptions& o, const std::filesystem::path& path);

}  // namespace dyncc::diagnose
