// Excitation logs for checking the sim-to-real diagnosis (`dyncc-sim excite`): the Kraft slave
// arm in closed loop on a plant (rigid or MuJoCo) that carries hidden effects, tracking either a
// Fourier excitation or the master arm's motion in the paper's tele-operation task, logged the way
// a real arm's controller would log it: the measured positions (through the sensors, so delayed,
// offset, noisy and quantised as the effects say) and the torque it COMMANDED, one row per control
// step. The controller is the runtime's Slotine-Li controller on the description's nominal model
// with adaptation off (a computed-torque controller with PD gains lambda^2, 2 lambda): it knows
// none of the effects, which live in the plant and in the interface between them.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "arm.hpp"
#include "effects_file.hpp"
#include "potentiometers.hpp"
#include "scenario.hpp"

namespace dyncc::sim {

enum class Trajectory { fourier, teleop };

struct ExciteSettings {
  PlantKind plant = PlantKind::dyncc;
  std::string mjcf;  // the exported MJCF, for the MuJoCo plant
  Trajectory trajectory = Trajectory::fourier;
  double rate = 200.0;                     // Hz, the control loop and the log (81..1000)
  double duration = 60.0;                  // s
  unsigned seed = 1;                       // the Fourier series, the sensor noise, the operator's run
  double quantum = kPotentiometerQuantum;  // rad (0: not quantised), a 12-bit potentiometer
  double noise = kPotentiometerNoise;      // rad, standard deviation
  HiddenEffects effects;
  double lambda = 5.0;  // rad/s, the controller's bandwidth
  // rad/s, the alpha-beta-gamma velocity estimate from the readings. Twice the tele-operation
  // runs' 25 rad/s: with backlash the motor alone (the Kraft's reflected rotor inertia is a tenth
  // of its links') sees the controller's gains ten times larger inside the dead band, and behind
  // a 25 rad/s estimate that loop chatters between the teeth; at 50 rad/s it does not (81..1000 Hz).
  double estimator_bandwidth = 50.0;
  Joints torque_limit{6.0, 12.0, 12.0};  // N m, actuator saturation of the command
  double plant_rate = 2000.0;            // Hz at least; raised to a whole multiple of `rate` so steps meet the periods
  double excitation_scale = 1.0;         // the Fourier series' reach (FourierExcitation)
};

struct ExciteSample {
  double t = 0;
  Joints measured{};  // the logged positions
  Joints tau{};       // the commanded torque (logged), after saturation
  Joints desired{};   // the reference at t
  Joints link{};      // the true link angles
  Joints sensor{};    // the true sensor-side angles (motor side behind a non-rigid transmission)
  // The table over the period that follows t (the one the torque is held over): touched at some
  // integration step, and the normal force's mean over the steps (MuJoCo's hard contact may touch
  // at one step of several while the hook slides on the table).
  bool contact = false;
  double contact_force = 0;  // N
  bool payload = false;      // the payload on the hook
};

struct ExciteRun {
  ExciteSettings settings;
  double table_height = 0;  // m, the table's when the contact effect is on
  double low_hook = 0;      // m, how low the reference's hook goes (ExciteReference::low_hook)
  std::vector<ExciteSample> samples;
};

/// Runs the arm; `progress` (if set) is called with the fraction done. Throws
/// std::invalid_argument for settings out of range or effects the plant cannot play.
ExciteRun excite(const ExciteSettings& settings, const std::function<void(double)>& progress = {});

/// The log: t,q1,q2,q3,tau1,tau2,tau3 (the format `dyncc diagnose` reads).
void write_excite_log(const ExciteRun& run, const std::filesystem::path& path);

/// A few lines for the terminal: rows and rate, effects, tracking and torque RMS per joint, contact.
std::string excite_summary(const ExciteRun& run);

}  // namespace dyncc::sim
