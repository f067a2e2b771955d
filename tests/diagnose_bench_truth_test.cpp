// What the blind bench counts as naming its injected effect, and how large it counts an effect
// injected into a closed-loop run (diagnose/bench_truth.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "diagnose/bench_truth.hpp"
#include "diagnose/crossval.hpp"
#include "diagnose/effects.hpp"
#include "dynamics_support.hpp"

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

// A Kraft log like a tele-operation's: joint 1 holds still for 3 s, then swings out and back in
// 2 s, over and over (60 % of the rows in holds), its positions read through 1.5 mrad steps with
// noise.
struct HoldingLog {
  JointLog log;
  Eigen::VectorXd velocity;  // joint 1's true velocity per sample
};

HoldingLog holding_log() {
  const pipeline::Derivation& derivation = test::kraft_derivation();
  const double rate = 200, duration = 60, hold = 3, swing = 2, quantum = 1.534e-3;
  const auto samples = static_cast<Eigen::Index>(duration * rate);
  HoldingLog out;
  out.log.path = "holding";
  out.log.t.resize(samples);
  out.log.q.resize(samples, 3);
  out.log.tau.resize(samples, 3);
  out.velocity = Eigen::VectorXd::Zero(samples);
  const Eigen::VectorXd nominal = derivation.numeric->nominal_standard_values();
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 4.4e-4);
  for (Eigen::Index s = 0; s < samples; ++s) {
    const double t = static_cast<double>(s) / rate;
    const double phase = std::fmod(t, hold + swing) - hold;  // < 0 in the hold
    const double w = 2 * std::numbers::pi / swing;
    Eigen::VectorXd q(3), qd(3), qdd(3);
    q << 0.0, -0.3, 0.7;
    qd.setZero();
    qdd.setZero();
    if (phase > 0) {
      q[0] = 0.25 * (1 - std::cos(w * phase));
      qd[0] = 0.25 * w * std::sin(w * phase);
      qdd[0] = 0.25 * w * w * std::cos(w * phase);
    }
    out.velocity[s] = qd[0];
    out.log.t[s] = t;
    const std::vector<dyn::State> state{{q, qd, qd, qdd}};
    out.log.tau.row(s) = derivation.numeric->evaluate(state, nominal, false).front().tau.transpose();
    for (Eigen::Index j = 0; j < 3; ++j) out.log.q(s, j) = quantum * std::round((q[j] + noise(random)) / quantum);
  }
  return out;
}

// A Coulomb friction and a Stribeck excess of joint 1 are sized by the torque they add while the
// joint moves: their formula on the true velocity, which is 0 in the holds (here 1.00 and 1.11
// times that; with the sign of the velocity estimate at 2 mrad/s, as before, 1.07 and 4.62 times:
// the excess is largest where the holds' noise is).
TEST(BenchTruth, AFrictionIsSizedByTheTorqueItAddsWhereTheJointMoves) {
  const HoldingLog holding = holding_log();
  const Dataset d = build_dataset({holding.log}, test::kraft_derivation());
  const Eigen::Index n = d.n;
  for (const char* effect : {"coulomb_friction", "stribeck_friction"}) {
    SCOPED_TRACE(effect);
    const Injection e = injected(effect, 0, 0.1);
    // The formula on the true velocity, sampled as the dataset's rows are.
    Eigen::MatrixXd torque = Eigen::MatrixXd::Zero(d.samples() * n, 1);
    for (Eigen::Index s = 0; s < d.samples(); ++s) {
      const auto at = static_cast<Eigen::Index>(std::lround((d.t[s] - holding.log.t[0]) * 200));
      const double v = holding.velocity[std::clamp<Eigen::Index>(at, 0, holding.velocity.size() - 1)];
      const double fade = e.effect == "stribeck_friction" ? stribeck_fade(v, 0.1) : 1.0;
      torque(s * n, 0) = e.size * fade * (v > 0 ? 1.0 : v < 0 ? -1.0 : 0.0);
    }
    const double truth = joint_rms(conditioned_columns(d, e.effect, torque).col(0), n)[0];
    const std::optional<Eigen::VectorXd> sized = closed_loop_effect_rms(d, e);
    ASSERT_TRUE(sized.has_value());
    EXPECT_NEAR((*sized)[0] / truth, 1.0, 0.15);
  }
}

}  // namespace
}  // namespace dyncc::diagnose
