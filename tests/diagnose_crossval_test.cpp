// Blocked cross-validation (gen/diagnose/crossval) against fits made independently: each fold's
// parameters are the weighted least-squares fit on the other folds' rows alone, solved by a QR
// decomposition of those rows (not through normal matrices, which the diagnosis accumulates once
// over the rows and subtracts a fold's block from).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "diagnose/crossval.hpp"

namespace dyncc::test {
namespace {

struct Problem {
  Eigen::Index joints = 3, samples = 101, columns = 4;  // 101: the folds are not all alike long
  Eigen::MatrixXd E, F;
  Eigen::VectorXd r, weight;
};

Problem random_problem() {
  Problem p;
  std::mt19937 random(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Index rows = p.joints * p.samples;
  p.E = Eigen::MatrixXd::NullaryExpr(rows, p.columns, [&]() { return normal(random); });
  p.E.col(2) *= 1e3;  // columns of very different sizes, as a payload's and a friction's are
  p.E.col(3) *= 1e-3;
  p.F = p.E;
  p.F.bottomRows(rows / 2).col(1).setZero();  // a column fitted on the first half only
  p.r = Eigen::VectorXd::NullaryExpr(rows, [&]() { return normal(random); });
  p.weight = Eigen::Vector3d(1.0, 0.5, 4.0);
  return p;
}

// The weighted least-squares fit of r ~ F theta on samples outside [begin, end), by QR.
Eigen::VectorXd fit_outside(const Problem& p, const Eigen::MatrixXd& F, Eigen::Index begin, Eigen::Index end) {
  const Eigen::Index train = p.samples - (end - begin);
  Eigen::MatrixXd a(train * p.joints, p.columns);
  Eigen::VectorXd b(train * p.joints);
  Eigen::Index row = 0;
  for (Eigen::Index s = 0; s < p.samples; ++s) {
    if (s >= begin && s < end) continue;
    for (Eigen::Index j = 0; j < p.joints; ++j, ++row) {
      a.row(row) = p.weight[j] * F.row(s * p.joints + j);
      b[row] = p.weight[j] * p.r[s * p.joints + j];
    }
  }
  return a.colPivHouseholderQr().solve(b);
}

void expect_near_relative(const Eigen::VectorXd& got, const Eigen::VectorXd& want) {
  for (Eigen::Index k = 0; k < want.size(); ++k) {
    EXPECT_NEAR(got[k], want[k], 1e-7 * std::max(1.0, std::abs(want[k]))) << "parameter " << k;
  }
}

// Each fold's parameters are the QR fit on `fitted_on`'s other folds' rows, and its held-out
// residual is what those parameters leave on its own rows, predicted with E.
void expect_folds_fitted_outside(const Problem& p, const Eigen::MatrixXd& fitted_on, const diagnose::Folds& folds,
                                 const diagnose::CrossValidation& cv) {
  ASSERT_EQ(cv.fold_end.size(), static_cast<std::size_t>(diagnose::kFolds));
  Eigen::Index begin = 0;
  for (int f = 0; f < diagnose::kFolds; ++f) {
    const Eigen::Index end = cv.fold_end[static_cast<std::size_t>(f)];
    EXPECT_EQ(end, folds.end_of(f));
    const Eigen::VectorXd theta = fit_outside(p, fitted_on, begin, end);
    expect_near_relative(cv.theta_folds.col(f), theta);
    const Eigen::Index rows = (end - begin) * p.joints;
    const Eigen::VectorXd left = p.r.segment(begin * p.joints, rows) - p.E.middleRows(begin * p.joints, rows) * theta;
    EXPECT_LT((cv.heldout.segment(begin * p.joints, rows) - left).norm(), 1e-9 * left.norm());
    begin = end;
  }
}

TEST(DiagnoseCrossValidation, EachFoldIsTheLeastSquaresFitOnTheOtherFolds) {
  const Problem p = random_problem();
  const diagnose::Folds folds = diagnose::Folds::even(p.samples);
  const diagnose::CrossValidation cv = diagnose::cross_validate(p.r, p.E, p.joints, p.weight, folds);
  expect_folds_fitted_outside(p, p.E, folds, cv);
  expect_near_relative(cv.theta, fit_outside(p, p.E, 0, 0));
  // The jackknife error from the folds' spread.
  const Eigen::VectorXd mean = cv.theta_folds.rowwise().mean();
  for (Eigen::Index k = 0; k < p.columns; ++k) {
    const double spread = (cv.theta_folds.row(k).transpose().array() - mean[k]).square().sum();
    EXPECT_NEAR(cv.theta_error[k], std::sqrt(spread * (diagnose::kFolds - 1) / diagnose::kFolds),
                1e-12 * std::max(1.0, cv.theta_error[k]));
  }
}

// With `fitted_on`, the folds fit on its columns and predict with E's.
TEST(DiagnoseCrossValidation, FitsOnOneMatrixAndPredictsWithTheOther) {
  const Problem p = random_problem();
  const diagnose::Folds folds = diagnose::Folds::even(p.samples);
  const diagnose::CrossValidation cv = diagnose::cross_validate(p.r, p.E, p.joints, p.weight, folds, &p.F);
  expect_folds_fitted_outside(p, p.F, folds, cv);
}

// Blocks of unequal length (where fold_plan places them) are held out just the same.
TEST(DiagnoseCrossValidation, BlocksOfUnequalLengthAreEachFittedOnTheOthers) {
  const Problem p = random_problem();
  const diagnose::Folds even = diagnose::Folds::even(p.samples);
  diagnose::Folds folds = even;
  folds.begin[1] = even.begin[1] / 2;
  folds.begin[3] = (even.begin[3] + even.begin[4]) / 2;
  ASSERT_NE(folds, even);
  const diagnose::CrossValidation cv = diagnose::cross_validate(p.r, p.E, p.joints, p.weight, folds, &p.F);
  expect_folds_fitted_outside(p, p.F, folds, cv);
}

// Errors in variables, with the closed forms of the textbook case: y = theta x + beta z + e, the
// first column measured as c = x + a e + v (its noise partly the target's own, as a spring's
// column made from the logged torque is). Least squares reads theta as
// (theta var x + a var e) / (var x + a^2 var e + var v); with draws of the noise (a e + v, e)
// taken off its normal equations it reads theta itself. The clean column's beta is unbiased
// either way.
struct ErrorsInVariables {
  Eigen::VectorXd y;
  Eigen::MatrixXd E;
  diagnose::NoiseDraws noise;
};

ErrorsInVariables errors_in_variables(double theta, double beta, double a, double sigma_e, double sigma_v) {
  constexpr Eigen::Index kRows = 40000;
  constexpr int kDraws = 40;
  std::mt19937 random(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto draw = [&](double sigma) {
    return Eigen::VectorXd(Eigen::VectorXd::NullaryExpr(kRows, [&]() { return sigma * normal(random); }));
  };
  const Eigen::VectorXd x = draw(1.0), z = draw(1.0), e = draw(sigma_e), v = draw(sigma_v);
  ErrorsInVariables p;
  p.y = theta * x + beta * z + e;
  p.E.resize(kRows, 2);
  p.E << x + a * e + v, z;
  p.noise.at = {0};
  for (int m = 0; m < kDraws; ++m) {
    const Eigen::VectorXd target = draw(sigma_e), own = draw(sigma_v);
    p.noise.columns.emplace_back(a * target + own);
    p.noise.target.push_back(target);
  }
  return p;
}

TEST(DiagnoseCrossValidation, NoiseDrawsTakeTheErrorsInVariablesBiasOff) {
  const double theta = 2.0, beta = -0.7, a = -1.0, sigma_e = 0.5, sigma_v = 0.5;
  const ErrorsInVariables p = errors_in_variables(theta, beta, a, sigma_e, sigma_v);
  const Eigen::VectorXd weight = Eigen::VectorXd::Ones(1);
  const double biased = (theta + a * sigma_e * sigma_e) / (1.0 + a * a * sigma_e * sigma_e + sigma_v * sigma_v);
  const diagnose::CrossValidation plain =
      diagnose::cross_validate(p.y, p.E, 1, weight, diagnose::Folds::even(p.y.size()));
  EXPECT_NEAR(plain.theta[0], biased, 0.03);  // 1.167: the bias is real
  EXPECT_NEAR(plain.theta[1], beta, 0.03);
  const diagnose::CrossValidation corrected =
      diagnose::cross_validate(p.y, p.E, 1, weight, diagnose::Folds::even(p.y.size()), nullptr, &p.noise);
  EXPECT_NEAR(corrected.theta[0], theta, 0.05);
  EXPECT_NEAR(corrected.theta[1], beta, 0.03);
  for (int f = 0; f < diagnose::kFolds; ++f) EXPECT_NEAR(corrected.theta_folds(0, f), theta, 0.1) << "fold " << f;
  // Each fold predicts its own rows with its corrected fit.
  const Eigen::Index rows = p.y.size() / diagnose::kFolds;
  const Eigen::VectorXd left = p.y.head(rows) - p.E.topRows(rows) * corrected.theta_folds.col(0);
  EXPECT_LT((corrected.heldout.head(rows) - left).norm(), 1e-9 * left.norm());
}

// Where the noise is most of the column (its expected square over kLargestNoiseShare of the
// column's), the correction would divide by what is left of the noise's estimate: the plain fit.
TEST(DiagnoseCrossValidation, NoiseThatSwampsAColumnLeavesThePlainFit) {
  const ErrorsInVariables p = errors_in_variables(2.0, -0.7, -1.0, 0.5, 1.2);
  const Eigen::VectorXd weight = Eigen::VectorXd::Ones(1);
  const diagnose::CrossValidation plain =
      diagnose::cross_validate(p.y, p.E, 1, weight, diagnose::Folds::even(p.y.size()));
  const diagnose::CrossValidation corrected =
      diagnose::cross_validate(p.y, p.E, 1, weight, diagnose::Folds::even(p.y.size()), nullptr, &p.noise);
  EXPECT_EQ(corrected.theta, plain.theta);
  EXPECT_EQ(corrected.heldout, plain.heldout);
}

}  // namespace
}  // namespace dyncc::test
