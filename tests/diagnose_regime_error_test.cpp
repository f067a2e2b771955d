// The systematic part of a stated error (gen/diagnose/regime_error): a bias that every block in
// time shares is invisible to the folds' spread; the regime splits must state it, and add
// nothing much where the model is right.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "diagnose/diagnosis.hpp"
#include "diagnose/regime_error.hpp"

namespace dyncc::test {
namespace {

constexpr double kViscous = 0.3;  // N m s/rad: the friction the fit is after

// One joint moving in sweeps of growing amplitude (0.2 to 2 rad/s), its velocity as the analysis
// rows' and a viscous-friction column; `coulomb` N m of a friction the fit does not model.
struct OneJointLog {
  diagnose::Dataset data;
  std::vector<diagnose::Effect> effects;
  Eigen::VectorXd residual;
};

OneJointLog one_joint_log(double coulomb) {
  constexpr Eigen::Index kSamples = 6000;
  constexpr double kStep = 0.01;
  OneJointLog log;
  log.data.n = 1;
  log.data.analysis_qd.resize(kSamples, 1);
  log.data.analysis_qdd.resize(kSamples, 1);
  log.residual.resize(kSamples);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (Eigen::Index s = 0; s < kSamples; ++s) {
    const double t = kStep * static_cast<double>(s);
    const double amplitude = 0.2 + 1.8 * std::fmod(t / 7.0, 1.0), w = 2 * std::numbers::pi * 0.5;
    const double v = amplitude * std::sin(w * t);
    log.data.analysis_qd(s, 0) = v;
    log.data.analysis_qdd(s, 0) = amplitude * w * std::cos(w * t);
    log.residual[s] = kViscous * v + coulomb * std::tanh(v / 0.01) + noise(random);
  }
  diagnose::Effect viscous;
  viscous.name = viscous.family = "viscous_friction";
  viscous.columns = log.data.analysis_qd;
  viscous.parameters = {"fv1"};
  viscous.joint_of = {0};
  viscous.reading = {diagnose::Reading::as_is};
  log.effects.push_back(viscous);
  return log;
}

struct Errors {
  double value, folds, regimes;
};

Errors fitted(const OneJointLog& log) {
  const Eigen::VectorXd weight = Eigen::VectorXd::Ones(1);
  const Eigen::VectorXd away = Eigen::VectorXd::Ones(log.residual.size());
  const diagnose::Folds folds = diagnose::Folds::even(log.residual.size());
  const auto fit = diagnose::fit_together(log.effects, log.residual, weight, folds, away, away, 1);
  const Eigen::VectorXd regimes = diagnose::regime_error(log.effects, log.residual, weight, folds, away, away, 1,
                                                         diagnose::regime_splits(log.data, away));
  return {fit.theta[0], fit.theta_error[0], regimes[0]};
}

TEST(RegimeError, AModelThatIsRightGetsLittleBeyondTheFoldsSpread) {
  const Errors e = fitted(one_joint_log(0.0));
  EXPECT_NEAR(e.value, kViscous, 2 * e.folds);
  EXPECT_LE(e.regimes, 3 * e.folds + 1e-12);
}

TEST(RegimeError, ABiasEveryFoldSharesIsStated) {
  // An unmodelled Coulomb friction of 0.05 N m pulls the viscous coefficient up by about
  // 0.05 E|v| / E v^2, alike in every block of time: the folds agree with each other, and the
  // truth is many of their errors away. Slow and fast motion disagree: the stated error covers it.
  const Errors e = fitted(one_joint_log(0.05));
  const double miss = std::abs(e.value - kViscous);
  ASSERT_GT(miss, 5 * e.folds) << "the bias the test is about";
  EXPECT_LE(miss, 2 * std::hypot(e.folds, e.regimes));
  EXPECT_LE(e.regimes, 2 * miss) << "stated, not blown up";
}

TEST(RegimeError, AHalfWhereAColumnIsNextToNothingSaysNothingOfIt) {
  // A Stribeck excess that fades over 0.1 rad/s beside the viscous friction, both in the data and
  // in the fit: the model is right. The fast half of the speed split holds next to none of the
  // excess column, so its fit of the excess is not a reading that disagrees.
  constexpr double kExcess = 0.08, kScale = 0.1;
  OneJointLog log = one_joint_log(0.0);
  diagnose::Effect excess = log.effects.front();
  excess.name = excess.family = "stribeck_friction";
  excess.parameters = {"fs1"};
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (Eigen::Index s = 0; s < log.residual.size(); ++s) {
    const double v = log.data.analysis_qd(s, 0);
    excess.columns(s, 0) = std::exp(-(v / kScale) * (v / kScale)) * std::tanh(v / 0.01);
    log.residual[s] = kViscous * v + kExcess * excess.columns(s, 0) + noise(random);
  }
  log.effects.push_back(excess);
  const Eigen::VectorXd weight = Eigen::VectorXd::Ones(1);
  const Eigen::VectorXd away = Eigen::VectorXd::Ones(log.residual.size());
  const diagnose::Folds folds = diagnose::Folds::even(log.residual.size());
  const auto fit = diagnose::fit_together(log.effects, log.residual, weight, folds, away, away, 1);
  const Eigen::VectorXd regimes = diagnose::regime_error(log.effects, log.residual, weight, folds, away, away, 1,
                                                         diagnose::regime_splits(log.data, away));
  // Compared whatever the support, the fast half's fit made the stated error 3e11 N m.
  EXPECT_NEAR(fit.theta[1], kExcess, 3 * fit.theta_error[1]);
  EXPECT_LE(regimes[1], 5 * fit.theta_error[1]) << "fs1 " << fit.theta[1] << " +- " << fit.theta_error[1];
  EXPECT_LE(regimes[0], 3 * fit.theta_error[0] + 1e-12);
}

}  // namespace
}  // namespace dyncc::test
