// What the blind bench counts as naming its injected effect (diagnose/bench_truth.hpp).
#include <gtest/gtest.h>

#include "diagnose/bench_truth.hpp"

namespace dyncc::diagnose {
namespace {

Injection injected(const std::string& effect, int joint, double size) {
  Injection e;
  e.effect = effect;
  e.joint = joint;
  e.size = size;
  return e;
}

TEST(BenchTruth, EachEffectIsNamedByItsOwnName) {
  EXPECT_TRUE(names_injected_effect("none", {}));
  EXPECT_FALSE(names_injected_effect("coulomb_friction", {}));
  EXPECT_TRUE(names_injected_effect("torque_gain", {injected("torque_gain", 2, 1.1)}));
  EXPECT_FALSE(names_injected_effect("rotor_inertia", {injected("torque_gain", 2, 1.1)}));
  // Only the largest (the first) is scored: naming the second is wrong.
  EXPECT_FALSE(names_injected_effect("payload", {injected("torque_gain", 2, 1.1), injected("payload", 0, 0.2)}));
}

// Blind seed 389 case 24: a Coulomb friction (0.070 N m) and a Stribeck excess (0.141 N m) of the
// Kraft's joint 1, named `stribeck_friction` with fc1 0.0700 and fs1 0.157: the whole friction.
TEST(BenchTruth, AStribeckFrictionNamesACoulombFrictionInjectedWithAnExcessOfItsJoint) {
  const std::vector<Injection> both = {injected("coulomb_friction", 0, 0.070), injected("stribeck_friction", 0, 0.141)};
  EXPECT_TRUE(names_injected_effect("stribeck_friction", both));
  EXPECT_TRUE(names_injected_effect("coulomb_friction", both));
}

TEST(BenchTruth, AStribeckFrictionDoesNotNameACoulombFrictionWithoutAnExcessOfItsJoint) {
  EXPECT_FALSE(names_injected_effect("stribeck_friction", {injected("coulomb_friction", 0, 0.070)}));
  EXPECT_FALSE(names_injected_effect("stribeck_friction", {injected("coulomb_friction", 0, 0.070),
                                                           injected("stribeck_friction", 1, 0.141)}));
  // Nor does a Coulomb friction name a Stribeck excess beside it: it leaves the excess out.
  EXPECT_FALSE(names_injected_effect("coulomb_friction", {injected("stribeck_friction", 0, 0.141),
                                                          injected("coulomb_friction", 0, 0.070)}));
}

}  // namespace
}  // namespace dyncc::diagnose
