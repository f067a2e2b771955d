// The planar two-link arm against the textbook closed form (Spong, Hutchinson & Vidyasagar,
// "Robot Modeling and Control", sec. 7.4.1 / 6.4), at random states and random parameters.
//
// robots/planar_2link.yaml uses standard D-H with frame i at the FAR end of link i, so the
// centre of mass written as com x = c_i (negative) lies lc_i = l_i + c_i from joint i. With
// I_i the inertia about the centre of mass about the joint axes (z), and motor 1's reflected
// inertia Jr = G^2 Jm on joint 1:
//   H11 = m1 lc1^2 + m2 (l1^2 + lc2^2 + 2 l1 lc2 c2) + I1 + I2 + Jr
//   H12 = H21 = m2 (lc2^2 + l1 lc2 c2) + I2,       H22 = m2 lc2^2 + I2
//   h = -m2 l1 lc2 s2,   C = [[h qd2, h (qd1 + qd2)], [-h qd1, 0]]
//   g1 = (m1 lc1 + m2 l1) g c1 + m2 lc2 g c12,     g2 = m2 lc2 g c12      (g = 9.81, y up)
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dynamics_support.hpp"

namespace dyncc::test {
namespace {

TEST(DynamicsPlanar, TwoLinkArmEqualsTextbookClosedForm) {
  const auto d = derive_file(robots_dir() / "planar_2link.yaml");
  ASSERT_TRUE(d);
  const robot::RobotDescription& robot = d->robot;
  ASSERT_EQ(robot.coordinates.size(), 2U);
  // The file's setting, which the closed form assumes: gravity -9.81 along y, both joints about z.
  const auto gravity = robot.gravity_values();
  ASSERT_EQ(gravity[0], 0.0);
  ASSERT_EQ(gravity[2], 0.0);
  const double g = -gravity[1];
  const double l1 = robot.constant_doubles().at("l1");
  const double l2 = robot.constant_doubles().at("l2");
  double rotor = 0.0;
  for (const auto& r : robot.rotors) {
    ASSERT_EQ(r.coordinate, 0) << "the closed form has a motor on joint 1 only";
    ASSERT_TRUE(r.inertia.is_number());
    rotor = r.gear_ratio.to_double() * r.gear_ratio.to_double() * r.inertia.value().to_double();
  }

  std::mt19937_64 rng(314);
  std::uniform_real_distribution<double> mass(0.2, 5.0), offset(-1.0, 0.2), inertia(0.001, 0.5);
  double worst = 0.0;
  for (int k = 0; k < 40; ++k) {
    std::map<std::string, double> p = robot.nominal_values();
    p["m1"] = mass(rng);
    p["m2"] = mass(rng);
    p["c1"] = offset(rng);
    p["c2"] = offset(rng);
    p["i1zz"] = inertia(rng);
    p["i2zz"] = inertia(rng);
    const double m1 = p["m1"], m2 = p["m2"], lc1 = l1 + p["c1"], lc2 = l2 + p["c2"], I1 = p["i1zz"], I2 = p["i2zz"];

    const dyn::State s = random_state(2, rng);
    const dyn::Evaluation e = d->numeric->evaluate(s, d->numeric->standard_values(p));
    const double c2 = std::cos(s.q[1]), s2 = std::sin(s.q[1]);
    const double c1 = std::cos(s.q[0]), c12 = std::cos(s.q[0] + s.q[1]);
    Eigen::Matrix2d H;
    H(0, 0) = m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * c2) + I1 + I2 + rotor;
    H(0, 1) = H(1, 0) = m2 * (lc2 * lc2 + l1 * lc2 * c2) + I2;
    H(1, 1) = m2 * lc2 * lc2 + I2;
    const double h = -m2 * l1 * lc2 * s2;
    Eigen::Matrix2d C;
    C << h * s.qd[1], h * (s.qd[0] + s.qd[1]), -h * s.qd[0], 0.0;
    const Eigen::Vector2d G((m1 * lc1 + m2 * l1) * g * c1 + m2 * lc2 * g * c12, m2 * lc2 * g * c12);

    worst = std::max({worst, relative_difference(e.H, H, max_abs(H)),
                      relative_difference(e.C, C, std::max(max_abs(C), max_abs(H))),
                      relative_difference(e.g, G, std::max(max_abs(G), max_abs(H)))});
    ASSERT_LT(worst, 1e-12) << "state " << k << "\nH dyncc\n"
                            << e.H << "\nH textbook\n"
                            << H << "\nC dyncc\n"
                            << e.C << "\nC textbook\n"
                            << C << "\ng dyncc " << e.g.transpose() << "\ng textbook " << G.transpose();
  }
  RecordProperty("largest_relative_error", scientific(worst));
}

}  // namespace
}  // namespace dyncc::test
