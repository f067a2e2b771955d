// The systematic part of a fitted parameter's error: how far the fit moves between regimes of the
// motion. The folds' spread (the jackknife over blocks in time) measures the log's noise; it does
// not see a bias that every block shares (a filter lag, a friction that is not quite the model's,
// a second effect not in the fit), and on the blind bench only 73 % of fits held the truth within
// two of those errors. A model that is right reads the same parameter at slow and fast motion, at
// small and large acceleration; where the halves disagree by more than their own noise, that
// disagreement is a bias the fit carries, and it is added to the stated error.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/effects.hpp"

namespace dyncc::diagnose {

/// Two halves of the analysis rows (stacked masks, 1 on the rows of the half): the samples below
/// and above the median of a measure of the motion.
struct RegimeSplit {
  Eigen::VectorXd lower, upper;
};

/// The splits by speed and by acceleration (each joint's share scaled by its RMS) of the samples
/// where some joint moves (`away`, stacked: away from zero velocity); the others are in both halves.
std::vector<RegimeSplit> regime_splits(const Dataset& d, const Eigen::VectorXd& away);

/// Per column of the effects fitted together: the largest over the splits of half the difference
/// between the two halves' fits, less (in quadrature) what the halves' own fold spreads explain;
/// 0 where the halves agree within their noise.
Eigen::VectorXd regime_error(const std::vector<Effect>& effects, const Eigen::VectorXd& residual,
                             const Eigen::VectorXd& weight, const Folds& folds, const Eigen::VectorXd& away,
                             const Eigen::VectorXd& far, Eigen::Index n, const std::vector<RegimeSplit>& splits);

}  // namespace dyncc::diagnose
