// Blocked cross-validation in time: the rows are cut into K contiguous blocks; each block is
// predicted by a least-squares fit on the others, so every reported error is on data the fit
// never saw (contiguous blocks, because neighbouring samples of a filtered log are not
// independent).
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace dyncc::diagnose {

inline constexpr int kFolds = 5;

/// The first sample of block f (0 <= f <= kFolds; block f is [fold_begin(f), fold_begin(f + 1))):
/// K contiguous blocks of nearly equal length over `samples`.
inline Eigen::Index fold_begin(Eigen::Index samples, int f) { return samples * f / kFolds; }

struct CrossValidation {
  Eigen::VectorXd heldout;             // S*n: the residual left on each row when its block was held out
  Eigen::VectorXd theta;               // fitted on all rows
  Eigen::VectorXd theta_error;         // standard error from the spread over the K fits (jackknife)
  Eigen::MatrixXd theta_folds;         // k x K
  std::vector<Eigen::Index> fold_end;  // sample index where each block ends
};

/// Fits r ~ E theta (columns scaled to unit norm, a tiny ridge for collinear columns) with
/// rows weighted per joint (weight[j] for joint j's rows), K times on K-1 blocks.
/// With `fitted_on` (same shape as E), the fits use its columns and the predictions E's: a column
/// can be fitted on some rows only (zero elsewhere in `fitted_on`) and still predict on all.
CrossValidation cross_validate(const Eigen::VectorXd& r, const Eigen::MatrixXd& E, Eigen::Index joints,
                               const Eigen::VectorXd& weight, const Eigen::MatrixXd* fitted_on = nullptr);

/// Per-joint RMS of stacked rows (row s*n + j), over samples [begin, end).
Eigen::VectorXd joint_rms(const Eigen::VectorXd& stacked, Eigen::Index joints, Eigen::Index begin = 0,
                          Eigen::Index end = -1);

}  // namespace dyncc::diagnose
