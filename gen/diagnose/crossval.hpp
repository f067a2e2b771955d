// Blocked cross-validation in time: the rows are cut into K contiguous blocks; each block is
// predicted by a least-squares fit on the others, so every reported error is on data the fit
// never saw (contiguous blocks, because neighbouring samples of a filtered log are not
// independent). Where the blocks begin is the caller's (Folds; fold_plan.hpp places them).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

namespace dyncc::diagnose {

inline constexpr int kFolds = 5;

/// Where the K contiguous blocks of the samples begin: block f is [begin[f], begin[f + 1]), with
/// begin[0] = 0 and begin[kFolds] = the number of samples.
struct Folds {
  std::array<Eigen::Index, kFolds + 1> begin{};
  /// K blocks of nearly equal length over `samples`.
  static Folds even(Eigen::Index samples) {
    Folds folds;
    for (int f = 0; f <= kFolds; ++f) folds.begin[static_cast<std::size_t>(f)] = samples * f / kFolds;
    return folds;
  }
  [[nodiscard]] Eigen::Index begin_of(int f) const { return begin[static_cast<std::size_t>(f)]; }
  [[nodiscard]] Eigen::Index end_of(int f) const { return begin[static_cast<std::size_t>(f) + 1]; }
  bool operator==(const Folds&) const = default;
};

struct CrossValidation {
  Eigen::VectorXd heldout;             // S*n: the residual left on each row when its block was held out
  Eigen::VectorXd theta;               // fitted on all rows
  Eigen::VectorXd theta_error;         // standard error from the spread over the K fits (jackknife)
  Eigen::MatrixXd theta_folds;         // k x K
  std::vector<Eigen::Index> fold_end;  // sample index where each block ends
};

/// Draws of the noise that some columns share with the target (errors in variables): per draw,
/// those columns' noise (rows x at.size(), masked as the columns are fitted) and the target's. A
/// column made from the noisy target (a spring's, from the logged torque it carries) has a noise
/// part whose square biases its coefficient toward zero and whose product with the target's noise
/// biases it away; their expected values over the draws, taken off the normal equations, leave
/// an unbiased fit (corrected least squares).
struct NoiseDraws {
  std::vector<Eigen::Index> at;          // the columns of E the draws belong to
  std::vector<Eigen::MatrixXd> columns;  // per draw
  std::vector<Eigen::VectorXd> target;   // per draw
};

/// The jackknife standard error of each row's estimate from its K fold fits (rows x K, each fit
/// on K-1 blocks): sqrt((K-1)/K sum (x_f - mean)^2), as CrossValidation::theta_error states it.
Eigen::VectorXd jackknife_error(const Eigen::MatrixXd& per_fold);

/// Fits r ~ E theta (columns scaled to unit norm, a tiny ridge for collinear columns) with
/// rows weighted per joint (weight[j] for joint j's rows), K times on K-1 blocks (`folds`, over
/// the samples r.size() / joints).
/// With `fitted_on` (same shape as E), the fits use its columns and the predictions E's: a column
/// can be fitted on some rows only (zero elsewhere in `fitted_on`) and still predict on all.
/// With `noise`, each fit's normal equations lose the noise's expected share (NoiseDraws), unless
/// on some noisy column it is over kLargestNoiseShare of the column's square (the noise then
/// swamps what the column says, and the plain fit is returned).
inline constexpr double kLargestNoiseShare = 0.5;
CrossValidation cross_validate(const Eigen::VectorXd& r, const Eigen::MatrixXd& E, Eigen::Index joints,
                               const Eigen::VectorXd& weight, const Folds& folds,
                               const Eigen::MatrixXd* fitted_on = nullptr, const NoiseDraws* noise = nullptr);

/// Per-joint RMS of stacked rows (row s*n + j), over samples [begin, end).
Eigen::VectorXd joint_rms(const Eigen::VectorXd& stacked, Eigen::Index joints, Eigen::Index begin = 0,
                          Eigen::Index end = -1);

}  // namespace dyncc::diagnose
