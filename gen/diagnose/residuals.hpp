// The selected effects refitted together on every analysis row, for the report's figures: the
// held-out residual left with all of them (what Diagnosis::final_after measures) and each
// effect's fitted part of the residual, so that a figure can show the residual an effect
// explains beside the effect itself.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"

namespace dyncc::diagnose {

struct EffectFit {
  std::string effect;                   // the effect fitted: the first of "A or B"
  std::vector<int> joints;              // 1-based, where the diagnosis places it
  std::vector<std::string> parameters;  // per column, e.g. "fc2"
  std::vector<int> joint_of;            // per column: its joint (0-based), -1 shared
  Eigen::VectorXd values;               // per column: its coefficient in the joint fit on all rows
  double profile = 0;                   // the shape parameter of a profile effect (Stribeck's scale)
  Eigen::VectorXd sign_velocity;        // per joint: over which a friction column's sign turns over
  Eigen::VectorXd contribution;         // A*n: the fitted part of the residual (columns * values)
};

struct SelectedResiduals {
  Eigen::VectorXd nominal;         // A*n: the nominal model's residual (nothing fitted)
  Eigen::VectorXd heldout;         // A*n: held out per block with every selected effect
  std::vector<EffectFit> effects;  // the selected effects, in the order they were selected
};

/// The selected effects (Diagnosis::accepted_effects) fitted together with the selection's
/// weights and folds, so `heldout` is the residual behind Diagnosis::final_after.
SelectedResiduals selected_residuals(const Dataset& data, const Diagnosis& diagnosis);

}  // namespace dyncc::diagnose
