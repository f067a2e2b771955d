// Signal conditioning for identification from position-only logs: a uniform time grid, a
// zero-phase low-pass (Butterworth, forward and backward), derivatives of the filtered positions,
// and the audit of what the log itself says about its sampling and noise.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "diagnose/joint_log.hpp"

namespace dyncc::diagnose {

/// Second-order Butterworth low-pass run forward then backward: zero phase, |H|^2 of fourth
/// order. `cutoff` in Hz, `rate` the sample rate in Hz. Edges padded by odd reflection so a
/// ramp passes through without a transient.
Eigen::VectorXd zero_phase_lowpass(const Eigen::VectorXd& x, double cutoff, double rate);

/// Central differences (one-sided at the ends) on a uniform grid.
Eigen::VectorXd derivative(const Eigen::VectorXd& x, double dt);

/// Linear interpolation of the columns of `values` (at times `t`) onto `grid`.
Eigen::MatrixXd interpolate(const Eigen::VectorXd& t, const Eigen::MatrixXd& values, const Eigen::VectorXd& grid);

/// The share of the rows of each column that have the column's less common sign (how much of the
/// time a joint's torque has turned over).
Eigen::VectorXd minority_sign_share(const Eigen::MatrixXd& values);

struct JointAudit {
  double quantum = 0;         // position quantisation step (rad or m); 0 = none detected
  double position_noise = 0;  // std of position noise (sample to sample)
  double torque_noise = 0;    // std of torque noise (sample to sample)
};

struct Audit {
  double rate = 0;         // Hz, from the median interval
  double jitter = 0;       // std of the interval / median interval
  double largest_gap = 0;  // largest interval / median interval
  Eigen::Index samples = 0;
  double duration = 0;  // s
  std::vector<JointAudit> joints;
};

Audit audit_log(const JointLog& log);

}  // namespace dyncc::diagnose
