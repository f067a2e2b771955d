// The hidden effects of an excitation log (`dyncc-sim excite --effects FILE.json`), read from
// JSON. The file names each effect, the joints it acts on (numbered from 1) and its parameters;
// sim/README.md documents every effect and parameter. Any mistake in the file (malformed JSON, an
// unknown effect, field or parameter, a wrong joint, a missing or out-of-range value) is refused
// with a message naming the file and the field: a misspelt name must not quietly mean "no effect".
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "arm.hpp"
#include "joint_effects.hpp"
#include "scenario.hpp"

namespace dyncc::sim {

/// The hook touching a horizontal table (sim/plant.hpp's Table); unset values keep the plant's.
struct ContactEffect {
  bool present = false;
  std::optional<double> height;              // m, base frame
  std::optional<double> depth;               // m, or: how far below it the reference's lowest hook point reaches
  double friction = 0.6;                     // Coulomb coefficient, tangential
  std::optional<double> stiffness, damping;  // N/m, N s/m (the rigid plant's penalty contact)
};

struct HiddenEffects {
  JointEffects joints;                     // in the plant's joints
  double payload = 0.0;                    // kg hung on the hook
  Vec3 payload_position = kHookInForearm;  // m, forearm D-H frame
  ContactEffect contact;
  Joints torque_gain{1.0, 1.0, 1.0};  // applied = gain * commanded
  double sensor_delay = 0.0;          // s, the measured positions are those of this long ago
  Joints position_offset{};           // rad, measured = true + offset

  struct Listed {
    std::string effect;
    std::size_t index = 0;  // its place in the file's "effects" array
  };
  std::vector<Listed> listed;  // what the file names, in its order
  [[nodiscard]] bool has(const std::string& effect) const;
};

/// Every effect a file may name.
std::vector<std::string> effect_names();

/// Reads an effects file; throws std::invalid_argument("FILE: field: what is wrong").
HiddenEffects read_effects(const std::filesystem::path& path);

/// Throws std::invalid_argument naming the file and the effect when the plant cannot play one
/// (backlash and joint elasticity need a motor body apart from the link: the rigid plant only;
/// MuJoCo's soft contact has no stiffness or damping to set).
void require_playable(const HiddenEffects& effects, PlantKind plant, const std::string& file);

}  // namespace dyncc::sim
