// Whole logs of the blind sim2real bench that a binary once got wrong, regenerated from the
// bench's seed (the same synthetic generator, arm, rate and injected sizes as the case) and
// diagnosed again. They are long logs of 6- and 7-joint arms (tens of thousands of samples), a
// minute or more each under the sanitizers, so the sanitizer run leaves this suite out (the
// asan test preset excludes BlindBenchCase); the same code paths run there on the shorter Kraft
// logs of diagnose_effect_test.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/diagnosis_output.hpp"
#include "diagnose/synthetic_log.hpp"
#include "dynamics_support.hpp"
#include "temp_path.hpp"

namespace dyncc::test {
namespace {

using diagnose::Injection;

// A bench case regenerated: the arm's log with the injected effects at the case's rate and seed
// (the bench seeds case c of seed S with S * 1000 + c; a payload picked up at `payload_on` and
// put down at `payload_off`), diagnosed.
struct BenchCase {
  diagnose::Dataset data;
  diagnose::Diagnosis diagnosis;
  std::map<std::string, double> fitted;  // every selected effect's parameters, by name
};

BenchCase diagnosed(const char* arm, const std::vector<Injection>& effects, double rate, unsigned seed,
                    double payload_on = 0, double payload_off = 1e300) {
  const std::unique_ptr<pipeline::Derivation> robot =
      derive_file(std::filesystem::path(DYNCC_SOURCE_DIR) / "robots" / (std::string(arm) + ".yaml"));
  diagnose::SyntheticOptions options;
  options.rate = rate;
  options.seed = seed;
  options.payload_on = payload_on;
  options.payload_off = payload_off;
  const auto path = temp_path(std::string(arm) + "_case.csv");
  diagnose::write_synthetic_log(*robot, effects, options, path);
  const auto joints = static_cast<Eigen::Index>(robot->robot.coordinates.size());
  BenchCase out{diagnose::build_dataset({diagnose::read_joint_log(path.string(), joints)}, *robot), {}, {}};
  out.diagnosis = diagnose::diagnose(out.data, *robot);
  for (const auto& r : out.diagnosis.selected) {
    for (const auto& p : r.parameters) out.fitted[p.name] = p.value;
  }
  return out;
}

// A selected effect's parameter and how near its truth it must be read.
struct Fit {
  std::string name;
  double truth = 0, tolerance = 0;
};

// The verdict names `effect` first (a tie "A or B" counts by its first name) on `joints` alone
// (not checked when empty: an effect of the whole arm), and each of `fits` is among the selected effects' parameters,
// within its tolerance. A failure prints the whole diagnosis.
void expect_case(const BenchCase& c, const std::string& effect, const std::vector<int>& joints,
                 const std::vector<Fit>& fits) {
  SCOPED_TRACE(diagnose::diagnosis_text(c.data, c.diagnosis));
  const std::string& verdict = c.diagnosis.verdict.effect;
  EXPECT_EQ(verdict.substr(0, verdict.find(" or ")), effect) << verdict;
  if (!joints.empty()) {
    EXPECT_EQ(c.diagnosis.verdict.joints, joints);
  }
  for (const Fit& f : fits) {
    const auto it = c.fitted.find(f.name);
    if (it == c.fitted.end()) {
      ADD_FAILURE() << f.name << " is not among the selected effects' parameters";
      continue;
    }
    EXPECT_NEAR(it->second, f.truth, f.tolerance) << f.name;
  }
}

// An effect-free log whose friction turns over differently from the model's: the PUMA 560 log of
// the blind bench's seed 23, case 25 (1 kHz; the log's Coulomb friction is an exact sign, the
// model's is smoothed over the estimated velocity). Its only residual is at reversals, where a
// Stribeck excess at the smallest scale fits it (it was read as stribeck_friction of joint 5);
// the friction does not differ where the velocity is away from zero, so the verdict is none.
TEST(BlindBenchCase, PumaFrictionTurningOverDifferentlyAtReversalsIsNotAnEffect) {
  const BenchCase c = diagnosed("puma560", {}, 1000, 23U * 1000U + 25U);
  SCOPED_TRACE(diagnose::diagnosis_text(c.data, c.diagnosis));
  EXPECT_EQ(c.diagnosis.verdict.effect, "none");
  EXPECT_TRUE(c.diagnosis.selected.empty());
}

// Case 29 of the blind seed 23 (Panda, 500 Hz): a Stribeck excess on joint 1 (5 % of its torque)
// beside a Coulomb friction on joint 4 (half as big). Stribeck columns on both joints lead the
// first step; narrowed to joint 1 they kept the scale chosen for both joints together (bent to
// fit joint 4's Coulomb), explained less than Coulomb friction on both, and the verdict was the
// smaller effect. The scale is chosen again on the kept joints, and a simpler effect is as good
// as a fuller one only when no fold shows the fuller one clearly better.
TEST(BlindBenchCase, PandaStribeckBesideASmallerCoulombOfAnotherJointLeads) {
  const Injection stribeck{.effect = "stribeck_friction", .joint = 0, .size = 0.0604};
  const Injection coulomb{.effect = "coulomb_friction", .joint = 3, .size = 0.205};
  expect_case(diagnosed("panda", {stribeck, coulomb}, 500, 23U * 1000U + 29U), "stribeck_friction", {1},
              {{"fs1", stribeck.size, 0.1 * stribeck.size}, {"fc4", coulomb.size, 0.1 * coulomb.size}});
}

// Case 14 of the blind seed 211 (Panda, 1 kHz): a torque gain of joint 7 (20 % of its torque)
// beside a Coulomb friction of joint 1 (half as big). The first step accepted a Coulomb friction
// of joints 1 and 7 (its joint 7 mimicking the gain), the gain of joint 7 came second, and the
// joint refit narrowed the friction to joint 1; the steps kept the figures of the friction as
// accepted (joint 7's gap in its step), and the verdict named it. Stated again with the effects
// as narrowed, the gain's step removes more than the friction's and leads.
TEST(BlindBenchCase, PandaGainLeadsAFrictionNarrowedOffItsJoint) {
  const Injection gain{.effect = "torque_gain", .joint = 6, .size = 1.22};
  const Injection coulomb{.effect = "coulomb_friction", .joint = 0, .size = 0.04767716184435421};
  expect_case(diagnosed("panda", {gain, coulomb}, 1000, 211U * 1000U + 14U), "torque_gain", {7},
              {{"gain7", gain.size, 0.1 * (gain.size - 1.0)}, {"fc1", coulomb.size, 0.1 * coulomb.size}});
}

// Case 37 of the blind seed 241 (PUMA 560, 500 Hz): a position offset of joint 2 (5 % of the
// torque). A spring of joint 2 explains the same (the offset's gravity column is what a spring's
// deflection under gravity adds), so the step is "position_offset or joint_elasticity". The log
// cannot tell them apart; the spring is fitted in the offset's place, so the user is shown what
// it would be if that is the explanation.
TEST(BlindBenchCase, AnAlternativeIsFittedInThePlaceOfTheEffectItTiesWith) {
  const Injection offset{.effect = "position_offset", .joint = 1, .size = 0.044877789130104435};
  const BenchCase c = diagnosed("puma560", {offset}, 500, 241U * 1000U + 37U);
  SCOPED_TRACE(diagnose::diagnosis_text(c.data, c.diagnosis));
  EXPECT_EQ(c.diagnosis.verdict.effect, "position_offset or joint_elasticity");
  EXPECT_NEAR(c.fitted.at("offset2"), offset.size, 0.1 * offset.size);
  const diagnose::FittedParameter* stiffness = nullptr;
  double named = 0, in_place = 0;
  for (const auto& r : c.diagnosis.selected) {
    for (const auto& a : r.alternatives) {
      if (a.effect != "joint_elasticity") continue;
      EXPECT_EQ(r.joints, std::vector<int>{2});
      for (const auto& p : a.parameters) {
        if (p.name == "stiffness2") stiffness = &p;
      }
      named = a.named_selection_shrink;
      in_place = a.selection_shrink;
    }
  }
  ASSERT_NE(stiffness, nullptr) << "no spring of joint 2 stated as an alternative";
  EXPECT_GT(stiffness->value, 0.0);
  EXPECT_LT(stiffness->low, stiffness->value);
  EXPECT_GT(stiffness->high, stiffness->value);
  // A tie: the selection removes about as much either way (the step could not tell them apart).
  EXPECT_NEAR(in_place, named, 0.05);
}

// Case 29 of the blind seed 229 (Panda, 500 Hz): a torque gain of joint 2 (5 % of its torque)
// beside a spring of the same joint. The gain was accepted first (on joints 1-3, narrowed to
// joint 2 by the joint refit), the spring second; the two partly cancel, so beside the gain the
// spring removed more than the gain had, and the steps stated again put it first, where alone
// it removes 7 % and the gain after it 95 %: the verdict named the spring. A new order is kept
// only where its steps still remove less at each step.
TEST(BlindBenchCase, PandaGainLeadsASpringOfItsJointThatPartlyCancelsIt) {
  const Injection gain{.effect = "torque_gain", .joint = 1, .size = 1.055};
  const Injection spring{.effect = "joint_elasticity", .joint = 1, .size = 2303.207036800785};
  expect_case(diagnosed("panda", {gain, spring}, 500, 229U * 1000U + 29U), "torque_gain", {2},
              {{"gain2", gain.size, 0.1 * (gain.size - 1.0)}});
}

// Case 4 of the blind seed 229 (PUMA 560, 81 Hz): a table touched by the wrist (20 % of the
// torque) beside a sensor delay half as large. The contact, with touches in few folds, has a wide
// interval (75 % [47, 103]), so a delay with a smaller effect beside it was "as good" a pair and
// led; the contact came second and removed 93 % of what was left, three times what the delay had.
// Stated again in the order of what each removes (consistent: the delay after the contact still
// removes less), the contact leads.
TEST(BlindBenchCase, PumaContactLeadsTheDelayThatStoodInForItAtTheFirstStep) {
  const Injection contact{.effect = "contact", .joint = 4, .size = 0.7923591422036024};
  const Injection delay{.effect = "sensor_delay", .joint = 0, .size = 0.013865857026542527};
  expect_case(diagnosed("puma560", {contact, delay}, 81, 229U * 1000U + 4U), "contact", {},
              {{"delay", delay.size, 1.0 / 81}});
}

// Case 49 of the blind seed 43 (PUMA 560, 500 Hz): a torque gain of joint 2 (5 % of the torque)
// beside an elastic joint 3 (half as big). The gain, narrowed to joint 2, gave way to the whole
// inertial parameter set, which two smaller effects together explain as well; the pair's weaker
// member, the spring (23 % of the gap alone against the gain's 72 %), then led. The pair's
// stronger member leads.
TEST(BlindBenchCase, PumaTorqueGainLeadsTheSpringItIsPairedWith) {
  const Injection gain{.effect = "torque_gain", .joint = 1, .size = 1.055};
  const Injection spring{.effect = "joint_elasticity", .joint = 2, .size = 194.138};
  expect_case(diagnosed("puma560", {gain, spring}, 500, 43U * 1000U + 49U), "torque_gain", {2},
              {{"gain2", gain.size, 0.1 * (gain.size - 1.0)}, {"stiffness3", spring.size, 0.1 * spring.size}});
}

// Case 44 of the blind seed 43 (Panda, 200 Hz): a rotor inertia of joint 4 (10 % of the torque)
// and a spring of the same joint. The rotor inertias fitted over the arm took a negative
// correction beyond twice its error on joint 3, so the whole candidate was implausible and the
// spring was named alone first. A per-joint fit implausible on some joints only is judged on the
// others.
TEST(BlindBenchCase, PandaRotorInertiaIsNotLostToANegativeFitOfAnotherJoint) {
  const Injection rotor{.effect = "rotor_inertia", .joint = 3, .size = 0.75219};
  const Injection spring{.effect = "joint_elasticity", .joint = 3, .size = 276.144};
  // (The spring alone explains as much: "rotor_inertia or joint_elasticity".)
  expect_case(diagnosed("panda", {rotor, spring}, 200, 43U * 1000U + 44U), "rotor_inertia", {4},
              {{"ia4", rotor.size, 0.1 * rotor.size}, {"stiffness4", spring.size, 0.1 * spring.size}});
}

// Case 34 of the blind seed 47 (PUMA 560, 81 Hz): a Coulomb friction of joint 1 (20 % of the
// torque) beside a sensor delay. The PUMA's first joint carries mostly its own friction, so a
// torque gain of that joint explains nearly the same over all rows (55.5 % both), and the step was
// "torque_gain or stribeck_friction or coulomb_friction" with the gain first (0.834). Where joint
// 1 moves, away from the reversals at which the model's own friction turns over differently, the
// gain leaves eleven times what the Coulomb friction does, fold by fold: the log tells them apart.
TEST(BlindBenchCase, PumaCoulombFrictionThatATorqueGainMimicsIsToldApartWhereTheJointMoves) {
  const Injection coulomb{.effect = "coulomb_friction", .joint = 0, .size = 5.5253348052934115};
  const Injection delay{.effect = "sensor_delay", .joint = 5, .size = 0.015426726874363961};
  const BenchCase c = diagnosed("puma560", {coulomb, delay}, 81, 47U * 1000U + 34U);
  expect_case(c, "coulomb_friction", {1}, {{"fc1", coulomb.size, 0.1 * coulomb.size}, {"delay", delay.size, 1.0 / 81}});
  EXPECT_EQ(c.diagnosis.verdict.effect, "coulomb_friction");
}

// Case 52 of the blind seed 241 (PUMA 560, 500 Hz): a torque gain of 1.11 on joint 1, the other
// way round: it was "torque_gain or stribeck_friction or coulomb_friction". Where joint 1 moves,
// a Coulomb friction leaves 900 times what the gain does (the gain also scales the
// joint's inertial torque, which no friction fits).
TEST(BlindBenchCase, PumaTorqueGainThatACoulombFrictionMimicsIsToldApartWhereTheJointMoves) {
  const Injection gain{.effect = "torque_gain", .joint = 0, .size = 1.11};
  const BenchCase c = diagnosed("puma560", {gain}, 500, 241U * 1000U + 52U);
  expect_case(c, "torque_gain", {1}, {{"gain1", gain.size, 0.1 * (gain.size - 1.0)}});
  EXPECT_EQ(c.diagnosis.verdict.effect, "torque_gain");
}

// Case 9 of the blind seed 241 (Kraft, 81 Hz): a payload picked up at 14.5 s and a torque gain of
// 1.055 on the base joint. The gain's step was "torque_gain or rotor_inertia": the base joint
// carries no gravity, so its torque is mostly its own inertia's, and a rotor inertia of -0.035
// explained as much over all rows. The two differ by what the gain also scales, the joint's
// Coriolis and friction torques, which act where it moves: there the rotor inertia leaves 1.6
// times what the gain does, in every fold, and the gain is named alone (on the closed-loop Kraft
// logs of blind seed 269, cases 9 and 57, this told a rotor inertia and a gain of the base joint
// apart where the verdict had taken each for the other).
TEST(BlindBenchCase, KraftBaseJointGainIsToldFromARotorInertiaWhereTheJointMoves) {
  const Injection payload{.effect = "payload", .joint = 1, .size = 0.04775229723636052};
  const Injection gain{.effect = "torque_gain", .joint = 0, .size = 1.055};
  const BenchCase c = diagnosed("kraft", {payload, gain}, 81, 241U * 1000U + 9U, 14.507612357354143);
  expect_case(c, "payload", {}, {{"mass", payload.size, 0.03 * payload.size}, {"gain1", gain.size, 0.1 * 0.055}});
  ASSERT_EQ(c.diagnosis.selected.size(), 2U);
  EXPECT_EQ(c.diagnosis.selected[1].effect, "torque_gain");
  EXPECT_EQ(c.diagnosis.selected[1].joints, std::vector<int>{1});
}

// Case 39 of the blind seed 83 (Kraft, 81 Hz): a Coulomb friction of joint 1 (5 % of the torque)
// beside a 12.4 ms sensor delay. At the first step, with the delay not yet fitted, a Stribeck
// friction of joint 1 explained more than Coulomb alone (72.8 % against 66.5 %); once the delay
// was in, the joint fit read its excess as -0.0009, yet the verdict stayed stribeck_friction. An
// excess the joint fit reads as zero or less is no Stribeck effect: the verdict is the Coulomb
// friction, and both parameters are within the bench's goals.
TEST(BlindBenchCase, KraftStribeckExcessThatADelayExplainsIsACoulombFriction) {
  const Injection coulomb{.effect = "coulomb_friction", .joint = 0, .size = 0.0195478};
  const Injection delay{.effect = "sensor_delay", .joint = 0, .size = 0.0123953};
  const BenchCase c = diagnosed("kraft", {coulomb, delay}, 81, 83U * 1000U + 39U);
  expect_case(c, "coulomb_friction", {1}, {{"fc1", coulomb.size, 0.1 * coulomb.size}, {"delay", delay.size, 1.0 / 81}});
  EXPECT_EQ(c.fitted.count("fs1"), 0U);
}

// Case 19 of the blind seed 67 (PUMA 560, 200 Hz): a Coulomb friction of joint 5 (10 % of the
// torque) beside a viscous friction of joint 4. Coulomb columns on joints 4 and 5 explained 88.6 %,
// a torque gain of the same joints 88.1 %; narrowed to joint 5 (joint 4 is the viscous
// friction's) the Coulomb friction was compared with the gain still counted on both joints, the
// gain led, and the verdict was a gain of joint 5 (0.91). Counted on its own joint too, the gain
// does not lead.
TEST(BlindBenchCase, PumaCoulombFrictionIsNotLedByAGainCountedOnTheViscousJointBesideIt) {
  const Injection coulomb{.effect = "coulomb_friction", .joint = 4, .size = 0.09667718651432111};
  const Injection viscous{.effect = "viscous_friction", .joint = 3, .size = 0.15677597443865066};
  expect_case(diagnosed("puma560", {coulomb, viscous}, 200, 67U * 1000U + 19U), "coulomb_friction", {5},
              {{"fc5", coulomb.size, 0.1 * coulomb.size}, {"fv4", viscous.size, 0.1 * viscous.size}});
}

// Case 49 of the blind seed 73 (PUMA 560, 500 Hz): a torque gain of joint 6 (20 % of the torque)
// beside a viscous friction of joint 5. The gain's columns on joints 5 and 6 explained 96.3 %;
// narrowed to joint 6 (joint 5 is the friction's), it gave way to a Coulomb friction of joints 5
// and 6 that explained more but kept none of its joints (the gain and the viscous friction each
// explain one better), which then dropped out, and the viscous friction was named first. Such a
// candidate leads only when a simpler effect took its joints (Coulomb for Stribeck).
TEST(BlindBenchCase, PumaGainIsNotLedByACoulombFrictionWhoseJointsTheGainItselfExplains) {
  const Injection gain{.effect = "torque_gain", .joint = 5, .size = 1.22};
  const Injection viscous{.effect = "viscous_friction", .joint = 4, .size = 0.27810010199447427};
  expect_case(diagnosed("puma560", {gain, viscous}, 500, 73U * 1000U + 49U), "torque_gain", {6},
              {{"gain6", gain.size, 0.1 * (gain.size - 1.0)}, {"fv5", viscous.size, 0.1 * viscous.size}});
}

// Case 34 of the blind seed 109 (PUMA 560, 200 Hz): a torque gain of joint 1 (20 % of the torque)
// beside a viscous friction of joint 5. Joint 1's torque is mostly friction, so narrowed to joint 1
// the gain (85.1 %) and a Coulomb friction of joint 1 (84.2 %) were alike and the Coulomb friction
// was accepted first; the gain came in at the third step and explained all the Coulomb friction
// had, which was dropped, and the verdict went to the viscous friction, accepted second. The
// effect that took over a dropped one's joints takes its place in the order.
TEST(BlindBenchCase, PumaGainTakesThePlaceOfTheCoulombFrictionItTookOver) {
  const Injection gain{.effect = "torque_gain", .joint = 0, .size = 1.22};
  const Injection viscous{.effect = "viscous_friction", .joint = 4, .size = 0.2556362415623103};
  expect_case(diagnosed("puma560", {gain, viscous}, 200, 109U * 1000U + 34U), "torque_gain", {1},
              {{"gain1", gain.size, 0.1 * (gain.size - 1.0)}, {"fv5", viscous.size, 0.1 * viscous.size}});
}

// Case 4 of the blind seed 127 (PUMA 560, 1 kHz): a torque gain of joint 4 (5 % of the torque)
// beside a viscous friction of the same joint. A Coulomb friction of joint 4 was accepted first,
// then the viscous friction and the gain, which together explain all the Coulomb friction did; the
// place of the dropped Coulomb friction went to the first of them, the viscous friction. It goes
// to the one that reproduces what the Coulomb friction fitted, the gain (whose column, the joint's
// torque, is mostly its friction).
TEST(BlindBenchCase, PumaGainTakesThePlaceOfTheCoulombFrictionItReproducesBesideAViscousOne) {
  const Injection gain{.effect = "torque_gain", .joint = 3, .size = 1.055};
  const Injection viscous{.effect = "viscous_friction", .joint = 3, .size = 0.08237523447855896};
  expect_case(diagnosed("puma560", {gain, viscous}, 1000, 127U * 1000U + 4U), "torque_gain", {4},
              {{"gain4", gain.size, 0.1 * (gain.size - 1.0)}, {"fv4", viscous.size, 0.1 * viscous.size}});
}

// Case 59 of the blind seed 127 (Panda, 200 Hz): a Stribeck friction of joint 1 (10 % of the
// torque) beside a spring of joint 2. The Stribeck friction led the first step (58.1 %, over a wide
// interval), and the spring (38.4 %) was "as good" by the folds' spread, with fewer columns, so it
// was named first though it explains another joint. Parsimony chooses among explanations of the
// same joints.
TEST(BlindBenchCase, PandaSpringOfAnotherJointIsNotASimplerStribeckFriction) {
  const Injection stribeck{.effect = "stribeck_friction", .joint = 0, .size = 0.22105114548699825};
  const Injection spring{.effect = "joint_elasticity", .joint = 1, .size = 1317.4310553571474};
  expect_case(diagnosed("panda", {stribeck, spring}, 200, 127U * 1000U + 59U), "stribeck_friction", {1},
              {{"fs1", stribeck.size, 0.1 * stribeck.size}, {"stiffness2", spring.size, 0.1 * spring.size}});
}

// Case 11 of the blind seed 43 (Panda, 81 Hz): a table touched by the hand (10 % of the torque)
// in one or two of the five folds. The contact explained 96 % held out, but its folds' spread made
// a payload explaining 58 % "as good", and the payload, with fewer columns, was accepted first
// ("payload or contact", a mass of 1 +- 1.3 g); the contact beside it explained all the payload
// had. A whole-arm effect that the others explain all of is dropped, its place to the contact.
TEST(BlindBenchCase, PandaContactTakesThePlaceOfAWeightlessPayloadItExplains) {
  const Injection contact{.effect = "contact", .joint = 6, .size = 0.3943922537539499};
  expect_case(diagnosed("panda", {contact}, 81, 43U * 1000U + 11U), "contact", {}, {});
}

// Case 9 of the blind seed 53 (Kraft, 81 Hz): a Stribeck excess of joint 2 (20 % of the torque)
// and a viscous friction of the same joint. The Stribeck scale was chosen before the viscous
// friction was fitted and bent to mimic it: fs2 0.449 for 0.350, fv2 0.109 for 0.201. Each
// profile effect's point is chosen again beside all accepted effects.
TEST(BlindBenchCase, KraftStribeckScaleIsChosenAgainBesideTheViscousFrictionOfItsJoint) {
  const Injection stribeck{.effect = "stribeck_friction", .joint = 1, .size = 0.350485};
  const Injection viscous{.effect = "viscous_friction", .joint = 1, .size = 0.200918};
  expect_case(diagnosed("kraft", {stribeck, viscous}, 81, 53U * 1000U + 9U), "stribeck_friction", {2},
              {{"fs2", stribeck.size, 0.1 * stribeck.size}, {"fv2", viscous.size, 0.1 * viscous.size}});
}

// Case 54 of the blind seed 23 (Kraft, 81 Hz): a payload picked up at 9.3 s beside a contact
// (20 % of the torque). The model plant's friction is the description's, so the rows near zero
// velocity are explained as well as the others and carry much of what tells the load from the
// contact: fitting the load on the rows away from zero velocity only (and the contact, which acts
// at rest, on all) read the mass 8 % low (0.0824 kg for 0.0899; 0.0878 on all rows). Rows near
// zero are dropped only for a joint whose residual there is over twice that away from zero.
TEST(BlindBenchCase, KraftPayloadBesideAContactKeepsTheRowsAtRestThatTheEffectsExplain) {
  const Injection payload{.effect = "payload", .joint = 1, .size = 0.0899221};
  const Injection contact{.effect = "contact", .joint = 1, .size = 2.07215};
  expect_case(diagnosed("kraft", {payload, contact}, 81, 23U * 1000U + 54U, 9.31551), "payload", {},
              {{"mass", payload.size, 0.03 * payload.size}});
}

// Case 4 of the blind seed 101 (PUMA 560, 81 Hz): a Stribeck friction of joint 1 (20 % of the
// torque) beside a sensor delay. The Stribeck friction led the first step (55.8 %), but counted
// with its columns on all six joints (twelve) it was a large set that a delay and a spring stand
// in for together, so the delay was named first. Counted where it acts (joint 1: two columns), it
// leads.
TEST(BlindBenchCase, PumaStribeckOfOneJointIsNotALargeSetThatADelayAndASpringStandInFor) {
  const Injection stribeck{.effect = "stribeck_friction", .joint = 0, .size = 19.108314232206272};
  const Injection delay{.effect = "sensor_delay", .joint = 4, .size = 0.014434993042380722};
  expect_case(diagnosed("puma560", {stribeck, delay}, 81, 101U * 1000U + 4U), "stribeck_friction", {1},
              {{"fs1", stribeck.size, 0.1 * stribeck.size}, {"delay", delay.size, 1.0 / 81}});
}

// Case 29 of the blind seed 97 (Panda, 1 kHz): a Stribeck friction of joint 4 (5 % of the
// torque) and a spring of the same joint. Narrowed to joint 4, the Stribeck friction gave the
// joint to the spring (simpler, and not clearly less in every fold) and the spring gave it to the
// Stribeck friction (better by the margin), so neither was named and a payload explaining 7 % led
// the verdict. A simpler effect is not as good as one that is better by that margin.
TEST(BlindBenchCase, PandaStribeckAndSpringOfOneJointDoNotGiveTheJointToEachOther) {
  const Injection stribeck{.effect = "stribeck_friction", .joint = 3, .size = 2.6566104200824867};
  const Injection spring{.effect = "joint_elasticity", .joint = 3, .size = 653.4152243834509};
  expect_case(diagnosed("panda", {stribeck, spring}, 1000, 97U * 1000U + 29U), "stribeck_friction", {4},
              {{"fs4", stribeck.size, 0.1 * stribeck.size}});
}

// Case 23 of the blind seed 53 (Panda, 1 kHz): positions logged 36 ms late (20 % of the torque).
// The delay's column was the tangent, delay times the model torque's rate, which leaves out the
// cubic term of the shift: the fit read 34.95 ms for 35.97, a sample too short at 1 kHz, and
// explained 95 % of the gap. The column is the secant at the fitted delay.
TEST(BlindBenchCase, PandaDelayOfThirtySixSamplesIsReadToWithinHalfASample) {
  const Injection delay{.effect = "sensor_delay", .joint = 6, .size = 0.035973};
  const BenchCase c = diagnosed("panda", {delay}, 1000, 53U * 1000U + 23U);
  expect_case(c, "sensor_delay", {}, {{"delay", delay.size, 0.0005}});
  ASSERT_FALSE(c.diagnosis.selected.empty());
  EXPECT_GT(c.diagnosis.selected.front().shrink, 0.99);
}

// Case 9 of the blind seed 137 (Kraft, open loop, 81 Hz): a 29 g payload carried from 6.8 s to
// 25.6 s beside a torque gain of 1.0275 on joint 2 (5 % of the torque). Both were selected, but
// the payload read 3.0 % light: the arm applies the gain times the logged torque, so the logged
// torque of the payload on joint 2 is the applied one over the gain, and the payload's columns,
// which have rows on joints 2 and 3, were fitted as if applied and logged were the same. Its rows
// of joint 2 are now divided by the fitted gain.
TEST(BlindBenchCase, KraftPayloadBesideATorqueGainOfItsJointIsReadInAppliedTorque) {
  const Injection payload{.effect = "payload", .joint = 1, .size = 0.029033830074849328};
  const Injection gain{.effect = "torque_gain", .joint = 1, .size = 1.0275};
  expect_case(diagnosed("kraft", {payload, gain}, 81, 137U * 1000U + 9U, 6.794017166581532, 25.643529397353092),
              "payload", {},
              {{"mass", payload.size, 0.01 * payload.size}, {"gain2", gain.size, 0.1 * (gain.size - 1)}});
}

// Case 24 of the blind seed 439 (Kraft, open loop, 81 Hz): a 47 g payload picked up at 13.6 s
// beside an offset of joint 2 of 0.173 rad. Alone, the offset fits 0.242 rad (it takes up part of
// the load's torque), and its columns were the secant made there: read beside the payload, that
// chord left the mass 3.8 % heavy. Made again at the joint fit's offset, 1.6 %.
TEST(BlindBenchCase, KraftPayloadBesideALargeOffsetIsReadWithTheSecantMadeAtTheJointFit) {
  const Injection payload{.effect = "payload", .joint = 1, .size = 0.04744393495034269};
  const Injection offset{.effect = "position_offset", .joint = 1, .size = 0.1725234006694808};
  expect_case(diagnosed("kraft", {payload, offset}, 81, 439U * 1000U + 24U, 13.58631949482385), "payload", {},
              {{"mass", payload.size, 0.03 * payload.size}, {"offset2", offset.size, 0.1 * offset.size}});
}

// Case 4 of seed 379 (PUMA 560, Fourier excitation, 500 Hz): a 17.3 ms sensor delay beside a
// rotor inertia of joint 6 of 0.0375. The delay lags the rotor's torque as it lags the model's:
// the torque is ia6 qdd6 at the true positions, which the logged ones reach `delay` later. With
// the delay's column the model's torque alone, the rotor's lag (ia6 times the delay times the
// jerk) had only the delay's column on joint 6 to go to, and read 18.45 ms (+0.56 samples) and
// ia6 1.9 % light; seed 509 case 4, the same pair at 1 kHz, 1.24 samples long. The column now
// carries the other effects' fitted torque, lagged alike (settle.cpp, torque_the_positions_lag).
TEST(BlindBenchCase, PumaDelayLagsTheRotorInertiaBesideIt) {
  const Injection delay{.effect = "sensor_delay", .joint = 3, .size = 0.017330794983432568};
  const Injection rotor{.effect = "rotor_inertia", .joint = 5, .size = 0.03754934974843335};
  expect_case(diagnosed("puma560", {delay, rotor}, 500, 379U * 1000U + 4U), "sensor_delay", {},
              {{"delay", delay.size, 0.0005}, {"ia6", rotor.size, 0.01 * rotor.size}});
}

// Case 7 of the blind seed 569 (PUMA 560, Fourier excitation, 200 Hz): a rotor inertia of joint 6
// of 0.0314 (5 % of the torque), alone. After it, a Stribeck friction of joint 6 was accepted for
// how the friction turns over at reversals, and a torque gain after that; in the joint fit the
// friction held no excess and became a Coulomb friction, and stated in order the two made the
// held-out gap larger (by 0.2 % and 2.4 %), yet stayed, and beside them ia6 read 0.0272 (-13.5 %).
// No stated step may make the gap larger.
TEST(BlindBenchCase, PumaRotorInertiaIsNotReadBesideStepsThatAddToTheGap) {
  const Injection rotor{.effect = "rotor_inertia", .joint = 5, .size = 0.03144978990895537};
  const BenchCase c = diagnosed("puma560", {rotor}, 200, 569U * 1000U + 7U);
  expect_case(c, "rotor_inertia", {6}, {{"ia6", rotor.size, 0.1 * rotor.size}});
  for (const auto& r : c.diagnosis.selected) EXPECT_GE(r.shrink, 0) << r.effect;
}

// Case 19 of the blind seed 563 (PUMA 560, Fourier excitation, 200 Hz): an offset of joint 2 of
// 0.0915 rad beside a 117 g load. The positions the load's torque is computed from are off by the
// offset too, but the offset's column was the model's change alone, so the load's part of it went
// to the offset, read 0.0964 (+5.4 %). The column is now made again with the fitted load moved by
// the shift as the model is (settle.cpp, relinearise_secants; payload.cpp, standard_change).
TEST(BlindBenchCase, PumaOffsetMovesTheLoadBesideItAsItMovesTheModel) {
  const Injection offset{.effect = "position_offset", .joint = 1, .size = 0.0914963532799243};
  const Injection payload{.effect = "payload", .joint = 4, .size = 0.11654654272194363};
  expect_case(diagnosed("puma560", {offset, payload}, 200, 563U * 1000U + 19U), "position_offset", {2},
              {{"offset2", offset.size, 0.01 * offset.size}, {"mass", payload.size, 0.01 * payload.size}});
}

// Case 59 of the blind seed 139 (Panda, 1 kHz): a torque gain of 1.22 on joint 7 beside a 14 ms
// delay. Joint 7's torque is mostly the drive's friction, so at the first step a Coulomb friction
// of joint 7 ties with the gain and led ("coulomb_friction or torque_gain"); after the delay, the
// gain's share of the rest of the torque read as "payload or torque_gain" on joint 7. The gain
// alone explains both steps as well as the two together, so it is the one effect named.
TEST(BlindBenchCase, PandaGainThatTwoStepsNameIsOneEffect) {
  const Injection gain{.effect = "torque_gain", .joint = 6, .size = 1.22};
  const Injection delay{.effect = "sensor_delay", .joint = 6, .size = 0.0142503351816462};
  expect_case(diagnosed("panda", {gain, delay}, 1000, 139U * 1000U + 59U), "torque_gain", {7},
              {{"gain7", gain.size, 0.1 * (gain.size - 1.0)}, {"delay", delay.size, 0.001}});
}

// Case 21 of seed 97 (Kraft, Fourier excitation, 81 Hz): a soft spring of 17.81 N m/rad in the
// base joint, read 20.58 (+15.5 %) with a rotor inertia of 0.0187 beside it. The spring's columns
// are made from the logged torque, whose 0.01 N m noise, twice differentiated, was a quarter of
// them in the filter's band: errors in variables. Read free of that noise (torque_noise.hpp).
//
// Its stated 95 % interval holds the truth, though the value is more than two standard errors
// from it: the error is a jackknife's over five folds, four degrees of freedom, and the interval
// is Student's t's (2.776 errors, the textbook's 97.5 % quantile), taken on the compliance the
// column fits and read as a stiffness (so it reaches further above the value than below).
TEST(BlindBenchCase, SoftKraftSpringReadFreeOfTheTorqueNoise) {
  const Injection spring{.effect = "joint_elasticity", .joint = 0, .size = 17.813850755355983};
  const BenchCase c = diagnosed("kraft", {spring}, 81, 97U * 1000U + 21U);
  expect_case(c, "joint_elasticity", {1}, {{"stiffness1", spring.size, 0.1 * spring.size}});
  ASSERT_FALSE(c.diagnosis.selected.empty());
  const auto& parameters = c.diagnosis.selected.front().parameters;
  const auto stiffness = std::find_if(parameters.begin(), parameters.end(),
                                      [](const diagnose::FittedParameter& p) { return p.name == "stiffness1"; });
  ASSERT_NE(stiffness, parameters.end());
  const diagnose::FittedParameter& k = *stiffness;
  EXPECT_LT(k.low, k.value);
  EXPECT_GT(k.high, k.value);
  EXPECT_GT(k.high - k.value, k.value - k.low);
  EXPECT_LE(k.low, spring.size);
  EXPECT_GE(k.high, spring.size);
  // The compliance's interval: 2 * 2.776 of its error (the stiffness's over the stiffness squared).
  constexpr double kStudentFourDof = 2.776;
  const double compliance_error = k.error / (k.value * k.value);
  EXPECT_NEAR(1.0 / k.low - 1.0 / k.high, 2 * kStudentFourDof * compliance_error, 1e-3 * compliance_error);
}

// Case 34 of the blind seed 149 (PUMA 560, 81 Hz): a viscous friction of 4.31 on joint 1 beside
// a contact of the wrist, half as large. A spring of joint 1 explained more of the log (38 %) than
// the friction (33 %), all of it at reversals (-0.5 % where the velocity is away from zero, so it
// is never acceptable), yet the friction, the gain and Coulomb friction each gave joint 1 to it,
// and the contact was named alone. An effect that explains nothing away from zero velocity, where
// it must, takes no joint from another.
TEST(BlindBenchCase, PumaViscousFrictionDoesNotGiveItsJointToASpringThatCannotTakeIt) {
  const Injection viscous{.effect = "viscous_friction", .joint = 0, .size = 4.3096242892800936};
  const Injection contact{.effect = "contact", .joint = 4, .size = 0.15189403586410116};
  expect_case(diagnosed("puma560", {viscous, contact}, 81, 149U * 1000U + 34U), "viscous_friction", {1},
              {{"fv1", viscous.size, 0.1 * viscous.size}});
}

// Case 49 of the blind seed 173 (PUMA 560, 200 Hz): a Stribeck friction of joint 5 (20 % of the
// torque) beside a viscous friction of joint 4, half as large. Fitted over both joints at each
// velocity scale, the Stribeck columns of joint 4 bent to the viscous friction there and the whole
// candidate was implausible at every scale (94.7 % held out), so it never led, and the viscous
// friction was named first. A profile effect implausible on some joints only is judged on the
// others at each of its points.
TEST(BlindBenchCase, PumaStribeckImplausibleOnAViscousJointIsJudgedOnItsOwn) {
  const Injection stribeck{.effect = "stribeck_friction", .joint = 4, .size = 2.299864106618789};
  const Injection viscous{.effect = "viscous_friction", .joint = 3, .size = 0.39662267073575475};
  expect_case(diagnosed("puma560", {stribeck, viscous}, 200, 173U * 1000U + 49U), "stribeck_friction", {5},
              {{"fs5", stribeck.size, 0.1 * stribeck.size}, {"fv4", viscous.size, 0.1 * viscous.size}});
}

// Case 49 of the blind seed 179 (PUMA 560, 81 Hz): a Coulomb friction of 2.76 N m on joint 1, an
// exact sign in the log, beside an offset of joint 3. A Stribeck excess accepted after the gain
// that ties with the friction took the gain's place, and chosen again beside the other effects
// its scale went to 0.02 rad/s: fs1 0.72, an excess that fades within the band near zero velocity
// and so describes only how sharply the plant's friction turns over. Such an excess is not a
// Stribeck friction; the verdict is the Coulomb friction.
TEST(BlindBenchCase, PumaCoulombFrictionTurningOverSharplyIsNotAStribeckFriction) {
  const Injection coulomb{.effect = "coulomb_friction", .joint = 0, .size = 2.7629870434165418};
  const Injection offset{.effect = "position_offset", .joint = 2, .size = 0.05731188942111526};
  expect_case(diagnosed("puma560", {coulomb, offset}, 81, 179U * 1000U + 49U), "coulomb_friction", {1},
              {{"fc1", coulomb.size, 0.1 * coulomb.size}, {"offset3", offset.size, 0.1 * offset.size}});
}

}  // namespace
}  // namespace dyncc::test
