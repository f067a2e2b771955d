#include "diagnose/crossval.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace dyncc::diagnose {
namespace {

constexpr double kRidge = 1e-9;  // relative to the scaled normal matrix's unit diagonal

// A least-squares fit from its normal equations, the columns scaled by `scale` (1 / their norms
// over all rows, not over the training rows: a column that is nearly zero where a fold trains, a
// load carried only in the held-out stretch, is then held near zero by the ridge instead of being
// blown up to unit size and predicting nonsense).
Eigen::VectorXd solve(const Eigen::MatrixXd& normal, const Eigen::VectorXd& moment, const Eigen::VectorXd& scale) {
  Eigen::MatrixXd scaled = scale.asDiagonal() * normal * scale.asDiagonal();
  scaled.diagonal().array() += kRidge;
  const Eigen::VectorXd x = scaled.ldlt().solve(scale.asDiagonal() * moment);
  return scale.asDiagonal() * x;
}

// Block `begin`..`end` (samples)'s expected noise share of the normal matrix and moment, over the
// draws, weighted as the rows are, added at the noisy columns.
void add_noise_share(const NoiseDraws& noise, Eigen::Index joints, const Eigen::VectorXd& weight, Eigen::Index begin,
                     Eigen::Index end, Eigen::MatrixXd& normal, Eigen::VectorXd& moment) {
  const Eigen::Index rows = (end - begin) * joints, k = static_cast<Eigen::Index>(noise.at.size());
  if (rows <= 0) return;
  const Eigen::VectorXd w = weight.replicate(end - begin, 1);
  const double share = 1.0 / static_cast<double>(noise.columns.size());
  Eigen::MatrixXd nn = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd ny = Eigen::VectorXd::Zero(k);
  for (std::size_t m = 0; m < noise.columns.size(); ++m) {
    const Eigen::MatrixXd block = w.asDiagonal() * noise.columns[m].middleRows(begin * joints, rows);
    nn += share * block.transpose() * block;
    ny += share * block.transpose() * w.cwiseProduct(noise.target[m].segment(begin * joints, rows));
  }
  for (Eigen::Index a = 0; a < k; ++a) {
    moment[noise.at[static_cast<std::size_t>(a)]] += ny[a];
    for (Eigen::Index b = 0; b < k; ++b) {
      normal(noise.at[static_cast<std::size_t>(a)], noise.at[static_cast<std::size_t>(b)]) += nn(a, b);
    }
  }
}

}  // namespace

Eigen::VectorXd joint_rms(const Eigen::VectorXd& stacked, Eigen::Index joints, Eigen::Index begin, Eigen::Index end) {
  const Eigen::Index samples = stacked.size() / joints;
  if (end < 0) end = samples;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(joints);
  for (Eigen::Index s = begin; s < end; ++s) {
    for (Eigen::Index j = 0; j < joints; ++j) sum[j] += stacked[s * joints + j] * stacked[s * joints + j];
  }
  return (sum / static_cast<double>(std::max<Eigen::Index>(1, end - begin))).cwiseSqrt();
}

CrossValidation cross_validate(const Eigen::VectorXd& r, const Eigen::MatrixXd& E, Eigen::Index joints,
                               const Eigen::VectorXd& weight, const Folds& folds, const Eigen::MatrixXd* fitted_on,
                               const NoiseDraws* noise) {
  const Eigen::Index k = E.cols();
  assert(folds.begin_of(0) == 0 && folds.end_of(kFolds - 1) * joints == r.size());  // the blocks cover the rows
  const Eigen::MatrixXd& F = fitted_on != nullptr ? *fitted_on : E;
  CrossValidation cv;
  cv.heldout = r;
  cv.theta_folds.resize(k, kFolds);
  // One pass over the rows: each block's weighted normal matrix and moment. A fold trains on the
  // sums less its own block's (the rows are read once, not copied and multiplied K + 1 times).
  std::vector<Eigen::MatrixXd> normal(kFolds);
  std::vector<Eigen::VectorXd> moment(kFolds);
  Eigen::MatrixXd all_normal = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd all_moment = Eigen::VectorXd::Zero(k);
  for (int f = 0; f < kFolds; ++f) {
    const Eigen::Index begin = folds.begin_of(f), end = folds.end_of(f);
    cv.fold_end.push_back(end);
    normal[f] = Eigen::MatrixXd::Zero(k, k);
    moment[f] = Eigen::VectorXd::Zero(k);
    const Eigen::Index rows = (end - begin) * joints;
    if (rows > 0) {  // (a log shorter than the folds leaves a block empty)
      Eigen::MatrixXd block = F.middleRows(begin * joints, rows);  // row s * joints + j weighted by weight[j]
      Eigen::VectorXd target = r.segment(begin * joints, rows);
      for (Eigen::Index i = 0; i < rows; ++i) {
        block.row(i) *= weight[i % joints];
        target[i] *= weight[i % joints];
      }
      normal[f] = block.transpose() * block;
      moment[f] = block.transpose() * target;
    }
    all_normal += normal[f];
    all_moment += moment[f];
  }
  Eigen::VectorXd scale(k);
  for (Eigen::Index c = 0; c < k; ++c) {
    const double norm_squared = all_normal(c, c);
    scale[c] = norm_squared > 0 ? 1.0 / std::sqrt(norm_squared) : 0.0;
  }
  if (noise != nullptr && !noise->at.empty()) {
    std::vector<Eigen::MatrixXd> noise_normal(kFolds, Eigen::MatrixXd::Zero(k, k));
    std::vector<Eigen::VectorXd> noise_moment(kFolds, Eigen::VectorXd::Zero(k));
    Eigen::MatrixXd all_noise = Eigen::MatrixXd::Zero(k, k);
    for (int f = 0; f < kFolds; ++f) {
      add_noise_share(*noise, joints, weight, folds.begin_of(f), folds.end_of(f), noise_normal[f], noise_moment[f]);
      all_noise += noise_normal[f];
    }
    const bool swamped = std::any_of(noise->at.begin(), noise->at.end(), [&](Eigen::Index c) {
      return all_noise(c, c) > kLargestNoiseShare * all_normal(c, c);
    });
    for (int f = 0; f < kFolds && !swamped; ++f) {
      normal[f] -= noise_normal[f];
      moment[f] -= noise_moment[f];
      all_normal -= noise_normal[f];
      all_moment -= noise_moment[f];
    }
  }
  for (int f = 0; f < kFolds; ++f) {
    const Eigen::Index begin = folds.begin_of(f), end = folds.end_of(f);
    const Eigen::VectorXd theta = solve(all_normal - normal[f], all_moment - moment[f], scale);
    cv.theta_folds.col(f) = theta;
    cv.heldout.segment(begin * joints, (end - begin) * joints) -=
        E.middleRows(begin * joints, (end - begin) * joints) * theta;
  }
  cv.theta = solve(all_normal, all_moment, scale);
  cv.theta_error = jackknife_error(cv.theta_folds);
  return cv;
}

Eigen::VectorXd jackknife_error(const Eigen::MatrixXd& per_fold) {
  const auto k = static_cast<double>(per_fold.cols());
  const Eigen::VectorXd mean = per_fold.rowwise().mean();
  return ((per_fold.colwise() - mean).array().square().rowwise().sum() * ((k - 1) / k)).sqrt();
}

}  // namespace dyncc::diagnose
