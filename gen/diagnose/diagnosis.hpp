// The diagnosis: where the nominal model disagrees with the logs, which effect of the library
// explains it (greedy forward selection by held-out error, with confidence intervals from the
// blocked folds), and how far the gap shrinks once it is added. Effects that explain the same
// thing equally well are reported as "A or B"; `none` when the residual is at the noise floor;
// `unknown` when it is above it and nothing in the library explains it.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "diagnose/crossval.hpp"
#include "diagnose/dataset.hpp"
#include "diagnose/effects.hpp"
#include "diagnose/gap.hpp"

namespace dyncc::diagnose {

struct FittedParameter {
  std::string name;             // "fc2", "mass", "delay", ...
  double value = 0, error = 0;  // physical value (stiffness, gain, ... read from the column)
  // Its 95 % interval: Student's t over the folds (the error is a jackknife standard error with
  // kFolds - 1 degrees of freedom, so two errors cover only 88 %), read through the same reading
  // as the value (a stiffness's is not symmetric; a bound past the reading's pole is infinite).
  // NaN where the value is not fitted over folds (a search's resolution, a gate's point).
  double low = std::numeric_limits<double>::quiet_NaN(), high = std::numeric_limits<double>::quiet_NaN();
};

/// An effect that a selected "A or B" names beside the one it fits (B), fitted in A's place beside
/// every other selected effect: what B's parameters would read if B were the explanation, and how
/// much the selection removes with it there (held out) against with A, which the log cannot tell
/// apart (the same joints, within the folds' spread).
struct AlternativeFit {
  std::string effect;
  std::vector<FittedParameter> parameters;  // their error: the folds' spread alone
  double selection_shrink = 0;              // the joint fit of the selection with it in A's place
  double named_selection_shrink = 0;        // ... and with A, as named
  bool plausible = true;                    // its parameters make physical sense (as a selected effect's)
};

struct RankedEffect {
  std::string effect;  // vocabulary name, or "A or B"
  std::string family;
  std::vector<int> joints;  // 1-based: where it shrinks the held-out gap
  std::vector<FittedParameter> parameters;
  Eigen::VectorXd before, after;           // held-out RMS per joint without and with it
  double shrink = 0;                       // 1 - after/before, weighted over joints (torque-normalised)
  double shrink_low = 0, shrink_high = 0;  // 95 % interval over the folds
  std::size_t columns = 0;
  std::string profile_name;
  double profile = 0;
  bool accepted = false;
  bool plausible = true;  // its parameters make physical sense (no negative friction or mass)
  // Friction effects: the shrink on the rows where the velocity is away from zero (what explains
  // residual only near zero is how the friction turns over, not a friction effect).
  std::optional<double> shrink_away_from_zero;
  // Selected only: the per-joint effects named beside it ("A or B"), each fitted in its place.
  std::vector<AlternativeFit> alternatives;
  // Selected only: per-joint effects as good at its step on some of its joints only (name, 1-based
  // joints), named beside it if the joint fit narrows it to those joints.
  std::vector<std::pair<std::string, std::vector<int>>> alternatives_if_narrowed;
};

struct Verdict {
  std::string effect = "none";
  std::vector<int> joints;  // 1-based
  double confidence = 0;
};

struct Diagnosis {
  Gap gap;
  std::vector<RankedEffect> ranking;   // every candidate at the first step, best first
  std::vector<RankedEffect> selected;  // the forward selection, in order
  RankedEffect within_model;           // inertial_parameters alone (re-identification)
  Verdict verdict;
  Eigen::VectorXd final_after;  // held-out RMS per joint with every selected effect
  // What the selection fitted, for refits (the report's figures): the selected effects exactly as
  // accepted (per-joint effects narrowed to their joints), in order, and the per-joint weights.
  std::vector<Effect> accepted_effects;
  Eigen::VectorXd weight;
  Folds folds;           // the cross-validation's blocks (folds_sharing_bursts of the residual)
  Eigen::VectorXd away;  // away_from_zero_velocity of the data: where friction columns are fitted
  // away_from_zero_velocity at kStaticFrictionLeak: the rows that a static friction held near zero
  // velocity does not reach through the filter (fit_together).
  Eigen::VectorXd far;
  // 1 on the stacked rows the selection scores its candidates on: all but the holds (in_long_rests)
  // of joints where a friction is evident and its static part holds at rest (see diagnose).
  Eigen::VectorXd scored;
};

Diagnosis diagnose(const Dataset& data, const pipeline::Derivation& derivation);

/// The effects' columns side by side (`all`) and where fit_together fits each (`fitted`, 0 or 1
/// per row and column): a friction's on the rows away from zero velocity (`away`), every other
/// column on all rows.
struct FittedColumns {
  Eigen::MatrixXd all, fitted;
};
FittedColumns fitted_columns(const std::vector<Effect>& effects, const Eigen::VectorXd& away);

/// Effects fitted together on the residual (blocked cross-validation with the per-joint weights,
/// over the blocks `folds`):
/// friction columns are fitted where the velocity is away from zero (`away`) and predict on every
/// row. Near zero a log's friction turns over in its own way, which would bend a Coulomb term
/// fitted there (a rigid plant's friction regularised over 10 mrad/s read 11 % low). A joint's rows
/// near zero whose held-out mean square after a first fit is over that away from zero hold
/// a static friction, not noise: the fit is made again without them, nor the rows around them
/// that the filter spreads it into (`far` 0: away_from_zero_velocity at kStaticFrictionLeak).
/// With `rows` (stacked, 0 or
/// 1), only the rows marked 1 are fitted on. `unbiased`: the coefficients (theta, its folds and
/// error) are read free of the logged torque's noise where columns are made from it
/// (Effect::torque_noise); the held-out residual is then the corrected fits', a worse predictor.
CrossValidation fit_together(const std::vector<Effect>& effects, const Eigen::VectorXd& residual,
                             const Eigen::VectorXd& weight, const Folds& folds, const Eigen::VectorXd& away,
                             const Eigen::VectorXd& far, Eigen::Index n, const Eigen::VectorXd* rows = nullptr,
                             bool unbiased = false);

}  // namespace dyncc::diagnose
