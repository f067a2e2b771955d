// Effects that show as the measured positions being off the link's by a shift theta_j * w_j(t):
// a constant offset (w = 1), an elastic transmission read on the motor side (w = the joint torque,
// theta = 1 / stiffness), a backlash (w = half the sign of the torque, theta = the width). The
// logged torque is the model's at the link's trajectory, so the residual is the model's change
// when the positions AND their filtered velocity and acceleration move by the shift: a torque
// that swings makes w swing, and the acceleration error it brings (H times w'') is as large as the
// position error on joints whose torque is dynamic. The columns are that change per unit theta,
// evaluated through the model itself, then re-linearised as secants at a first fit (exact at that
// shift) where the shift is large.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/effects.hpp"

namespace dyncc::diagnose {

/// The shift pattern w_j(t) on the evaluation rows (S x n), as the positions saw it: through the
/// same zero-phase low-pass, with its first and second derivatives.
struct Shift {
  Eigen::MatrixXd w, wd, wdd;
};
Shift filtered_shift(const Dataset& d, const Eigen::MatrixXd& raw);

/// The nominal model's torque without its friction along the evaluation rows and its
/// derivatives by each joint's position, velocity and acceleration there: what the
/// tangents of every shift are made of, computed once for all the shift effects.
struct ModelSensitivity {
  Eigen::MatrixXd tau;  // S x n
  // S x n: what a transmission between motor and link carries, the logged torque less the
  // description's friction (Coulomb through the smoothed sign, viscous) at the estimated velocity:
  // the drive's friction acts on the motor side.
  Eigen::MatrixXd transmitted;
  std::vector<Eigen::MatrixXd> by_qd, by_qdd;  // S of n x n (by position: Dataset::dtau_dq)
};
ModelSensitivity model_sensitivity(const Dataset& d, const pipeline::Derivation& derivation);

/// Per unit theta, the model's change when the positions move by -theta w_j (with the filtered
/// velocity and acceleration): S*n x n on the evaluation rows, not conditioned. Column j is the
/// tangent of a shift of joint j; linear in the shift pattern.
Eigen::MatrixXd shift_tangents(const Dataset& d, const ModelSensitivity& m, const Shift& shift);

/// The effect's columns (S*n x n, conditioned into the analysis rows) for the shift pattern:
/// column j is (model at positions - theta_j w_j) - (model) over theta_j: the tangent first, then,
/// twice, the secant at the fitted theta_j where the largest shift exceeds 0.01 rad. Sets
/// effect.secant_at, which makes a column again at another theta (the final joint fit's).
void fit_shift_columns(const Dataset& d, const pipeline::Derivation& derivation, const ModelSensitivity& m,
                       const Shift& shift, Effect& effect);

/// The sensor delay's column (S*n x 1, conditioned), for positions measured late by a delay d: the
/// torque is the model's d later. Its tangent, d times d model_tau / dt, misses the third-order
/// term, which pulls the fit of a delay of a few filter-period hundredths short by d^3 w^2 / 6
/// (a 36 ms delay on 2 Hz motion read 1 ms short): so twice, where the fitted delay is over
/// 0.5 rad of phase at the filter's cut-off (20 ms at 4 Hz), the secant at the fitted delay,
/// (model_tau(t + d) - model_tau(t)) / d, with the model's torque shifted in time by cubic Hermite
/// interpolation between evaluation rows (its rate is their slope).
void fit_delay_column(const Dataset& d, Effect& effect);

/// Whether a delay is long enough for the secant (over 0.5 rad of phase at the filter's cut-off).
bool delay_needs_secant(const Dataset& d, double delay);
/// The sensor delay's secant column at `delay` (S*n x 1, conditioned), as fit_delay_column makes it.
Eigen::MatrixXd delay_secant(const Dataset& d, double delay);

/// A column of the analysis rows (A*n) advanced in time by `lead` seconds along each log's rows:
/// cubic Hermite between them, with central differences as the slopes; a row whose time plus
/// `lead` falls outside its log keeps its own value. The analysis rows are eight per period of the
/// filter's cut-off, so a conditioned column is smooth between them.
Eigen::VectorXd advanced_in_time(const Dataset& d, const Eigen::VectorXd& column, double lead);

}  // namespace dyncc::diagnose
