// Base (identifiable) parameters: the independent combinations of standard parameters that
// the torque actually depends on.
//
// Found by EXACT linear algebra: the regressor is evaluated at random points over two prime
// fields (sin/cos from rational points of the unit circle, so every value is exact), columns are
// taken link by link and kept when they add rank (so a later link's mass folds into an earlier
// link's first moment, as in p13 = m2*x2 + 0.18*m3 + m4*x4), and each other column's
// coefficients on the kept ones are solved modulo both primes and lifted to rationals (CRT and
// rational reconstruction). Each regrouping identity Y_d == sum_b beta_db Y_b is then proved
// with the trigonometric normal form (small arms) or checked exactly at fresh random points.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "dynamics/numeric_model.hpp"
#include "dynamics/regressor.hpp"

namespace dyncc::base {

struct BaseParameter {
  std::string name;  // the kept standard parameter's name, + "R" when others are regrouped into it
  int kept = -1;     // index of that standard parameter
  std::vector<std::pair<int, sym::Rational>> combination;  // standard index -> coefficient
  sym::Expr definition;  // in the description's parameter names (constants as numbers)
};

struct BaseParameterSet {
  std::vector<BaseParameter> list;
  std::vector<int> no_effect;      // standard parameters the torque does not depend on at all
  Eigen::MatrixXd map;             // base = map * standard  (r x p)
  bool exact = true;               // every coefficient was recovered as a rational
  bool proved = true;              // the regrouping identities were proved symbolically
  std::string note;                // what was not exact or proved, if anything
  std::string proof;               // how the regrouping identities were established
  double relative_residual = 0.0;  // max |Y_d - Y_B beta_d| / |Y_d| over the samples

  /// Values of the base parameters for standard parameter values.
  [[nodiscard]] Eigen::VectorXd values(const Eigen::VectorXd& standard) const { return map * standard; }
};

struct BaseParameterOptions {
  int samples = 0;                         // regressor samples to stack; 0 = automatic
  bool prove = true;                       // prove each regrouping identity
  std::size_t symbolic_proof_max_dof = 4;  // above: exact randomised check over GF(p) instead
};

BaseParameterSet find_base_parameters(const robot::RobotDescription& robot, const dyn::DynamicModel& model,
                                      const dyn::Regressor& regressor, const dyn::NumericModel& numeric,
                                      const BaseParameterOptions& options = {});

/// The regressor columns of the base parameters at a state (Y_base * base == Y * standard).
Eigen::MatrixXd base_regressor(const BaseParameterSet& base, const Eigen::MatrixXd& full_regressor);

}  // namespace dyncc::base
