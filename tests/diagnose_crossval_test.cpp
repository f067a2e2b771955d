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
void expect_folds_fitted_outside(const Problem& p, const Eigen::MatrixXd& fitted_on,
                                 const diagnose::CrossValidation& cv) {
  ASSERT_EQ(cv.fold_end.size(), static_cast<std::size_t>(diagnose::kFolds));
  Eigen::Index begin = 0;
  for (int f = 0; f < diagnose::kFolds; ++f) {
    const Eigen::Index end = cv.fold_end[static_cast<std::size_t>(f)];
    EXPECT_EQ(end, diagnose::fold_begin(p.samples, f + 1));
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
  const diagnose::CrossValidation cv = diagnose::cross_validate(p.r, p.E, p.joints, p.weight);
  expect_folds_fitted_outside(p, p.E, cv);
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
  const diagnose::CrossValidation cv = diagnose::cross_validate(p.r, p.E, p.joints, p.weight, &p.F);
  expect_folds_fitted_outside(p, p.F, cv);
}

}  // namespace
}  // namespace dyncc::test
