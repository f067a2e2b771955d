// One tele-operation run: the operator moves the master through the task script, the slave tracks
// the master's measured angles with the runtime's Slotine-Li controller at 81 Hz (zero-order hold),
// the true slave arm is a plant (rigid or MuJoCo) that picks up and puts down the payload and
// pushes on the table. Everything the figures and the summary need is logged once per control
// period.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "arm.hpp"
#include "potentiometers.hpp"

namespace dyncc::sim {

enum class PlantKind { dyncc, mujoco };

struct ScenarioSettings {
  std::string name = "paper-0.5kg";
  double payload = 0.5;            // kg, hung on the hook at the pick-up
  bool adaptation = true;          // adaptation law on (the paper's "adaptive") or off ("fixed")
  bool simplified = false;         // controller without velocity terms (Fig. 8)
  bool freeze_in_contact = false;  // adaptation off while the hook touches the table
  PlantKind plant = PlantKind::dyncc;
  std::string mjcf;                        // the exported MJCF, for the MuJoCo plant
  std::string master_csv;                  // replay this master trajectory instead of the operator model
  double control_rate = 81.0;              // Hz, the paper's loop
  double plant_rate = 2000.0;              // Hz, integration
  double quantum = kPotentiometerQuantum;  // rad: a 12-bit potentiometer over a turn
  double noise = kPotentiometerNoise;      // rad, standard deviation of the potentiometer noise
  unsigned seed = 1;
  Joints torque_limit{6.0, 12.0, 12.0};  // N m, actuator saturation
  double estimator_bandwidth = 25.0;     // rad/s, alpha-beta-gamma filters on the potentiometers
  double duration = 0.0;                 // s; 0 = the whole task
};

/// The named scenarios of `dyncc simulate --scenario`.
std::vector<std::string> scenario_names();
/// Settings of a named scenario; throws std::invalid_argument listing the names for others.
ScenarioSettings scenario_settings(const std::string& name);

struct Sample {
  double t = 0;
  Joints master{}, slave{};  // true angles (rad)
  Joints s{};                // tracking error s = q~' + lambda q~ (the controller's eps)
  Joints tau{};              // commanded slave torque after saturation (N m)
  Parameters estimate{};     // p^
  bool contact = false;
  double contact_force = 0;  // N
  bool payload = false;      // payload on the hook
  bool adapting = false;     // adaptation switched on this period
};

struct Run {
  ScenarioSettings settings;
  std::vector<Sample> samples;                 // one per control period
  double attach_time = -1, release_time = -1;  // s; -1 = never
};

/// Runs the scenario. `progress` (if set) is called with the fraction done.
Run simulate(const ScenarioSettings& settings, const std::function<void(double)>& progress = {});

/// The log as CSV: t, master_q*, slave_q*, s*, tau*, one column per base parameter, contact,
/// contact_force, payload, adapting.
void write_csv(const Run& run, const std::filesystem::path& path);

}  // namespace dyncc::sim
