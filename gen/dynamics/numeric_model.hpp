// Numbers from the derived model: H, C, tau_g, friction and Y at a state, for given parameter
// values. Everything is compiled once into instruction tapes (constants substituted exactly
// beforehand) and then evaluated at as many states as the checks need.
#pragma once

#include <Eigen/Dense>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "dynamics/regressor.hpp"
#include "sym/evaluate.hpp"

namespace dyncc::dyn {

struct State {
  Eigen::VectorXd q, qd, v, a;
};

struct Evaluation {
  Eigen::MatrixXd H, C;
  Eigen::VectorXd g, friction, tau;  // friction = FC sgn(qd) + FV v; tau = H a + C v + g + friction
  Eigen::MatrixXd Y;                 // tau == Y * standard parameter values
};

class NumericModel {
 public:
  NumericModel(const robot::RobotDescription& robot, const DynamicModel& model, const Regressor& regressor);

  /// Standard parameter values for the description's parameter values (nominal by default).
  [[nodiscard]] Eigen::VectorXd standard_values(const std::map<std::string, double>& parameter_values) const;
  [[nodiscard]] Eigen::VectorXd nominal_standard_values() const { return nominal_; }

  /// H, C, g, friction, tau and (unless with_regressor is false: Y is then left empty, which
  /// makes a simulation step several times cheaper) the regressor Y.
  [[nodiscard]] Evaluation evaluate(const State& s, const Eigen::VectorXd& standard, bool with_regressor = true) const;
  /// The same at many states: the same numbers, several times faster (the tapes run over blocks
  /// of states, CompiledFunction::evaluate_rows).
  [[nodiscard]] std::vector<Evaluation> evaluate(std::span<const State> states, const Eigen::VectorXd& standard,
                                                 bool with_regressor = true) const;
  /// Only the regressor (does not depend on parameters).
  [[nodiscard]] Eigen::MatrixXd regressor(const State& s) const;
  [[nodiscard]] std::vector<Eigen::MatrixXd> regressor(std::span<const State> states) const;
  /// The friction alone, FC sgn(qd) + FV v (no tape: a few multiplications).
  [[nodiscard]] Eigen::VectorXd friction(const State& s, const Eigen::VectorXd& standard) const;
  /// H alone (cheaper), for positive-definiteness and energy checks.
  [[nodiscard]] Eigen::MatrixXd mass_matrix(const Eigen::VectorXd& q, const Eigen::VectorXd& standard) const;
  /// Kinetic + potential energy.
  [[nodiscard]] double energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                              const Eigen::VectorXd& standard) const;
  /// At many states (their q and qd), together: the same numbers.
  [[nodiscard]] std::vector<double> energy(std::span<const State> states, const Eigen::VectorXd& standard) const;

  [[nodiscard]] std::size_t dof() const { return n_; }
  [[nodiscard]] std::size_t parameter_count() const { return p_; }

 private:
  // Evaluation / Y from the tapes' outputs: output k at values[k * stride].
  [[nodiscard]] Evaluation assemble(const State& s, const Eigen::VectorXd& standard, const double* values,
                                    std::size_t stride) const;
  [[nodiscard]] Eigen::MatrixXd assemble_regressor(const State& s, const double* values, std::size_t stride) const;

  const DynamicModel& model_;
  std::size_t n_, p_;
  std::vector<sym::Expr> parameter_symbols_;
  sym::CompiledFunction dynamics_;   // inputs q, qd, standard -> H (n*n), C (n*n), g (n)
  sym::CompiledFunction mass_;       // inputs q, standard -> H
  sym::CompiledFunction energy_;     // inputs q, qd, standard -> T + V
  sym::CompiledFunction regressor_;  // inputs q, qd, v, a -> Y (n*p)
  Eigen::VectorXd nominal_;
  std::vector<sym::Expr> definitions_;  // standard parameter definitions with constants substituted
  std::vector<sym::Expr> user_symbols_;
};

/// A tape at many points: row r of `inputs` holds point r's inputs (in the tape's order), row r
/// of the result its outputs (CompiledFunction::evaluate_rows on column-major matrices).
Eigen::MatrixXd evaluate_rows(const sym::CompiledFunction& f, const Eigen::MatrixXd& inputs);
/// One state per row: its q, its qd, then `parameters` (the inputs of tapes in q, qd and the
/// standard parameters: the dynamics, the energy, Hdot).
Eigen::MatrixXd state_rows(std::span<const State> states, const Eigen::VectorXd& parameters);

/// Uniform random states (angles in [-pi, pi], rates in [-2, 2]) from a seed: reproducible.
State random_state(std::size_t n, std::uint64_t seed);

}  // namespace dyncc::dyn
