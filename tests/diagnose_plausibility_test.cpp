// The plausibility stage of the diagnosis (gen/diagnose/plausibility): a fit no real arm could have
// is refused, judged against the description (a correction to its friction) and against the log
// (the joint's torque, the sensor's resolution), each rule checked at both sides of its line.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "diagnose/plausibility.hpp"
#include "dynamics_support.hpp"

namespace dyncc::test {
namespace {

// A log's gap as the rules read it: 1 N m of torque RMS and 1 mrad of position resolution on each
// of the Kraft's three joints.
diagnose::Gap gap() {
  diagnose::Gap g;
  g.torque_rms = Eigen::VectorXd::Constant(3, 1.0);
  g.position_resolution = Eigen::VectorXd::Constant(3, 1e-3);
  return g;
}

bool plausible(const std::string& name, double value, double error = 0.0) {
  return diagnose::plausible_parameter({name, value, error}, kraft_derivation(), gap());
}

TEST(Plausibility, AFrictionCorrectionIsJudgedWithTheDescriptionsFriction) {
  const Eigen::VectorXd nominal = kraft_derivation().numeric->nominal_standard_values();
  const int index = kraft_derivation().model.params.coulomb_of[0];
  ASSERT_GE(index, 0);
  const double described = nominal[index];
  ASSERT_GT(described, 0.0);
  EXPECT_TRUE(plausible("fc1", -0.5 * described, 1e-4)) << "the total friction is still positive";
  EXPECT_FALSE(plausible("fc1", -described - 0.01, 1e-3)) << "the total is negative beyond twice its error";
  EXPECT_TRUE(plausible("fc1", -described - 0.01, 0.01)) << "within twice its error of zero";
  EXPECT_FALSE(plausible("fs1", -0.01, 1e-3)) << "a static excess has no description to lean on";
}

TEST(Plausibility, ASpringMustGiveWayLessThanATransmissionCanAndMoreThanTheSensorResolves) {
  // Under 1 N m RMS a stiffness k gives way 1/k rad: at most 2 * kLargestDeflection, at least two
  // sensor steps.
  const double loosest = 1.0 / (2.0 * diagnose::kLargestDeflection);
  EXPECT_FALSE(plausible("stiffness2", 0.5 * loosest));
  EXPECT_TRUE(plausible("stiffness2", 2.0 * loosest));
  EXPECT_TRUE(plausible("stiffness2", 400.0));   // 2.5 mrad
  EXPECT_FALSE(plausible("stiffness2", 600.0));  // 1.7 mrad: under two steps of 1 mrad
}

TEST(Plausibility, ADeadBandMustBeNarrowerThanALooseJointAndHalfOfItResolved) {
  EXPECT_FALSE(plausible("width3", 0.0015)) << "half of it is under one sensor step";
  EXPECT_TRUE(plausible("width3", 0.004));
  EXPECT_FALSE(plausible("width3", 5.0 * diagnose::kLargestDeflection, 1e-3));
  EXPECT_FALSE(plausible("width3", -0.004, 1e-3));
}

TEST(Plausibility, ADriveOffByMoreThanAFactorOfTwoIsAWrongDescriptionNotAGain) {
  EXPECT_TRUE(plausible("gain1", 1.3));
  EXPECT_FALSE(plausible("gain1", 2.5));
  EXPECT_FALSE(plausible("gain1", 0.4));
}

TEST(Plausibility, ALoadsPointIsOnItsLink) {
  diagnose::RankedEffect near;
  near.parameters = {{"mass", 0.1, 0.01}, {"point_x", 0.3, 0.01}, {"point_y", 0.0, 0.01}};
  EXPECT_TRUE(diagnose::plausible(near, kraft_derivation(), gap()));
  diagnose::RankedEffect far = near;
  far.parameters[1].value = 3.0;
  EXPECT_FALSE(diagnose::plausible(far, kraft_derivation(), gap()));
  diagnose::RankedEffect negative = near;
  negative.parameters[0].value = -0.1;
  EXPECT_FALSE(diagnose::plausible(negative, kraft_derivation(), gap()));
}

// A held contact (its push alone, at the gate's point) pushes beyond twice its error.
TEST(Plausibility, AHeldContactPushes) {
  diagnose::RankedEffect held;
  held.family = "contact";
  held.parameters = {{"force", 0.3, 0.03}, {"point_x", 0.4, 0.0}, {"point_y", 0.0, 0.0}, {"point_z", 0.0, 0.0}};
  EXPECT_TRUE(diagnose::plausible(held, kraft_derivation(), gap()));
  held.parameters[0] = {"force", 0.05, 0.03};
  EXPECT_FALSE(diagnose::plausible(held, kraft_derivation(), gap())) << "a push within twice its error of zero";
  diagnose::RankedEffect pressed = held;  // with moments, a pressed contact only may not pull
  pressed.parameters.push_back({"moment_x", 0.02, 0.01});
  EXPECT_TRUE(diagnose::plausible(pressed, kraft_derivation(), gap()));
}

// A pressed contact's friction is judged by its coefficient: a frictionless table reads a friction
// force of a few mN either side of zero beside its push (blind seed 433 case 19).
TEST(Plausibility, APressedContactsFrictionIsJudgedByItsCoefficient) {
  diagnose::RankedEffect pressed;
  pressed.family = "contact";
  pressed.parameters = {{"force", 0.47, 0.04},
                        {"moment_x", 0.42, 0.02},
                        {"friction_force", -0.0022, 0.0007},
                        {"point_x", 0.9, 0.1},
                        {"friction_coefficient", -0.009, 0.011}};
  EXPECT_TRUE(diagnose::plausible(pressed, kraft_derivation(), gap()));
  pressed.parameters[4] = {"friction_coefficient", -0.3, 0.05};
  EXPECT_FALSE(diagnose::plausible(pressed, kraft_derivation(), gap())) << "friction that pushes the point along";
}

}  // namespace
}  // namespace dyncc::test
