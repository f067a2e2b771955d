// The gap stage: how large the nominal model's held-out residual is on each joint against the
// floors it cannot go below (the torque's noise, the positions' noise through the model, the
// friction's sign at reversals), and where it lies (time windows well above its usual level,
// regimes of motion). The diagnosis' none/unknown test and the report read it.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "diagnose/dataset.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::diagnose {

struct Window {
  int log = 0;
  double start = 0, end = 0;  // s, the log's clock
  double rms_ratio = 0;       // window RMS / median window RMS
};

struct Regime {
  std::string name;       // "near_zero_velocity", "reversal", "high_acceleration", "other"
  Eigen::VectorXd rms;    // per joint
  Eigen::VectorXd share;  // per joint: fraction of the samples in this regime
};

struct Gap {
  Eigen::VectorXd torque_rms, residual_rms, percent, noise_floor;  // per joint
  Eigen::VectorXd sign_floor;           // per joint: the model friction's uncertainty at reversals (see gap.cpp)
  Eigen::VectorXd position_floor;       // per joint: the rigid model's answer to the positions' noise (dataset.hpp)
  Eigen::VectorXd position_resolution;  // per joint: the larger of the positions' quantum and noise
  std::vector<Window> windows;          // flagged time windows (residual well above its usual level)
  std::vector<Regime> regimes;
};

/// The gap of the held-out residual `heldout` (stacked rows of the analysis samples).
Gap locate_gap(const Dataset& d, const Eigen::VectorXd& heldout, const pipeline::Derivation& derivation);

}  // namespace dyncc::diagnose
