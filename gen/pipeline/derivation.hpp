// The whole front half of the compiler in one call: description -> kinematics -> loops ->
// energies -> H, C, tau_g -> regressor -> numeric tapes -> base parameters, with stage timings.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/base_parameters.hpp"
#include "base/grouping_check.hpp"
#include "dynamics/model.hpp"
#include "dynamics/numeric_model.hpp"
#include "dynamics/regressor.hpp"
#include "kinematics/kinematics.hpp"
#include "kinematics/loops.hpp"
#include "robot/description.hpp"

namespace dyncc::pipeline {

struct StageTime {
  std::string stage;
  double milliseconds = 0.0;
};

/// Pinned in memory (the numeric model refers to the symbolic one): always held by unique_ptr.
struct Derivation {
  robot::RobotDescription robot;
  kin::Kinematics kinematics;
  std::vector<kin::LoopCheck> loops;
  dyn::DynamicModel model;
  dyn::Regressor regressor;
  std::unique_ptr<dyn::NumericModel> numeric;
  base::BaseParameterSet base;
  std::optional<base::GroupingCheck> grouping;  // when the description has base_parameters
  std::vector<std::string> warnings;            // "file:line:col: warning: ..." lines
  std::vector<StageTime> timings;

  Derivation() = default;
  Derivation(const Derivation&) = delete;
  Derivation& operator=(const Derivation&) = delete;
  Derivation(Derivation&&) = delete;
  Derivation& operator=(Derivation&&) = delete;
  ~Derivation() = default;

  [[nodiscard]] double total_milliseconds() const;
};

struct DerivationError {
  std::string message;  // already in "file:line:column: error: ..." form when it has a place
};

struct DerivationOptions {
  bool prove_base_parameters = true;
};

/// Throws DerivationError for a description that loads but cannot be derived (a loop that does
/// not close, a or alpha depending on a coordinate).
std::unique_ptr<Derivation> derive(robot::RobotDescription robot, const DerivationOptions& options = {});

}  // namespace dyncc::pipeline
