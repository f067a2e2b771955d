// What plays the real arm: a plant takes a torque held constant over a control period (zero-order
// hold) and integrates the arm at its own, finer rate. Two implementations with the same
// interface: the generated model with the true parameters and RK4 (rigid_plant.cpp), and MuJoCo
// on the MJCF that `dyncc export` writes, with its own contact and friction models
// (mujoco_plant.cpp). The scenario code (scenario.cpp) sees only this interface.
#pragma once

#include <memory>
#include <string>

#include "arm.hpp"
#include "joint_effects.hpp"

namespace dyncc::sim {

/// A horizontal surface the hook point pushes on. `height` is the z (base frame) at which the
/// hook point touches it: the payload's top before the pick-up, and (the payload hanging the
/// same distance below the hook) the table under the payload's bottom after it.
struct Table {
  bool present = true;
  double height = -0.34;     // m, base frame: the payload's top under the task's press pose
  double stiffness = 2.0e4;  // N/m (the rigid plant's unilateral spring)
  double damping = 400.0;    // N s/m: near critical for the few kg the hook carries
  double friction = 0.6;     // Coulomb coefficient, tangential
};

struct PlantSettings {
  Payload payload;  // its mass is carried only while attached
  Table table;
  double rate = 2000.0;        // integration steps per second (>= 1 kHz)
  bool joint_friction = true;  // Coulomb and viscous joint friction of the description
  JointEffects effects;        // hidden effects in the joints beyond the description (none by default)
};

struct ContactState {
  bool active = false;
  double normal_force = 0.0;  // N, >= 0
};

class Plant {
 public:
  virtual ~Plant() = default;
  /// At rest at q, payload detached (a non-rigid transmission: its motor where it holds the link
  /// at q against gravity).
  virtual void reset(const Joints& q) = 0;
  /// Advances by `duration` seconds with the joint torque `tau` held constant.
  virtual void advance(const Joints& tau, double duration) = 0;
  /// Hangs the payload on the hook (true) or takes it off (false).
  virtual void set_payload_attached(bool attached) = 0;
  [[nodiscard]] virtual Joints q() const = 0;  // the links' angles
  [[nodiscard]] virtual Joints qd() const = 0;
  /// Where the joint sensors sit: the motor side of a joint whose transmission is not rigid (the
  /// deflection of the transmission is then between sensor and link), the link otherwise.
  [[nodiscard]] virtual Joints sensor_q() const { return q(); }
  [[nodiscard]] virtual ContactState contact() const = 0;
  [[nodiscard]] virtual bool payload_attached() const = 0;
  [[nodiscard]] virtual std::string name() const = 0;
};

/// The generated Kraft model with the true (nominal) parameters, payload merged by dyncc's
/// base-parameter map, table contact as a penalty force through the hook Jacobian, RK4. Every
/// joint effect is supported; a joint with a non-rigid transmission gets a motor body (two more
/// states) carrying its reflected rotor inertia.
std::unique_ptr<Plant> make_rigid_plant(const PlantSettings& settings);

/// MuJoCo on the exported MJCF (`dyncc export robots/kraft.yaml --format mjcf`), with a hook
/// geom, a payload body and a table added; throws std::runtime_error if it does not load. Joint
/// effects: extra friction as frictionloss (Stribeck: a frictionloss that follows the speed),
/// damping and armature; its joints are rigid, so a non-rigid transmission throws
/// std::invalid_argument.
std::unique_ptr<Plant> make_mujoco_plant(const PlantSettings& settings, const std::string& mjcf_path);

/// MuJoCo's own kinematics of a MuJoCo plant, for tests of its loop closure and frames: the value
/// of the MJCF joint `joint` (rad or m, 0 at q = 0) and the hook point (m, base frame, the hook
/// geom's centre). Throw std::invalid_argument for another plant or an unknown joint.
double mujoco_joint_position(const Plant& plant, const std::string& joint);
Vec3 mujoco_hook_position(const Plant& plant);

}  // namespace dyncc::sim
