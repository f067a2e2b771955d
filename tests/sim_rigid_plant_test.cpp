// The rigid plant of the simulation (sim/rigid_plant.cpp) and the arm geometry it uses
// (sim/arm.cpp), against closed forms: the hook's position from the paper's Fig. 1 geometry, the
// Jacobian by finite differences, the payload's change of the base parameters from its first
// moments, the power balance of free motion, and the statics of pressing on the table.
#include <gtest/gtest.h>

#include <cmath>

#include "arm.hpp"
#include "plant.hpp"

namespace dyncc::sim {
namespace {

namespace gen = dyncc::generated::kraft_right;
constexpr double kL2 = 0.180, kB2 = 0.130, kHook = 0.40;

// Fig. 1: the upper arm (length l2) at elevation q2 and the forearm at absolute elevation q3 lie
// in a vertical plane offset b2 sideways from the yaw axis; positive elevations pitch down.
Vec3 hook_closed_form(const Joints& q) {
  const double reach = kL2 * std::cos(q[1]) + kHook * std::cos(q[2]);
  const double height = -kL2 * std::sin(q[1]) - kHook * std::sin(q[2]);
  return {std::cos(q[0]) * reach - std::sin(q[0]) * kB2, std::sin(q[0]) * reach + std::cos(q[0]) * kB2, height};
}

const Joints kStates[] = {{0.0, 0.0, 0.0}, {0.3, -0.35, 0.5}, {-1.2, 0.7, -0.4}, {2.0, 1.1, 1.3}};

TEST(KraftArm, HookPositionMatchesThePapersGeometry) {
  for (const Joints& q : kStates) {
    const Vec3 p = forearm_point(q, kHookInForearm), expected = hook_closed_form(q);
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(p[r], expected[r], 1e-12) << "q = " << q[0] << "," << q[1] << "," << q[2];
  }
}

TEST(KraftArm, JacobianMatchesFiniteDifferences) {
  const Vec3 point{0.25, -0.03, 0.07};
  for (const Joints& q : kStates) {
    const auto j = forearm_point_jacobian(q, point);
    for (int c = 0; c < kDof; ++c) {
      Joints plus = q, minus = q;
      plus[c] += 1e-6;
      minus[c] -= 1e-6;
      const Vec3 a = forearm_point(plus, point), b = forearm_point(minus, point);
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(j[r * 3 + c], (a[r] - b[r]) / 2e-6, 1e-8);
    }
  }
}

// A point mass m at (x, y, z) in the forearm frame adds m times its position to the forearm's
// first moments: m x to MX3R, m y to MY3, m (z + b2 - b1) to MZ3R (the frame's offset
// d3 = b2 - b1 along z), and m l2 to MX2R (the elbow's distance from the shoulder).
TEST(KraftArm, PayloadChangesTheFirstMomentsByItsOwn) {
  const Payload payload{0.7, {0.40, 0.02, -0.01}, 0.0};
  const Parameters before = true_parameters({}), after = true_parameters(payload);
  const double m = payload.mass;
  const Vec3& r = payload.position_in_forearm;
  EXPECT_NEAR(after[base_parameter_index("MX3R")] - before[base_parameter_index("MX3R")], m * r[0], 1e-12);
  EXPECT_NEAR(after[base_parameter_index("MY3")] - before[base_parameter_index("MY3")], m * r[1], 1e-12);
  EXPECT_NEAR(after[base_parameter_index("MZ3R")] - before[base_parameter_index("MZ3R")], m * (r[2] + 0.055), 1e-12);
  EXPECT_NEAR(after[base_parameter_index("MX2R")] - before[base_parameter_index("MX2R")], m * kL2, 1e-12);
  for (const char* friction : {"FC1", "FV1", "FC2", "FV2", "FC3", "FV3"}) {
    EXPECT_EQ(after[base_parameter_index(friction)], before[base_parameter_index(friction)]);
  }
  // The gravity torque of the loaded arm grows by the payload's weight times its lever arms,
  // J_z^T (-m g): the closed form of a point mass.
  const Joints q{0.2, -0.3, 0.6};
  Joints g0{}, g1{};
  gen::gravity_torque<double>(q.data(), before.data(), g0.data());
  gen::gravity_torque<double>(q.data(), after.data(), g1.data());
  const auto j = forearm_point_jacobian(q, r);
  for (int k = 0; k < kDof; ++k) EXPECT_NEAR(g1[k] - g0[k], j[6 + k] * m * 9.81, 1e-9) << "joint " << k + 1;
}

// Free motion without friction: the kinetic energy changes only by the work of gravity,
// T(t) - T(0) = -integral qd^T g dt (Christoffel C: qd^T (Hdot/2 - C) qd = 0).
TEST(RigidPlant, FreeMotionConservesEnergy) {
  PlantSettings s;
  s.table.present = false;
  s.joint_friction = false;
  s.rate = 4000;
  auto plant = make_rigid_plant(s);
  plant->reset({0.1, -0.4, 0.3});
  plant->set_payload_attached(true);
  const Parameters p = true_parameters(s.payload);
  auto kinetic = [&p](const Joints& q, const Joints& qd) {
    std::array<double, kDof * kDof> h{};
    gen::mass_matrix<double>(q.data(), p.data(), h.data());
    double t = 0;
    for (int i = 0; i < kDof; ++i) {
      for (int k = 0; k < kDof; ++k) t += 0.5 * qd[i] * h[i * kDof + k] * qd[k];
    }
    return t;
  };
  auto power_of_gravity = [&p](const Joints& q, const Joints& qd) {
    Joints g{};
    gen::gravity_torque<double>(q.data(), p.data(), g.data());
    return qd[0] * g[0] + qd[1] * g[1] + qd[2] * g[2];
  };
  const Joints tau{0.4, 0.0, 0.0};  // a yaw torque too, whose work is tau^T (q - q0)
  const Joints q0 = plant->q();
  double work = 0, previous = 0;
  const double dt = 1e-3;
  for (int i = 0; i < 1500; ++i) {
    plant->advance(tau, dt);
    const double now = power_of_gravity(plant->q(), plant->qd());
    work += 0.5 * (previous + now) * dt;  // trapezoid on a smooth integrand
    previous = now;
  }
  const Joints q = plant->q();
  const double applied = tau[0] * (q[0] - q0[0]);
  const double t = kinetic(q, plant->qd());
  EXPECT_GT(t, 0.1) << "the arm must actually move";
  EXPECT_NEAR(t, applied - work, 1e-3 * t);
}

// Pressing the hook down on the table with a force F on top of the weight: at rest the table
// carries exactly F (the statics J^T F = tau - g), at a depth F / stiffness.
TEST(RigidPlant, PressingOnTheTableIsBalancedByTheContactForce) {
  const Joints q0{0.3, 0.0, 1.0};
  PlantSettings s;
  s.table.height = forearm_point(q0, kHookInForearm)[2];
  auto plant = make_rigid_plant(s);
  plant->reset(q0);
  EXPECT_FALSE(plant->contact().active);
  const Parameters p = true_parameters({});
  Joints g{};
  gen::gravity_torque<double>(q0.data(), p.data(), g.data());
  const double push = 8.0;  // N, downwards
  const auto j = forearm_point_jacobian(q0, kHookInForearm);
  Joints tau{};
  for (int k = 0; k < kDof; ++k) tau[k] = g[k] - j[6 + k] * push;
  plant->advance(tau, 3.0);
  ASSERT_TRUE(plant->contact().active);
  EXPECT_NEAR(plant->contact().normal_force, push, 0.02 * push);
  const double depth = s.table.height - forearm_point(plant->q(), kHookInForearm)[2];
  EXPECT_NEAR(depth, push / s.table.stiffness, 0.05 * push / s.table.stiffness);
  // Lifting off: the weight alone, hook above the table -> no contact.
  plant->reset({0.3, -0.3, 0.5});
  plant->advance(g, 0.1);
  EXPECT_FALSE(plant->contact().active);
}

}  // namespace
}  // namespace dyncc::sim
