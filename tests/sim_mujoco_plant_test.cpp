// The MuJoCo plant against dyncc's own model of the Kraft arm. Every expectation is an independent
// comparison: MuJoCo's gravity, payload, loop closure and contact force against the generated
// model, the D-H kinematics of sim/arm.cpp and the rigid (RK4) plant; no stored numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "plant.hpp"
#include "temp_path.hpp"

namespace dyncc::sim {
namespace {

namespace gen = dyncc::generated::kraft_right;

constexpr const char* kMjcf = DYNCC_KRAFT_MJCF;
constexpr double kGravity = 9.81;  // robots/kraft.yaml

// Configurations inside the exported joint limits (|q2|, |q3| <= 1.5), away from the stretched
// arm (q3 = q2) where the hook Jacobian is singular.
constexpr std::array<Joints, 4> kPoses{{{0.0, 0.0, 0.0}, {0.4, -0.5, 0.3}, {-1.1, 0.6, -0.2}, {2.0, 0.2, 1.0}}};

// No joint friction and no table: the smooth rigid-body dynamics both plants share.
PlantSettings smooth_settings() {
  PlantSettings s;
  s.table.present = false;
  s.joint_friction = false;
  return s;
}

Joints gravity(const Joints& q, const Payload& payload) {
  const Parameters p = true_parameters(payload);
  Joints g{};
  gen::gravity_torque<double>(q.data(), p.data(), g.data());
  return g;
}

double max_abs_difference(const Joints& a, const Joints& b) {
  double out = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) out = std::max(out, std::abs(a[i] - b[i]));
  return out;
}

double distance(const Vec3& a, const Vec3& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

Joints scaled(const Joints& a, double s) { return {s * a[0], s * a[1], s * a[2]}; }

// Largest |q(t) - q0| while held for `seconds` by the constant torque `tau`.
double hold_drift(Plant& plant, const Joints& q0, const Joints& tau, double seconds) {
  double drift = 0.0;
  for (int k = 0; k < static_cast<int>(std::lround(seconds / 0.01)); ++k) {
    plant.advance(tau, 0.01);
    drift = std::max(drift, max_abs_difference(plant.q(), q0));
  }
  return drift;
}

TEST(SimMujocoPlant, ResetPlacesEveryJointOnTheCouplingAndTheHookOnTheDhForearm) {
  const auto plant = make_mujoco_plant(smooth_settings(), kMjcf);
  EXPECT_EQ(plant->name(), "mujoco");
  for (const Joints& q : kPoses) {
    plant->reset(q);
    EXPECT_LT(max_abs_difference(plant->q(), q), 1e-12);
    EXPECT_EQ(max_abs_difference(plant->qd(), Joints{}), 0.0);
    EXPECT_FALSE(plant->payload_attached());
    // robots/kraft.yaml: the forearm's D-H angle is q3 - q2, the coupler's q2 - q3.
    EXPECT_NEAR(mujoco_joint_position(*plant, "forearm_joint"), q[2] - q[1], 1e-12);
    EXPECT_NEAR(mujoco_joint_position(*plant, "coupler_joint"), q[1] - q[2], 1e-12);
    // MuJoCo's kinematics of the exported bodies put the hook where sim/arm.cpp's D-H chain does:
    // the exported forearm body frame is the forearm's D-H frame.
    EXPECT_LT(distance(mujoco_hook_position(*plant), forearm_point(q, kHookInForearm)), 1e-12);
  }
  EXPECT_THROW((void)mujoco_joint_position(*plant, "no_such_joint"), std::invalid_argument);
  const auto rigid = make_rigid_plant(smooth_settings());
  EXPECT_THROW((void)mujoco_hook_position(*rigid), std::invalid_argument);
}

// (a) The generated gravity torque holds MuJoCo's arm still: both see the same masses. A torque
// error dtau drifts the arm by about dtau t^2 / (2 H) (H ~ 0.5 kg m^2 with the rotors), so the
// 1e-6 rad bound over 1 s stands for a gravity mismatch below ~1e-6 N m; the measured drift is a
// few 1e-9 rad (rounding and the soft loop's start). 1 % less torque must drift far beyond it.
TEST(SimMujocoPlant, GeneratedGravityTorqueHoldsTheArmStill) {
  const auto plant = make_mujoco_plant(smooth_settings(), kMjcf);
  for (const Joints& q0 : kPoses) {
    const Joints g = gravity(q0, {});
    plant->reset(q0);
    const double drift = hold_drift(*plant, q0, g, 1.0);
    EXPECT_LT(drift, 1e-6) << "q0 = " << q0[0] << ", " << q0[1] << ", " << q0[2];
    plant->reset(q0);
    const double weak = hold_drift(*plant, q0, scaled(g, 0.99), 1.0);
    if (std::abs(g[1]) + std::abs(g[2]) > 0.1) {
      EXPECT_GT(weak, 1e-3);
    }
  }
}

// The rigid plant and the MuJoCo plant driven by the same torque from the same state for 0.3 s:
// the largest difference of q over the run (sampled every 5 ms) and the largest joint speed.
struct Comparison {
  double difference = 0.0;
  double speed = 0.0;
};
Comparison compare_with_rigid(double rate, const Joints& q0, const Joints& pulse) {
  PlantSettings settings = smooth_settings();
  settings.rate = rate;
  const auto mujoco = make_mujoco_plant(settings, kMjcf);
  const auto rigid = make_rigid_plant(settings);
  mujoco->reset(q0);
  rigid->reset(q0);
  Comparison out;
  for (int k = 0; k < 60; ++k) {
    const Joints tau = k < 20 ? pulse : Joints{};  // 0.1 s of torque, then free motion
    mujoco->advance(tau, 0.005);
    rigid->advance(tau, 0.005);
    out.difference = std::max(out.difference, max_abs_difference(mujoco->q(), rigid->q()));
    out.speed = std::max(out.speed, max_abs_difference(rigid->qd(), Joints{}));
  }
  return out;
}

// (b) Free motion: MuJoCo's semi-implicit Euler and the rigid plant's RK4 integrate the same
// dynamics, so the difference is MuJoCo's integration error (RK4's is orders of magnitude smaller
// at these steps) plus the soft loop closure's, negligible at the stiffness the plant sets (test
// (c)). Semi-implicit Euler (q += h qd_new) runs ahead of the exact motion by h/2 (qd - qd0),
// which from rest is h/2 |qd|: 1.2e-4 rad without torque (0.48 rad/s) and 4.2e-4 rad with the
// torque pulse (1.8 rad/s) at 2 kHz. The bound is 1.5 times that estimate, and the difference
// must shrink with the step (first order: ratio 1/4 at four times the rate; 0.35 leaves room).
TEST(SimMujocoPlant, FreeMotionAgreesWithTheRigidPlant) {
  const Joints q0{0.3, -0.4, 0.5};
  for (const Joints& pulse : {Joints{}, Joints{8.0, -6.0, 6.0}}) {
    const Comparison at_2k = compare_with_rigid(2000.0, q0, pulse);
    const Comparison at_8k = compare_with_rigid(8000.0, q0, pulse);
    EXPECT_GT(at_2k.speed, 0.3);  // it really moves
    EXPECT_LT(at_2k.difference, 1.5 * 0.5 / 2000.0 * at_2k.speed);
    EXPECT_LT(at_8k.difference, 0.35 * at_2k.difference);
  }
}

// (c) The loop stays closed while the arm moves fast: the joints MuJoCo constrains softly follow
// the coupling of robots/kraft.yaml, and the hook stays where the D-H chain puts it. The plant's
// stiff equality setting keeps the violation near 1e-9; 1e-6 would still catch MuJoCo's default
// softness (~1e-3 rad of sag).
TEST(SimMujocoPlant, LoopStaysClosedDuringMotion) {
  const auto plant = make_mujoco_plant(smooth_settings(), kMjcf);
  plant->reset({0.3, -0.4, 0.5});
  double joint_error = 0.0, hook_error = 0.0, speed = 0.0;
  for (int k = 0; k < 60; ++k) {
    plant->advance(k < 20 ? Joints{8.0, -6.0, 6.0} : Joints{}, 0.005);
    const Joints q = plant->q();
    joint_error = std::max({joint_error, std::abs(mujoco_joint_position(*plant, "forearm_joint") - (q[2] - q[1])),
                            std::abs(mujoco_joint_position(*plant, "coupler_joint") - (q[1] - q[2]))});
    hook_error = std::max(hook_error, distance(mujoco_hook_position(*plant), forearm_point(q, kHookInForearm)));
    speed = std::max(speed, max_abs_difference(plant->qd(), Joints{}));
  }
  EXPECT_GT(speed, 1.0);  // the loop is really loaded: joints move at over 1 rad/s
  EXPECT_LT(joint_error, 1e-6);
  EXPECT_LT(hook_error, 1e-6);
}

// (d) The payload: its weight adds m g dz/dq to the gravity torque of dyncc's model (z of the
// payload point, from the D-H Jacobian), and that torque is what holds MuJoCo's arm with the
// payload attached; without the extra torque it sags, and detaching restores the unloaded hold.
TEST(SimMujocoPlant, PayloadAddsItsWeightTimesTheLeverArm) {
  PlantSettings settings = smooth_settings();
  settings.payload = {0.5, {0.40, 0.0, 0.0}, 0.03};
  const auto plant = make_mujoco_plant(settings, kMjcf);
  for (const Joints& q0 : kPoses) {
    const Joints unloaded = gravity(q0, {}), loaded = gravity(q0, settings.payload);
    const std::array<double, 9> j = forearm_point_jacobian(q0, settings.payload.position_in_forearm);
    for (int i = 0; i < kDof; ++i) {
      EXPECT_NEAR(loaded[i] - unloaded[i], settings.payload.mass * kGravity * j[6 + i], 1e-9) << "joint " << i + 1;
    }
    plant->reset(q0);
    plant->set_payload_attached(true);
    EXPECT_TRUE(plant->payload_attached());
    EXPECT_LT(hold_drift(*plant, q0, loaded, 1.0), 1e-6);
    plant->reset(q0);
    plant->set_payload_attached(true);
    if (std::abs(loaded[1] - unloaded[1]) + std::abs(loaded[2] - unloaded[2]) > 0.1) {
      EXPECT_GT(hold_drift(*plant, q0, unloaded, 1.0), 1e-3);  // the payload's weight is really there
    }
    plant->reset(q0);
    plant->set_payload_attached(true);
    plant->set_payload_attached(false);
    EXPECT_LT(hold_drift(*plant, q0, unloaded, 1.0), 1e-6);
  }
}

// Solves J^T f = r for f (J 3 x 3 row-major), by Cramer's rule.
Vec3 solve_transposed(const std::array<double, 9>& j, const Joints& r) {
  // A = J^T: A(i, k) = J(k, i).
  auto a = [&j](int i, int k) { return j[k * 3 + i]; };
  auto det = [](const std::array<double, 9>& m) {
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
  };
  std::array<double, 9> base{};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) base[i * 3 + k] = a(i, k);
  }
  const double d = det(base);
  Vec3 f{};
  for (int c = 0; c < 3; ++c) {
    std::array<double, 9> m = base;
    for (int i = 0; i < 3; ++i) m[i * 3 + c] = r[i];
    f[c] = det(m) / d;
  }
  return f;
}

// (e) The table: a torque that pushes the hook down with `push` newtons presses it on the table,
// and at rest the table's normal force is the one the torque implies, J^T f = g(q) - tau, with
// f = (0, 0, push) (the Jacobian is invertible here, so the equilibrium force is unique whatever
// friction does on the way). With the table 5 cm lower the same arm, held still, touches nothing.
TEST(SimMujocoPlant, TableForceIsWhatTheTorqueImplies) {
  const Joints q0{0.4, 0.3, 0.8};
  const Vec3 hook = forearm_point(q0, kHookInForearm);
  const std::array<double, 9> j = forearm_point_jacobian(q0, kHookInForearm);
  const Joints g = gravity(q0, {});
  for (const double push : {5.0, 20.0}) {
    PlantSettings settings = smooth_settings();
    settings.table.present = true;
    settings.table.height = hook[2];
    const auto plant = make_mujoco_plant(settings, kMjcf);
    plant->reset(q0);
    Joints tau{};
    for (int i = 0; i < kDof; ++i) tau[i] = g[i] - push * j[6 + i];
    plant->advance(tau, 0.5);
    const ContactState contact = plant->contact();
    EXPECT_TRUE(contact.active);
    EXPECT_NEAR(contact.normal_force, push, 0.01 * push);
    // The force implied at the configuration the arm settled in (it sinks micrometres in).
    const Joints q = plant->q();
    Joints residual{};
    const Joints gq = gravity(q, {});
    for (int i = 0; i < kDof; ++i) residual[i] = gq[i] - tau[i];
    const Vec3 implied = solve_transposed(forearm_point_jacobian(q, kHookInForearm), residual);
    EXPECT_NEAR(contact.normal_force, implied[2], 0.002 * push);
    EXPECT_LT(std::hypot(implied[0], implied[1]), 0.01 * push);
    EXPECT_LT(max_abs_difference(q, q0), 1e-3);
    EXPECT_LT(max_abs_difference(plant->qd(), Joints{}), 1e-4);
  }
  PlantSettings settings = smooth_settings();
  settings.table.present = true;
  settings.table.height = hook[2] - 0.05;
  const auto plant = make_mujoco_plant(settings, kMjcf);
  plant->reset(q0);
  EXPECT_FALSE(plant->contact().active);
  plant->advance(g, 0.2);
  EXPECT_FALSE(plant->contact().active);
  EXPECT_EQ(plant->contact().normal_force, 0.0);
}

// Joint friction (settings.joint_friction): MuJoCo's dry friction on the yaw joint, which gravity
// does not load, holds a torque below the Coulomb level FC1 of the description and lets through
// what exceeds it: at 2 FC1 the yaw turns half as far as without friction (the viscous part is
// 1 % of that at the speeds reached). Off, the same half torque turns it.
TEST(SimMujocoPlant, JointFrictionHoldsBelowTheCoulombTorque) {
  const double fc1 = Kraft::nominal_parameters[base_parameter_index("FC1")];
  const Joints q0{0.4, -0.5, 0.3};
  auto turn = [&](bool friction, double torque) {
    PlantSettings settings = smooth_settings();
    settings.joint_friction = friction;
    const auto plant = make_mujoco_plant(settings, kMjcf);
    plant->reset(q0);
    Joints tau = gravity(q0, {});
    tau[0] = torque;
    plant->advance(tau, 0.5);
    return plant->q()[0] - q0[0];
  };
  EXPECT_LT(std::abs(turn(true, 0.5 * fc1)), 1e-6);
  EXPECT_GT(turn(false, 0.5 * fc1), 1e-3);
  EXPECT_NEAR(turn(true, 2.0 * fc1) / turn(false, 2.0 * fc1), 0.5, 0.02);
}

// (f) What cannot be loaded is an exception with the reason, not a crash or a half-built plant.
TEST(SimMujocoPlant, UnloadableModelsThrow) {
  const PlantSettings settings;
  EXPECT_THROW((void)make_mujoco_plant(settings, "/nonexistent/kraft.xml"), std::runtime_error);
  const std::filesystem::path broken = dyncc::test::temp_path("broken.xml");
  std::ofstream(broken) << "<mujoco><worldbody><body name=\"forearm\"";  // not XML
  EXPECT_THROW((void)make_mujoco_plant(settings, broken.string()), std::runtime_error);
  const std::filesystem::path bad = dyncc::test::temp_path("bad.xml");
  std::ofstream(bad) << "<mujoco><worldbody><body name=\"forearm\"><joint type=\"nonsense\"/>"
                        "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/></body></worldbody></mujoco>";
  try {
    (void)make_mujoco_plant(settings, bad.string());
    ADD_FAILURE() << "a joint of type \"nonsense\" loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("MuJoCo cannot load"), std::string::npos) << e.what();
  }
  const std::filesystem::path no_forearm = dyncc::test::temp_path("no_forearm.xml");
  std::ofstream(no_forearm) << "<mujoco><worldbody/></mujoco>";
  EXPECT_THROW((void)make_mujoco_plant(settings, no_forearm.string()), std::runtime_error);
  std::filesystem::remove(broken);
  std::filesystem::remove(bad);
  std::filesystem::remove(no_forearm);
}

}  // namespace
}  // namespace dyncc::sim
