#include "diagnose/regime_error.hpp"

#include <algorithm>
#include <cmath>

#include "diagnose/diagnosis.hpp"

namespace dyncc::diagnose {
namespace {

// The share of a column's weighted sum of squares a split's half must hold for the halves' fits
// of its coefficient to be compared (the slow half of a viscous column holds a few per cent; the
// fast half of a Stribeck excess over 0.1 rad/s, 2e-5 on the bench's seed 79 case 33).
constexpr double kLeastSupport = 0.01;

// The moving samples below / above the median of sum_j (x_sj / rms_j)^2, as stacked row masks;
// the samples at rest (no joint away from zero velocity) in both halves. A tele-operated arm rests
// most of the time: split with the others, the rest would make up the slow half alone, whose fit
// (gravity at a few postures) cannot tell a load's mass from its moment and moves by 20 %.
RegimeSplit split_by(const Eigen::MatrixXd& x, const Eigen::VectorXd& away) {
  const Eigen::Index samples = x.rows(), n = x.cols();
  std::vector<bool> moving(static_cast<std::size_t>(samples), false);
  for (Eigen::Index s = 0; s < samples; ++s)
    moving[static_cast<std::size_t>(s)] = away.segment(s * n, n).maxCoeff() > 0;
  const Eigen::VectorXd rms = x.array().square().colwise().mean().sqrt().transpose();
  Eigen::VectorXd measure = Eigen::VectorXd::Zero(samples);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (rms[j] > 0) measure += (x.col(j) / rms[j]).array().square().matrix();
  }
  std::vector<double> sorted;
  for (Eigen::Index s = 0; s < samples; ++s) {
    if (moving[static_cast<std::size_t>(s)]) sorted.push_back(measure[s]);
  }
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  const double median = sorted.empty() ? 0.0 : *middle;
  RegimeSplit out{Eigen::VectorXd::Zero(samples * n), Eigen::VectorXd::Zero(samples * n)};
  for (Eigen::Index s = 0; s < samples; ++s) {
    const bool at_rest = !moving[static_cast<std::size_t>(s)];
    if (at_rest || measure[s] < median) out.lower.segment(s * n, n).setOnes();
    if (at_rest || measure[s] >= median) out.upper.segment(s * n, n).setOnes();
  }
  return out;
}

}  // namespace

std::vector<RegimeSplit> regime_splits(const Dataset& d, const Eigen::VectorXd& away) {
  return {split_by(d.analysis_qd, away), split_by(d.analysis_qdd, away)};  // speed, acceleration
}

Eigen::VectorXd regime_error(const std::vector<Effect>& effects, const Eigen::VectorXd& residual,
                             const Eigen::VectorXd& weight, const Folds& folds, const Eigen::VectorXd& away,
                             const Eigen::VectorXd& far, Eigen::Index n, const std::vector<RegimeSplit>& splits) {
  const FittedColumns fitted = fitted_columns(effects, away);
  const Eigen::Index columns = fitted.all.cols();
  const Eigen::MatrixXd squares = fitted.all.cwiseProduct(fitted.fitted).array().square().matrix();  // as fitted
  const Eigen::VectorXd w2 = stacked_weights(weight, residual.size()).array().square();
  const Eigen::RowVectorXd whole = w2.transpose() * squares;
  Eigen::VectorXd error = Eigen::VectorXd::Zero(columns);
  for (const RegimeSplit& split : splits) {
    const CrossValidation lower = fit_together(effects, residual, weight, folds, away, far, n, &split.lower);
    const CrossValidation upper = fit_together(effects, residual, weight, folds, away, far, n, &split.upper);
    const Eigen::RowVectorXd in_lower = w2.cwiseProduct(split.lower).transpose() * squares;
    const Eigen::RowVectorXd in_upper = w2.cwiseProduct(split.upper).transpose() * squares;
    for (Eigen::Index k = 0; k < columns; ++k) {
      // A half where the column is next to nothing says nothing about its coefficient (a
      // Stribeck excess, which fades within a few tenths of a rad/s, in the fast half): its fit
      // there is not a reading of it, and the halves' difference no bias (79/33: fs1 0.163 +-
      // 0.32, the fast half's fit 0.81 +- 0.10; now +- 0.003 for a truth of 0.1663).
      if (std::min(in_lower[k], in_upper[k]) < kLeastSupport * whole[k]) continue;
      const double half = 0.5 * (upper.theta[k] - lower.theta[k]);
      const double noise = 0.5 * std::hypot(upper.theta_error[k], lower.theta_error[k]);
      const double beyond = half * half - noise * noise;
      if (std::isfinite(beyond) && beyond > 0) error[k] = std::max(error[k], std::sqrt(beyond));
    }
  }
  return error;
}

}  // namespace dyncc::diagnose
