// The logs conditioned for identification and the nominal model evaluated along them: filtered
// positions and their derivatives, filtered torques, the model's torque with the description's
// nominal parameters, its regressors and its sensitivity to the positions. Every later stage
// (effects, fits, the verdict) works on these stacked rows: row s*n + i is joint i at sample s.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "diagnose/joint_log.hpp"
#include "diagnose/signals.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::diagnose {

/// Velocity scale (rad/s) over which Coulomb friction turns over, in the nominal model and in the
/// friction effects alike: the sign of a filtered velocity estimate near zero is noise.
inline constexpr double kSignVelocity = 0.01;

struct ConditioningOptions {
  double cutoff = 0;  // Hz; 0 = automatic, min(rate / 8, 4 Hz)
};

struct Dataset {
  Eigen::Index n = 0;  // joints
  std::vector<std::string> logs;
  std::vector<Audit> audits;
  double cutoff = 0;                // Hz, of the zero-phase filter
  double step = 0;                  // s between the rows kept (after decimation)
  Eigen::VectorXd t;                // S, per log's own clock
  std::vector<int> log_of;          // S: which log
  Eigen::MatrixXd q, qd, qdd, tau;  // S x n, filtered
  Eigen::MatrixXd model_tau;        // S x n, nominal model
  Eigen::MatrixXd model_tau_rate;   // S x n, d model_tau / dt
  Eigen::MatrixXd base_rigid;       // S*n x r': base regressor without friction columns
  std::vector<std::string> base_rigid_names;
  Eigen::MatrixXd standard;              // S*n x p: standard regressor (for the payload link's columns)
  std::vector<Eigen::MatrixXd> dtau_dq;  // S of n x n: d model_tau / dq
  [[nodiscard]] Eigen::Index samples() const { return t.size(); }
  [[nodiscard]] Eigen::VectorXd residual() const;  // stacked tau - model_tau
};

/// Conditions the logs and evaluates the model. Throws LogError when a log is too short for the
/// filter (fewer than kMinimumSamples rows left after the edges are trimmed).
Dataset build_dataset(const std::vector<JointLog>& logs, const pipeline::Derivation& derivation,
                      const ConditioningOptions& options = {});

}  // namespace dyncc::diagnose
