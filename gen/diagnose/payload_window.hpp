// When a load was carried: a payload picked up and put down during a log (the paper's
// experiments) changes the torque only inside a time window, so a payload fitted over the whole
// log explains it half and varies wildly between the folds. The window is found from the data:
// the interval of one log whose gated payload columns explain the most of the nominal residual
// held out (each cross-validation block inside the window predicted by the fit on the window's
// other rows), searched on a coarse grid of the analysis rows and then refined edge by edge to
// single rows. Running sums over time make every window's fit a few k x k solves.
#pragma once

#include <Eigen/Dense>
#include <optional>

#include "diagnose/dataset.hpp"

namespace dyncc::diagnose {

struct PayloadWindow {
  int log = 0;
  Eigen::Index first_row = 0, end_row = 0;  // analysis rows [first_row, end_row)
  double start = 0, end = 0;                // s on the log's clock; -inf / +inf at the log's ends
  double explained = 0;                     // weighted sum of squares the gated fit removes, held out
};

/// The best proper sub-window (not the whole log: that is the constant payload) of any log, for
/// the payload columns `columns` (analysis rows, A*n x k) against `residual` (A*n), joints
/// weighted by `weight` (n), on the stacked rows where `scored` (A*n) is 1. Of windows that
/// explain the same, the narrowest: an edge that could lie anywhere in rows not scored lies at
/// their end nearest the window's inside. Empty when no log has enough rows for a window.
/// `fixed` (A*n x m, or empty): columns fitted over every row beside the load's (the effects
/// accepted before it).
std::optional<PayloadWindow> find_payload_window(const Dataset& d, const Eigen::MatrixXd& columns,
                                                 const Eigen::VectorXd& residual, const Eigen::VectorXd& weight,
                                                 const Eigen::VectorXd& scored,
                                                 const Eigen::MatrixXd& fixed = Eigen::MatrixXd());

/// The payload's columns (evaluation rows, S*n x k) kept only while the load is carried.
Eigen::MatrixXd gated(const Dataset& d, const Eigen::MatrixXd& columns, const PayloadWindow& window);

}  // namespace dyncc::diagnose
