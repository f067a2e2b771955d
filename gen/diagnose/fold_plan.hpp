// Where the cross-validation's blocks go. Even blocks in time, unless the residual is mostly a
// few short bursts that the even blocks leave in one block: a hook touching a table near a few
// of a Fourier trajectory's lowest points, once or twice a minute. A fit on the other blocks
// then has nothing to learn the touch from, and no effect that explains it can be confirmed held
// out (the Kraft's closed-loop Fourier contacts: 5 of 28 right over the stored bench logs, each
// touch in one or two of the five blocks). The blocks' edges move so that the bursts' energy is
// shared among blocks: first between bursts (whole touches predict each other), and through one
// only when a single burst holds most of it (its two halves predict each other). A log whose
// residual is not dominated by bursts, or whose bursts are already shared, keeps even blocks.
#pragma once

#include <Eigen/Dense>

#include "diagnose/crossval.hpp"

namespace dyncc::diagnose {

/// A burst row: its weighted square residual (over the joints) above kBurstOverMedian times the
/// median row's and above kBurstOfPeak times the largest row's (a small bump beside the touches is
/// not one: alone in a block it would be scored on almost nothing).
inline constexpr double kBurstOverMedian = 100.0;  // 10x the median in amplitude
inline constexpr double kBurstOfPeak = 0.01;       // within 10x of the peak in amplitude
/// The blocks move only when burst rows hold at least this share of the residual's energy and
/// one even block holds more than kBurstShareLimit of theirs.
inline constexpr double kBurstsOfResidual = 0.5;
inline constexpr double kBurstShareLimit = 0.5;
/// An edge may cut through a burst (with kBurstMargin around it) only when no edges between bursts
/// bring the largest block's share to kSingleBurst or below.
inline constexpr double kSingleBurst = 0.8;
inline constexpr double kBurstMargin = 1.0;  // s: a touch's filtered, closed-loop tail
/// Burst rows closer than kBurstMargin are one burst; one longer than this is a stretch (a load
/// carried for 9 s, a joint moving fast for a while), not a touch, and is not counted: its
/// effect is not one-off, and the payload's own window search finds where a load was carried.
inline constexpr double kLongestBurst = 4.0;  // s
/// No block shorter than this share of an even block.
inline constexpr double kShortestBlock = 0.5;

/// The blocks for the stacked `residual` (samples * n rows, joints weighted by `weight`, rows
/// `step` seconds apart).
Folds folds_sharing_bursts(const Eigen::VectorXd& residual, const Eigen::VectorXd& weight, Eigen::Index n, double step);

}  // namespace dyncc::diagnose
