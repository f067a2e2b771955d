#include "dynamics/numeric_model.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include "sym/substitute.hpp"

namespace dyncc::dyn {
namespace {

std::vector<sym::Expr> concat(std::initializer_list<const std::vector<sym::Expr>*> parts) {
  std::vector<sym::Expr> out;
  for (const auto* p : parts) out.insert(out.end(), p->begin(), p->end());
  return out;
}

std::vector<sym::Expr> substituted(const std::vector<sym::Expr>& exprs, const sym::Substitution& map) {
  std::vector<sym::Expr> out;
  out.reserve(exprs.size());
  for (const sym::Expr e : exprs) out.push_back(sym::substitute(e, map));
  return out;
}

std::vector<sym::Expr> flatten(const Matrix& m) {
  std::vector<sym::Expr> out;
  for (const auto& row : m) out.insert(out.end(), row.begin(), row.end());
  return out;
}

sym::CompiledFunction compile_dynamics(const DynamicModel& m, const sym::Substitution& constants,
                                       const std::vector<sym::Expr>& ps) {
  std::vector<sym::Expr> outs = flatten(m.H);
  const auto c = flatten(m.C);
  outs.insert(outs.end(), c.begin(), c.end());
  outs.insert(outs.end(), m.g.begin(), m.g.end());
  return {substituted(outs, constants), concat({&m.q, &m.qd, &ps})};
}

sym::CompiledFunction compile_mass(const DynamicModel& m, const sym::Substitution& constants,
                                   const std::vector<sym::Expr>& ps) {
  return {substituted(flatten(m.H), constants), concat({&m.q, &ps})};
}

sym::CompiledFunction compile_energy(const DynamicModel& m, const sym::Substitution& constants,
                                     const std::vector<sym::Expr>& ps) {
  const std::vector<sym::Expr> outs = {sym::substitute(m.kinetic_energy + m.potential_energy, constants)};
  return {outs, concat({&m.q, &m.qd, &ps})};
}

sym::CompiledFunction compile_regressor(const DynamicModel& m, const Regressor& r, const sym::Substitution& constants) {
  return {substituted(flatten(r.rows), constants), concat({&m.q, &m.qd, &m.v, &m.a})};
}

}  // namespace

NumericModel::NumericModel(const robot::RobotDescription& robot, const DynamicModel& model, const Regressor& regressor)
    : model_(model),
      n_(model.q.size()),
      p_(model.params.list.size()),
      parameter_symbols_(model.params.symbols()),
      dynamics_(compile_dynamics(model, robot.constant_values(), parameter_symbols_)),
      mass_(compile_mass(model, robot.constant_values(), parameter_symbols_)),
      energy_(compile_energy(model, robot.constant_values(), parameter_symbols_)),
      regressor_(compile_regressor(model, regressor, robot.constant_values())) {
  const sym::Substitution constants = robot.constant_values();
  for (const auto& p : model.params.list) definitions_.push_back(sym::substitute(p.definition, constants));
  for (const auto& p : robot.parameters) user_symbols_.push_back(p.symbol);
  nominal_ = standard_values(robot.nominal_values());
}

Eigen::VectorXd NumericModel::standard_values(const std::map<std::string, double>& values) const {
  std::vector<double> inputs;
  inputs.reserve(user_symbols_.size());
  for (const sym::Expr s : user_symbols_) {
    const auto it = values.find(s.name());
    inputs.push_back(it == values.end() ? 0.0 : it->second);
  }
  const sym::CompiledFunction f(definitions_, user_symbols_);
  const std::vector<double> out = f(inputs);
  return Eigen::Map<const Eigen::VectorXd>(out.data(), static_cast<Eigen::Index>(out.size()));
}

Eigen::VectorXd NumericModel::friction(const State& s, const Eigen::VectorXd& standard) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n_));
  for (std::size_t k = 0; k < n_; ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    const int fc = model_.params.coulomb_of[k];
    const int fv = model_.params.viscous_of[k];
    if (fc >= 0) f[i] += standard[fc] * ((s.qd[i] > 0) - (s.qd[i] < 0));
    if (fv >= 0) f[i] += standard[fv] * s.v[i];
  }
  return f;
}

Evaluation NumericModel::assemble(const State& s, const Eigen::VectorXd& standard, const double* values,
                                  std::size_t stride) const {
  const auto n = static_cast<Eigen::Index>(n_);
  const Eigen::InnerStride<> step(static_cast<Eigen::Index>(stride));
  using Strided = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>, 0,
                             Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
  const Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic> matrix_step(n * step.inner(), step.inner());
  Evaluation e;
  e.H = Strided(values, n, n, matrix_step);
  e.C = Strided(values + n * n * step.inner(), n, n, matrix_step);
  e.g = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>(values + 2 * n * n * step.inner(), n, step);
  e.friction = friction(s, standard);
  e.tau = e.H * s.a + e.C * s.v + e.g + e.friction;
  return e;
}

Evaluation NumericModel::evaluate(const State& s, const Eigen::VectorXd& standard, bool with_regressor) const {
  const auto n = static_cast<Eigen::Index>(n_);
  std::vector<double> in;
  in.insert(in.end(), s.q.data(), s.q.data() + n);
  in.insert(in.end(), s.qd.data(), s.qd.data() + n);
  in.insert(in.end(), standard.data(), standard.data() + standard.size());
  const std::vector<double> out = dynamics_(in);
  Evaluation e = assemble(s, standard, out.data(), 1);
  if (with_regressor) e.Y = regressor(s);
  return e;
}

std::vector<Evaluation> NumericModel::evaluate(std::span<const State> states, const Eigen::VectorXd& standard,
                                               bool with_regressor) const {
  const Eigen::MatrixXd out = evaluate_rows(dynamics_, state_rows(states, standard));
  std::vector<Eigen::MatrixXd> ys;
  if (with_regressor) ys = regressor(states);
  std::vector<Evaluation> result;
  result.reserve(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    result.push_back(assemble(states[i], standard, out.data() + i, states.size()));
    if (with_regressor) result.back().Y = std::move(ys[i]);
  }
  return result;
}

Eigen::MatrixXd NumericModel::assemble_regressor(const State& s, const double* values, std::size_t stride) const {
  const auto n = static_cast<Eigen::Index>(n_);
  const auto p = static_cast<Eigen::Index>(p_);
  const auto step = static_cast<Eigen::Index>(stride);
  Eigen::MatrixXd Y = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>, 0,
                                 Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>(
      values, n, p, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(p * step, step));
  for (std::size_t k = 0; k < n_; ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    if (const int fc = model_.params.coulomb_of[k]; fc >= 0) Y(i, fc) = (s.qd[i] > 0) - (s.qd[i] < 0);
    if (const int fv = model_.params.viscous_of[k]; fv >= 0) Y(i, fv) = s.v[i];
  }
  return Y;
}

Eigen::MatrixXd NumericModel::regressor(const State& s) const {
  const auto n = static_cast<Eigen::Index>(n_);
  std::vector<double> in;
  for (const Eigen::VectorXd* v : {&s.q, &s.qd, &s.v, &s.a}) in.insert(in.end(), v->data(), v->data() + n);
  const std::vector<double> out = regressor_(in);
  return assemble_regressor(s, out.data(), 1);
}

std::vector<Eigen::MatrixXd> NumericModel::regressor(std::span<const State> states) const {
  const auto n = static_cast<Eigen::Index>(n_);
  Eigen::MatrixXd in(static_cast<Eigen::Index>(states.size()), 4 * n);
  for (Eigen::Index r = 0; r < in.rows(); ++r) {
    const State& s = states[static_cast<std::size_t>(r)];
    in.row(r) << s.q.transpose(), s.qd.transpose(), s.v.transpose(), s.a.transpose();
  }
  const Eigen::MatrixXd out = evaluate_rows(regressor_, in);
  std::vector<Eigen::MatrixXd> result;
  result.reserve(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    result.push_back(assemble_regressor(states[i], out.data() + i, states.size()));
  }
  return result;
}

Eigen::MatrixXd NumericModel::mass_matrix(const Eigen::VectorXd& q, const Eigen::VectorXd& standard) const {
  const auto n = static_cast<Eigen::Index>(n_);
  std::vector<double> in(q.data(), q.data() + n);
  in.insert(in.end(), standard.data(), standard.data() + standard.size());
  const std::vector<double> out = mass_(in);
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out.data(), n, n);
}

double NumericModel::energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                            const Eigen::VectorXd& standard) const {
  std::vector<double> in(q.data(), q.data() + q.size());
  in.insert(in.end(), qd.data(), qd.data() + qd.size());
  in.insert(in.end(), standard.data(), standard.data() + standard.size());
  return energy_(in)[0];
}

std::vector<double> NumericModel::energy(std::span<const State> states, const Eigen::VectorXd& standard) const {
  const Eigen::MatrixXd out = evaluate_rows(energy_, state_rows(states, standard));
  return {out.data(), out.data() + out.size()};
}

Eigen::MatrixXd state_rows(std::span<const State> states, const Eigen::VectorXd& parameters) {
  const Eigen::Index n = states.empty() ? 0 : states.front().q.size();
  Eigen::MatrixXd in(static_cast<Eigen::Index>(states.size()), 2 * n + parameters.size());
  for (Eigen::Index r = 0; r < in.rows(); ++r) {
    const State& s = states[static_cast<std::size_t>(r)];
    in.row(r) << s.q.transpose(), s.qd.transpose(), parameters.transpose();
  }
  return in;
}

Eigen::MatrixXd evaluate_rows(const sym::CompiledFunction& f, const Eigen::MatrixXd& inputs) {
  Eigen::MatrixXd out(inputs.rows(), static_cast<Eigen::Index>(f.output_count()));
  f.evaluate_rows({inputs.data(), static_cast<std::size_t>(inputs.size())}, static_cast<std::size_t>(inputs.rows()),
                  {out.data(), static_cast<std::size_t>(out.size())});
  return out;
}

State random_state(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> rate(-2.0, 2.0);
  const auto m = static_cast<Eigen::Index>(n);
  State s{Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m)};
  for (Eigen::Index i = 0; i < m; ++i) {
    s.q[i] = angle(rng);
    s.qd[i] = rate(rng);
    s.v[i] = rate(rng);
    s.a[i] = rate(rng);
  }
  return s;
}

}  // namespace dyncc::dyn
