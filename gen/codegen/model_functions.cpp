#include "codegen/model_functions.hpp"

#include <fmt/format.h>

#include <optional>
#include <span>

#include "codegen/lower.hpp"
#include "dynamics/newton_euler.hpp"
#include "sym/diff.hpp"
#include "sym/substitute.hpp"

namespace dyncc::codegen {
namespace {

using sym::Expr;

// One regressor column: the expression on every row (friction columns are sgn(qd_k) or v_k on
// their own row), and whether it is a rigid-body column (enters H, C, g).
struct Column {
  std::vector<Expr> rows;
  bool rigid_body = true;
  int standard = -1;  // the standard parameter this column belongs to
};

// Symbols standing for the signs of the rates in regressor expressions (sgn is not a sym
// function; the generated code computes it).
Expr sign_symbol(std::size_t k) { return sym::symbol(fmt::format("$sgn{}", k)); }
Expr parameter_symbol(std::size_t b) { return sym::symbol(fmt::format("$p{}", b)); }
Expr weight_symbol(std::size_t i) { return sym::symbol(fmt::format("$e{}", i)); }

Column column_of_standard(const pipeline::Derivation& d, int standard, const sym::Substitution& constants) {
  const dyn::DynamicModel& m = d.model;
  const std::size_t n = m.q.size();
  const dyn::StandardParameter& sp = m.params.list[static_cast<std::size_t>(standard)];
  Column c;
  c.standard = standard;
  c.rows.assign(n, Expr(0));
  if (sp.kind == dyn::StandardKind::FC || sp.kind == dyn::StandardKind::FV) {
    const auto k = static_cast<std::size_t>(sp.coordinate);
    c.rows[k] = sp.kind == dyn::StandardKind::FC ? sign_symbol(k) : m.v[k];
    c.rigid_body = false;
    return c;
  }
  for (std::size_t i = 0; i < n; ++i) {
    c.rows[i] = sym::substitute(d.regressor.rows[i][static_cast<std::size_t>(standard)], constants);
  }
  return c;
}

// The inputs every function may read, by symbol. `rates`/`accelerations` name the arrays the
// velocity arguments come from (the identification form reads v from qd and a from qdd).
struct InputNames {
  std::unordered_map<Expr, std::string> map;
  std::map<std::string, std::string> labels;
};

InputNames input_names(const dyn::DynamicModel& m, std::size_t parameters, const std::string& v_array,
                       const std::string& a_array) {
  InputNames in;
  auto put = [&in](Expr s, const std::string& c, const std::string& label) {
    in.map[s] = c;
    in.labels[c] = label;
  };
  for (std::size_t k = 0; k < m.q.size(); ++k) {
    put(m.q[k], fmt::format("q[{}]", k), m.q[k].name());
    put(m.qd[k], fmt::format("qd[{}]", k), m.qd[k].name());
    put(m.v[k], fmt::format("{}[{}]", v_array, k), fmt::format("{}{}", v_array, k + 1));
    put(m.a[k], fmt::format("{}[{}]", a_array, k), fmt::format("{}{}", a_array, k + 1));
    put(sign_symbol(k), fmt::format("sgn(qd[{}])", k), fmt::format("sgn_qd{}", k + 1));
    put(weight_symbol(k), fmt::format("e[{}]", k), fmt::format("e{}", k + 1));
  }
  for (std::size_t b = 0; b < parameters; ++b) put(parameter_symbol(b), fmt::format("p[{}]", b), "");
  return in;
}

Function make_function(std::string name, std::string summary, std::vector<std::string> params,
                       std::vector<bool> is_output) {
  Function f;
  f.name = std::move(name);
  f.summary = std::move(summary);
  f.parameters = std::move(params);
  f.parameter_is_output = std::move(is_output);
  return f;
}

// sum_b p_b * column_b[row], each column already lowered.
ValueId parameter_dot(Program& prog, Lowering& lower, const std::vector<Expr>& entries,
                      const std::vector<std::size_t>& which) {
  ValueId acc = prog.constant(0.0);
  for (const std::size_t b : which) {
    if (entries[b].is_zero()) continue;
    // One lowering after the other: value numbers (and so the output) must not depend on the
    // compiler's order of evaluating function arguments.
    const ValueId parameter = lower(parameter_symbol(b));
    const ValueId entry = lower(entries[b]);
    acc = prog.add(acc, prog.mul(parameter, entry));
  }
  return acc;
}

class Builder {
 public:
  Builder(const pipeline::Derivation& d, std::vector<Column> columns)
      : robot_(d.robot), m_(d.model), n_(d.model.q.size()), columns_(std::move(columns)) {
    for (std::size_t b = 0; b < columns_.size(); ++b) {
      (columns_[b].rigid_body ? rigid_ : friction_).push_back(b);
    }
  }

  // entry(b) for every column, at one row, as expressions.
  [[nodiscard]] std::vector<Expr> row(std::size_t i) const {
    std::vector<Expr> r;
    for (const Column& c : columns_) r.push_back(c.rows[i]);
    return r;
  }

  Function mass_matrix() {
    Function f = make_function("mass_matrix", "H(q): joint-space inertia, row-major n x n", {"q", "p", "H"},
                               {false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    for (std::size_t j = 0; j < n_; ++j) {
      sym::Differentiator by_a(m_.a[j]);
      for (std::size_t i = 0; i < n_; ++i) {
        std::vector<Expr> entries;
        for (const Column& c : columns_) entries.push_back(c.rigid_body ? by_a(c.rows[i]) : Expr(0));
        f.program.set_output(fmt::format("H[{}]", i * n_ + j), parameter_dot(f.program, lower, entries, rigid_));
      }
    }
    return f;
  }

  Function coriolis_matrix() {
    Function f = make_function("coriolis_matrix", "C(q, qd): Christoffel form (Hdot - 2C skew), row-major n x n",
                               {"q", "qd", "p", "C"}, {false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    for (std::size_t j = 0; j < n_; ++j) {
      sym::Differentiator by_v(m_.v[j]);
      for (std::size_t i = 0; i < n_; ++i) {
        std::vector<Expr> entries;
        for (const Column& c : columns_) entries.push_back(c.rigid_body ? by_v(c.rows[i]) : Expr(0));
        f.program.set_output(fmt::format("C[{}]", i * n_ + j), parameter_dot(f.program, lower, entries, rigid_));
      }
    }
    return f;
  }

  Function gravity_torque() {
    Function f = make_function("gravity_torque", "tau_g(q): gravity torque", {"q", "p", "g"}, {false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    sym::Substitution at_rest;
    for (std::size_t k = 0; k < n_; ++k) {
      at_rest[m_.qd[k]] = Expr(0);
      at_rest[m_.v[k]] = Expr(0);
      at_rest[m_.a[k]] = Expr(0);
    }
    for (std::size_t i = 0; i < n_; ++i) {
      std::vector<Expr> entries;
      for (const Column& c : columns_) entries.push_back(c.rigid_body ? sym::substitute(c.rows[i], at_rest) : Expr(0));
      f.program.set_output(fmt::format("g[{}]", i), parameter_dot(f.program, lower, entries, rigid_));
    }
    return f;
  }

  Function friction_torque() {
    Function f = make_function("friction_torque", "FC sgn(qd) + FV v: joint friction", {"qd", "v", "p", "f"},
                               {false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    for (std::size_t i = 0; i < n_; ++i) {
      f.program.set_output(fmt::format("f[{}]", i), parameter_dot(f.program, lower, row(i), friction_));
    }
    return f;
  }

  Function regressor(bool identification) {
    Function f = identification
                     ? make_function("identification_regressor",
                                     "Y(q, qd, qdd): tau = Y p with v = qd, a = qdd, row-major n x r",
                                     {"q", "qd", "qdd", "Y"}, {false, false, false, true})
                     : make_function("regressor", "Y(q, qd, v, a): Y p = H a + C v + g + FC sgn(qd) + FV v, n x r",
                                     {"q", "qd", "v", "a", "Y"}, {false, false, false, false, true});
    if (identification) {
      set_inputs(f, "qd", "qdd");
    } else {
      set_inputs(f, "v", "a");
    }
    Lowering lower(f.program, inputs_.map);
    const std::size_t r = columns_.size();
    for (std::size_t i = 0; i < n_; ++i) {
      for (std::size_t b = 0; b < r; ++b)
        f.program.set_output(fmt::format("Y[{}]", i * r + b), lower(columns_[b].rows[i]));
    }
    return f;
  }

  Function slotine_li_torque() {
    Function f = make_function("slotine_li_torque", "tau = Y(q, qd, v, a) p without forming Y",
                               {"q", "qd", "v", "a", "p", "tau"}, {false, false, false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    emit_torque(f, lower);
    return f;
  }

  Function adaptation_term() {
    Function f = make_function("adaptation_term", "YTe = Y(q, qd, v, a)^T e without forming Y",
                               {"q", "qd", "v", "a", "e", "YTe"}, {false, false, false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    emit_adaptation(f, lower);
    return f;
  }

  Function control_step() {
    Function f = make_function("control_step", "tau = Y p and YTe = Y^T e in one pass, sharing every subexpression",
                               {"q", "qd", "v", "a", "p", "e", "tau", "YTe"},
                               {false, false, false, false, false, false, true, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    emit_torque(f, lower);
    emit_adaptation(f, lower);
    return f;
  }

  Function inverse_dynamics() {
    Function f = make_function("inverse_dynamics", "tau = H qdd + C qd + g + friction", {"q", "qd", "qdd", "p", "tau"},
                               {false, false, false, false, true});
    set_inputs(f, "qd", "qdd");
    Lowering lower(f.program, inputs_.map);
    emit_torque(f, lower);
    return f;
  }

  // ---- The same functions from the Newton-Euler torque (nullopt when the robot has none).

  std::optional<Function> inverse_dynamics_newton_euler() {
    sym::Bindings lets;
    const auto tau = newton_euler(m_.qd, m_.a, true, &lets);
    if (!tau) return std::nullopt;
    Function f = make_function("inverse_dynamics", "tau = H qdd + C qd + g + friction", {"q", "qd", "qdd", "p", "tau"},
                               {false, false, false, false, true});
    set_inputs(f, "qd", "qdd");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    for (std::size_t i = 0; i < n_; ++i) {
      const ValueId friction = parameter_dot(f.program, lower, row(i), friction_);
      f.program.set_output(fmt::format("tau[{}]", i), f.program.add(lower((*tau)[i]), friction));
    }
    return f;
  }

  std::optional<Function> gravity_newton_euler() {
    const std::vector<Expr> zeros(n_, Expr(0));
    sym::Bindings lets;
    const auto tau = newton_euler(zeros, zeros, true, &lets);
    if (!tau) return std::nullopt;
    Function f = make_function("gravity_torque", "tau_g(q): gravity torque", {"q", "p", "g"}, {false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    for (std::size_t i = 0; i < n_; ++i) f.program.set_output(fmt::format("g[{}]", i), lower((*tau)[i]));
    return f;
  }

  std::optional<Function> mass_matrix_newton_euler() {
    Function f = make_function("mass_matrix", "H(q): joint-space inertia, row-major n x n", {"q", "p", "H"},
                               {false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    const std::vector<Expr> zeros(n_, Expr(0));
    sym::Bindings lets;
    for (std::size_t j = 0; j < n_; ++j) {
      std::vector<Expr> unit(n_, Expr(0));
      unit[j] = Expr(1);
      const auto column = newton_euler(zeros, unit, false, &lets);
      if (!column) return std::nullopt;
      lower.define(lets);
      for (std::size_t i = 0; i < n_; ++i) f.program.set_output(fmt::format("H[{}]", i * n_ + j), lower((*column)[i]));
    }
    return f;
  }

  std::optional<Function> mass_matrix_composite() {
    const std::vector<Expr> values = standard_values();
    sym::Bindings lets;
    const auto H = dyn::composite_rigid_body_mass_matrix(robot_, m_, values, &lets);
    if (!H) return std::nullopt;
    Function f = make_function("mass_matrix", "H(q): joint-space inertia, row-major n x n", {"q", "p", "H"},
                               {false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    for (std::size_t i = 0; i < n_; ++i) {
      for (std::size_t j = 0; j < n_; ++j) f.program.set_output(fmt::format("H[{}]", i * n_ + j), lower((*H)[i][j]));
    }
    return f;
  }

  std::optional<Function> identification_regressor_newton_euler(bool bound) {
    sym::Bindings lets;
    const auto tau = newton_euler(m_.qd, m_.a, true, bound ? &lets : nullptr);
    if (!tau) return std::nullopt;
    Function f =
        make_function("identification_regressor", "Y(q, qd, qdd): tau = Y p with v = qd, a = qdd, row-major n x r",
                      {"q", "qd", "qdd", "Y"}, {false, false, false, true});
    set_inputs(f, "qd", "qdd");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    emit_regressor_rows(f, lower, *tau, bound ? &lets : nullptr);
    return f;
  }

  // H a + C(q, qd) v + g with the Christoffel C, from two Newton-Euler passes. The velocity
  // terms N(w) of inverse dynamics are a quadratic form whose symmetric bilinear form is
  // exactly the Christoffel one, Gamma(w, w) = N(w), so by polarisation
  //   C(qd) v = Gamma(qd, v) = N((qd + v)/2) - N((qd - v)/2)
  // and the torque is RNEA(q, (qd + v)/2, a, gravity) - RNEA(q, (qd - v)/2, 0, no gravity).
  std::optional<std::vector<Expr>> slotine_li_rigid_torque(sym::Bindings* lets = nullptr) {
    std::vector<Expr> half_sum, half_difference;
    const sym::Rational half(1, 2);
    for (std::size_t k = 0; k < n_; ++k) {
      half_sum.push_back(Expr(half) * (m_.qd[k] + m_.v[k]));
      half_difference.push_back(Expr(half) * (m_.qd[k] - m_.v[k]));
    }
    const std::vector<Expr> zeros(n_, Expr(0));
    const auto with_accelerations = newton_euler(half_sum, m_.a, true, lets);
    const auto velocity_only = newton_euler(half_difference, zeros, false, lets);
    if (!with_accelerations || !velocity_only) return std::nullopt;
    std::vector<Expr> tau;
    for (std::size_t i = 0; i < n_; ++i) tau.push_back((*with_accelerations)[i] - (*velocity_only)[i]);
    return tau;
  }

  std::optional<Function> slotine_li_torque_newton_euler() {
    sym::Bindings lets;
    const auto rigid = slotine_li_rigid_torque(&lets);
    if (!rigid) return std::nullopt;
    Function f = make_function("slotine_li_torque", "tau = Y(q, qd, v, a) p without forming Y",
                               {"q", "qd", "v", "a", "p", "tau"}, {false, false, false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    emit_torque_from(f, lower, *rigid);
    return f;
  }

  std::optional<Function> coriolis_matrix_newton_euler() {
    const auto rigid = slotine_li_rigid_torque();
    if (!rigid) return std::nullopt;
    Function f = make_function("coriolis_matrix", "C(q, qd): Christoffel form (Hdot - 2C skew), row-major n x n",
                               {"q", "qd", "p", "C"}, {false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    for (std::size_t j = 0; j < n_; ++j) {
      sym::Differentiator by_v(m_.v[j]);
      sym::Substitution at_rest;
      for (std::size_t k = 0; k < n_; ++k) {
        at_rest[m_.v[k]] = Expr(0);
        at_rest[m_.a[k]] = Expr(0);
      }
      for (std::size_t i = 0; i < n_; ++i) {
        f.program.set_output(fmt::format("C[{}]", i * n_ + j), lower(sym::substitute(by_v((*rigid)[i]), at_rest)));
      }
    }
    return f;
  }

  std::optional<Function> regressor_newton_euler(bool bound) {
    sym::Bindings lets;
    const auto rigid = slotine_li_rigid_torque(bound ? &lets : nullptr);
    if (!rigid) return std::nullopt;
    Function f = make_function("regressor", "Y(q, qd, v, a): Y p = H a + C v + g + FC sgn(qd) + FV v, n x r",
                               {"q", "qd", "v", "a", "Y"}, {false, false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    emit_regressor_rows(f, lower, *rigid, bound ? &lets : nullptr);
    return f;
  }

  std::optional<Function> adaptation_term_newton_euler(bool bound) {
    sym::Bindings lets;
    const auto rigid = slotine_li_rigid_torque(bound ? &lets : nullptr);
    if (!rigid) return std::nullopt;
    Function f = make_function("adaptation_term", "YTe = Y(q, qd, v, a)^T e without forming Y",
                               {"q", "qd", "v", "a", "e", "YTe"}, {false, false, false, false, false, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    emit_adaptation_from(f, lower, *rigid, bound ? &lets : nullptr);
    return f;
  }

  // bound: the torque from the Newton-Euler passes with named intermediates, and Y^T e by a
  // reverse sweep through them; otherwise both from the unbound (flattened) expressions.
  std::optional<Function> control_step_newton_euler(bool bound_form) {
    sym::Bindings lets;
    const auto bound = slotine_li_rigid_torque(bound_form ? &lets : nullptr);
    if (!bound) return std::nullopt;
    Function f = make_function("control_step", "tau = Y p and YTe = Y^T e in one pass, sharing every subexpression",
                               {"q", "qd", "v", "a", "p", "e", "tau", "YTe"},
                               {false, false, false, false, false, false, true, true});
    set_inputs(f, "v", "a");
    Lowering lower(f.program, inputs_.map);
    lower.define(lets);
    emit_torque_from(f, lower, *bound);
    emit_adaptation_from(f, lower, *bound, bound_form ? &lets : nullptr);
    return f;
  }

 private:
  // Y rows: the rigid-body columns as d tau_i / dp (one reverse sweep per row, through the
  // named intermediates when there are), the friction columns as they are.
  void emit_regressor_rows(Function& f, Lowering& lower, const std::vector<Expr>& rigid, const sym::Bindings* lets) {
    const std::size_t r = columns_.size();
    const std::vector<Expr> parameters = parameter_symbols();
    for (std::size_t i = 0; i < n_; ++i) {
      sym::Bindings adjoints(fmt::format("$adj{}_", i));
      const std::vector<Expr> gradient = lets == nullptr ? sym::gradient(rigid[i], parameters)
                                                         : sym::gradient_through(rigid[i], *lets, parameters, adjoints);
      lower.define(adjoints);
      for (std::size_t b = 0; b < r; ++b) {
        const Expr entry = columns_[b].rigid_body ? gradient[b] : columns_[b].rows[i];
        f.program.set_output(fmt::format("Y[{}]", i * r + b), lower(entry));
      }
    }
  }

  [[nodiscard]] std::vector<Expr> parameter_symbols() const {
    std::vector<Expr> out;
    for (std::size_t b = 0; b < columns_.size(); ++b) out.push_back(parameter_symbol(b));
    return out;
  }

  // tau = rigid-body torque (in the p symbols) + friction columns.
  void emit_torque_from(Function& f, Lowering& lower, const std::vector<Expr>& rigid) {
    for (std::size_t i = 0; i < n_; ++i) {
      const ValueId friction = parameter_dot(f.program, lower, row(i), friction_);
      f.program.set_output(fmt::format("tau[{}]", i), f.program.add(lower(rigid[i]), friction));
    }
  }

  // Y^T e = d(e . tau)/dp: one reverse sweep over the torque's expression graph gives every
  // parameter's entry at once (the adjoint method), without forming Y.
  // With lets (the torque's named intermediates), the sweep runs through them
  // (sym::gradient_through), keeping the recursion's sharing in the derivative too.
  void emit_adaptation_from(Function& f, Lowering& lower, const std::vector<Expr>& rigid,
                            const sym::Bindings* lets = nullptr) {
    Expr weighted(0);
    for (std::size_t i = 0; i < n_; ++i) weighted += weight_symbol(i) * rigid[i];
    const std::vector<Expr> parameters = parameter_symbols();
    sym::Bindings adjoints("$adj");
    const std::vector<Expr> gradient = lets == nullptr ? sym::gradient(weighted, parameters)
                                                       : sym::gradient_through(weighted, *lets, parameters, adjoints);
    lower.define(adjoints);
    for (std::size_t b = 0; b < columns_.size(); ++b) {
      ValueId acc = f.program.constant(0.0);
      if (columns_[b].rigid_body) {
        acc = lower(gradient[b]);
      } else {
        for (std::size_t i = 0; i < n_; ++i) {
          if (columns_[b].rows[i].is_zero()) continue;
          const ValueId entry = lower(columns_[b].rows[i]);
          const ValueId weight = lower(weight_symbol(i));
          acc = f.program.add(acc, f.program.mul(entry, weight));
        }
      }
      f.program.set_output(fmt::format("YTe[{}]", b), acc);
    }
  }

  // The Newton-Euler torque with each column's standard parameter replaced by its p symbol and
  // every other standard parameter by 0 (a dependent parameter's effect is carried by the
  // base parameters it regroups into).
  std::optional<std::vector<Expr>> newton_euler(std::span<const Expr> qd, std::span<const Expr> qdd, bool gravity,
                                                sym::Bindings* bindings = nullptr) {
    const std::vector<Expr> values = standard_values();
    return dyn::newton_euler_torque(robot_, m_, dyn::NewtonEulerInputs{qd, qdd, gravity, values, bindings});
  }

  // Per standard parameter: the p symbol of its column, or 0.
  [[nodiscard]] std::vector<Expr> standard_values() const {
    std::vector<Expr> values(m_.params.list.size(), Expr(0));
    for (std::size_t b = 0; b < columns_.size(); ++b) {
      values[static_cast<std::size_t>(columns_[b].standard)] = parameter_symbol(b);
    }
    return values;
  }

  void set_inputs(Function& f, const std::string& v_array, const std::string& a_array) {
    inputs_ = input_names(m_, columns_.size(), v_array, a_array);
    f.labels = inputs_.labels;
  }

  void emit_torque(Function& f, Lowering& lower) {
    std::vector<std::size_t> all(columns_.size());
    for (std::size_t b = 0; b < all.size(); ++b) all[b] = b;
    for (std::size_t i = 0; i < n_; ++i) {
      f.program.set_output(fmt::format("tau[{}]", i), parameter_dot(f.program, lower, row(i), all));
    }
  }

  void emit_adaptation(Function& f, Lowering& lower) {
    for (std::size_t b = 0; b < columns_.size(); ++b) {
      ValueId acc = f.program.constant(0.0);
      for (std::size_t i = 0; i < n_; ++i) {
        if (columns_[b].rows[i].is_zero()) continue;
        const ValueId entry = lower(columns_[b].rows[i]);
        const ValueId weight = lower(weight_symbol(i));
        acc = f.program.add(acc, f.program.mul(entry, weight));
      }
      f.program.set_output(fmt::format("YTe[{}]", b), acc);
    }
  }

  const robot::RobotDescription& robot_;
  const dyn::DynamicModel& m_;
  std::size_t n_;
  std::vector<Column> columns_;
  std::vector<std::size_t> rigid_, friction_;
  InputNames inputs_;
};

Function base_parameters_from_link(const pipeline::Derivation& d) {
  Function f =
      make_function("base_parameters_from_link", "p from the description's link parameters (kLinkParameterNames order)",
                    {"link", "p"}, {false, true});
  std::unordered_map<Expr, std::string> inputs;
  for (std::size_t k = 0; k < d.robot.parameters.size(); ++k) {
    const std::string c = fmt::format("link[{}]", k);
    inputs[d.robot.parameters[k].symbol] = c;
    f.labels[c] = d.robot.parameters[k].name;
  }
  Lowering lower(f.program, inputs);
  const sym::Substitution constants = d.robot.constant_values();
  for (std::size_t b = 0; b < d.base.list.size(); ++b) {
    f.program.set_output(fmt::format("p[{}]", b), lower(sym::substitute(d.base.list[b].definition, constants)));
  }
  return f;
}

// The cheaper of two programs for the same function (fewer multiplications and additions;
// the first when they tie).
Function cheaper(Function energy_form, std::optional<Function> newton_euler_form) {
  if (!newton_euler_form) return energy_form;
  const OpCounts a = energy_form.program.count_operations();
  const OpCounts b = newton_euler_form->program.count_operations();
  return b.mul + b.add + b.div < a.mul + a.add + a.div ? std::move(*newton_euler_form) : std::move(energy_form);
}

}  // namespace

ModelFunctions build_model_functions(const pipeline::Derivation& d) {
  const sym::Substitution constants = d.robot.constant_values();
  std::vector<Column> base_columns;
  for (const base::BaseParameter& b : d.base.list) base_columns.push_back(column_of_standard(d, b.kept, constants));

  ModelFunctions out;
  Builder base(d, base_columns);
  out.functions.push_back(
      cheaper(cheaper(base.mass_matrix(), base.mass_matrix_newton_euler()), base.mass_matrix_composite()));
  out.functions.push_back(cheaper(base.coriolis_matrix(), base.coriolis_matrix_newton_euler()));
  out.functions.push_back(cheaper(base.gravity_torque(), base.gravity_newton_euler()));
  out.functions.push_back(base.friction_torque());
  out.functions.push_back(cheaper(base.inverse_dynamics(), base.inverse_dynamics_newton_euler()));
  out.functions.push_back(
      cheaper(cheaper(base.regressor(false), base.regressor_newton_euler(false)), base.regressor_newton_euler(true)));
  out.functions.push_back(cheaper(cheaper(base.regressor(true), base.identification_regressor_newton_euler(false)),
                                  base.identification_regressor_newton_euler(true)));
  out.functions.push_back(cheaper(base.slotine_li_torque(), base.slotine_li_torque_newton_euler()));
  out.functions.push_back(cheaper(cheaper(base.adaptation_term(), base.adaptation_term_newton_euler(false)),
                                  base.adaptation_term_newton_euler(true)));
  out.functions.push_back(cheaper(cheaper(base.control_step(), base.control_step_newton_euler(false)),
                                  base.control_step_newton_euler(true)));
  out.functions.push_back(base_parameters_from_link(d));

  std::vector<Column> standard_columns;
  for (std::size_t l = 0; l < d.model.params.list.size(); ++l) {
    standard_columns.push_back(column_of_standard(d, static_cast<int>(l), constants));
  }
  Builder standard(d, standard_columns);
  out.standard_parameter_variants.push_back(
      cheaper(standard.inverse_dynamics(), standard.inverse_dynamics_newton_euler()));
  out.standard_parameter_variants.push_back(
      cheaper(cheaper(standard.mass_matrix(), standard.mass_matrix_newton_euler()), standard.mass_matrix_composite()));
  out.standard_parameter_variants.push_back(
      cheaper(standard.coriolis_matrix(), standard.coriolis_matrix_newton_euler()));
  out.standard_parameter_variants.push_back(cheaper(standard.gravity_torque(), standard.gravity_newton_euler()));
  out.standard_parameter_variants.push_back(
      cheaper(cheaper(standard.regressor(true), standard.identification_regressor_newton_euler(false)),
              standard.identification_regressor_newton_euler(true)));
  return out;
}

}  // namespace dyncc::codegen
