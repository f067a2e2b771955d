#include "base/grouping_check.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "base/rational_fit.hpp"
#include "sym/expand.hpp"
#include "sym/print.hpp"
#include "sym/substitute.hpp"

namespace dyncc::base {
namespace {

using Monomials = std::unordered_map<sym::Expr, Eigen::Index>;

// Coefficients of an expanded polynomial over its coefficient-free terms.
std::vector<std::pair<sym::Expr, double>> terms_of(sym::Expr e) {
  std::vector<std::pair<sym::Expr, double>> out;
  if (e.kind() == sym::Kind::Add) {
    if (!e.value().is_zero()) out.emplace_back(sym::Expr(1), e.value().to_double());
    for (std::size_t i = 0; i < e.args().size(); ++i) out.emplace_back(e.args()[i], e.weights()[i].to_double());
  } else if (!e.is_zero()) {
    auto [c, rest] = sym::split_coefficient(e);
    out.emplace_back(rest, c.to_double());
  }
  return out;
}

Eigen::Index index_of(Monomials& m, sym::Expr t) {
  const auto [it, inserted] = m.try_emplace(t, static_cast<Eigen::Index>(m.size()));
  return it->second;
}

// "p0 + p3 + p4" from coefficients over named parameters (exact where the numbers allow).
std::string combination_text(const Eigen::VectorXd& x, const std::vector<std::string>& names) {
  std::vector<std::pair<sym::Rational, sym::Expr>> terms;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (std::abs(x[i]) < 1e-9) continue;
    const auto r = rational_near(x[i], 1e-6, 1e-9, 1000);
    terms.emplace_back(r ? *r : sym::Rational(static_cast<std::int64_t>(std::llround(x[i] * 1e6)), 1000000),
                       sym::symbol(names[static_cast<std::size_t>(i)]));
  }
  return sym::to_string(sym::linear_combination(terms));
}

// Scales a direction so its smallest non-zero entry has magnitude 1 and its last non-zero
// entry is positive: p5 - p3 rather than 0.707*p3 - 0.707*p5.
Eigen::VectorXd normalised(Eigen::VectorXd x) {
  double smallest = 1e300;
  Eigen::Index last = -1;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (std::abs(x[i]) > 1e-9 * x.cwiseAbs().maxCoeff()) {
      smallest = std::min(smallest, std::abs(x[i]));
      last = i;
    } else {
      x[i] = 0.0;
    }
  }
  if (last < 0) return x;
  x /= smallest;
  if (x[last] < 0) x = -x;
  return x;
}

Eigen::MatrixXd null_space(const Eigen::MatrixXd& A) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  Eigen::MatrixXd k = lu.kernel();
  if (k.cols() == 1 && k.norm() < 1e-300) return Eigen::MatrixXd(A.cols(), 0);
  return k;
}

int rank_of(const Eigen::MatrixXd& A) {
  if (A.rows() == 0 || A.cols() == 0) return 0;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  qr.setThreshold(1e-9);
  return static_cast<int>(qr.rank());
}

// Sparsest basis of {x in R^S : Z^T x = 0} (Z: null directions restricted to S), by growing supports.
std::vector<Eigen::VectorXd> sparse_basis(const Eigen::MatrixXd& Z, int dimension) {
  const auto s = static_cast<int>(Z.rows());
  std::vector<Eigen::VectorXd> chosen;
  if (s > 14) return chosen;  // enumeration is exponential; give up politely on huge sets
  for (int size = 1; size <= s && static_cast<int>(chosen.size()) < dimension; ++size) {
    std::vector<int> subset(static_cast<std::size_t>(size));
    for (int i = 0; i < size; ++i) subset[static_cast<std::size_t>(i)] = i;
    for (;;) {
      Eigen::MatrixXd Zt(Z.cols(), size);
      for (int i = 0; i < size; ++i) Zt.col(i) = Z.row(subset[static_cast<std::size_t>(i)]).transpose();
      const Eigen::MatrixXd k = null_space(Zt);
      if (k.cols() == 1) {
        Eigen::VectorXd x = Eigen::VectorXd::Zero(s);
        bool full_support = true;
        for (int i = 0; i < size; ++i) {
          x[subset[static_cast<std::size_t>(i)]] = k(i, 0);
          full_support = full_support && std::abs(k(i, 0)) > 1e-9 * k.cwiseAbs().maxCoeff();
        }
        if (full_support) {
          Eigen::MatrixXd stack(s, static_cast<Eigen::Index>(chosen.size() + 1));
          for (std::size_t c = 0; c < chosen.size(); ++c) stack.col(static_cast<Eigen::Index>(c)) = chosen[c];
          stack.col(static_cast<Eigen::Index>(chosen.size())) = x;
          if (rank_of(stack) == static_cast<int>(chosen.size() + 1)) chosen.push_back(normalised(x));
        }
      }
      if (static_cast<int>(chosen.size()) == dimension) break;
      // next combination
      int i = size - 1;
      while (i >= 0 && subset[static_cast<std::size_t>(i)] == s - size + i) --i;
      if (i < 0) break;
      ++subset[static_cast<std::size_t>(i)];
      for (int j = i + 1; j < size; ++j)
        subset[static_cast<std::size_t>(j)] = subset[static_cast<std::size_t>(j - 1)] + 1;
    }
  }
  return chosen;
}

}  // namespace

GroupingCheck check_grouping(const robot::RobotDescription& robot, const dyn::DynamicModel& model,
                             const BaseParameterSet& base) {
  GroupingCheck out;
  const sym::Substitution constants = robot.constant_values();
  const auto p = static_cast<Eigen::Index>(model.params.list.size());

  // Standard parameters as vectors over monomials of the description's names.
  Monomials monomials;
  std::vector<std::vector<std::pair<Eigen::Index, double>>> standard_terms;
  for (const auto& sp : model.params.list) {
    std::vector<std::pair<Eigen::Index, double>> t;
    for (const auto& [term, c] : terms_of(sym::expand(sym::substitute(sp.definition, constants))))
      t.emplace_back(index_of(monomials, term), c);
    standard_terms.push_back(std::move(t));
  }
  std::vector<std::vector<std::pair<Eigen::Index, double>>> user_terms;
  for (const auto& bp : robot.base_parameters) {
    std::vector<std::pair<Eigen::Index, double>> t;
    for (const auto& [term, c] : terms_of(sym::expand(sym::substitute(bp.value, constants))))
      t.emplace_back(index_of(monomials, term), c);
    user_terms.push_back(std::move(t));
  }
  const auto m = static_cast<Eigen::Index>(monomials.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, p);
  for (Eigen::Index l = 0; l < p; ++l) {
    for (const auto& [i, c] : standard_terms[static_cast<std::size_t>(l)]) A(i, l) += c;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);

  std::vector<Eigen::VectorXd> rows;
  for (std::size_t k = 0; k < robot.base_parameters.size(); ++k) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
    for (const auto& [i, c] : user_terms[k]) b[i] += c;
    const Eigen::VectorXd x = qr.solve(b);
    if ((A * x - b).norm() > 1e-9 * std::max(1.0, b.norm())) {
      out.errors.push_back(
          fmt::format("{} = {} is not a linear combination of the standard parameters (mass, first moments, "
                      "inertia about the link origin, rotor inertia, friction): the dynamics cannot be "
                      "written in it",
                      robot.base_parameters[k].name, sym::to_string(robot.base_parameters[k].value)));
      continue;
    }
    out.names.push_back(robot.base_parameters[k].name);
    out.description_names.push_back(robot.base_parameters[k].name);
    rows.push_back(x);
  }
  // Friction the grouping does not mention is added as it is.
  std::vector<std::string> added;
  for (Eigen::Index l = 0; l < p; ++l) {
    const auto kind = model.params.list[static_cast<std::size_t>(l)].kind;
    if (kind != dyn::StandardKind::FC && kind != dyn::StandardKind::FV) continue;
    const bool mentioned =
        std::any_of(rows.begin(), rows.end(), [&](const Eigen::VectorXd& r) { return std::abs(r[l]) > 1e-12; });
    if (mentioned) continue;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(p);
    e[l] = 1.0;
    rows.push_back(e);
    out.names.push_back(model.params.list[static_cast<std::size_t>(l)].name);
    added.push_back(sym::to_string(model.params.list[static_cast<std::size_t>(l)].definition));
    out.description_names.push_back(added.back());
  }
  if (!added.empty())
    out.warnings.push_back(fmt::format("friction parameters not in base_parameters are used as they are: {}",
                                       fmt::format("{}", fmt::join(added, ", "))));
  if (!out.errors.empty()) return out;

  const auto u = static_cast<Eigen::Index>(rows.size());
  out.rows.resize(u, p);
  for (Eigen::Index k = 0; k < u; ++k) out.rows.row(k) = rows[static_cast<std::size_t>(k)].transpose();
  const Eigen::MatrixXd& K = base.map;
  const auto r = K.rows();

  // Coverage: every base combination must lie in the row space of the user's grouping.
  Eigen::MatrixXd span = out.rows;
  for (Eigen::Index b = 0; b < r; ++b) {
    Eigen::MatrixXd extended(span.rows() + 1, p);
    extended << span, K.row(b);
    if (rank_of(extended) > rank_of(span)) {
      out.errors.push_back(fmt::format("the grouping misses a combination the torque depends on: {} = {}",
                                       base.list[static_cast<std::size_t>(b)].name,
                                       sym::to_string(base.list[static_cast<std::size_t>(b)].definition)));
      span = extended;
    }
  }
  if (!out.errors.empty()) return out;
  out.complete = true;

  // base = M * user with K = M * U.
  const Eigen::MatrixXd M = out.rows.transpose().colPivHouseholderQr().solve(K.transpose()).transpose();
  out.to_base = M;
  const Eigen::MatrixXd null = null_space(M);
  if (null.cols() > 0) {
    std::vector<Eigen::Index> involved;
    for (Eigen::Index k = 0; k < u; ++k) {
      if (null.row(k).cwiseAbs().maxCoeff() > 1e-9) involved.push_back(k);
    }
    Eigen::MatrixXd Z(static_cast<Eigen::Index>(involved.size()), null.cols());
    std::vector<std::string> involved_names;
    for (std::size_t i = 0; i < involved.size(); ++i) {
      Z.row(static_cast<Eigen::Index>(i)) = null.row(involved[i]);
      involved_names.push_back(out.names[static_cast<std::size_t>(involved[i])]);
    }
    out.involved = involved_names;
    const int dim = static_cast<int>(involved.size()) - static_cast<int>(null.cols());
    for (const Eigen::VectorXd& x : sparse_basis(Z, dim))
      out.effective_combinations.push_back(combination_text(x, involved_names));
    // Redundant directions, sparsest first: the null space of M itself.
    // Redundant directions, sparsest first: vectors of span(Z) = orthogonal to the effective combinations.
    const Eigen::MatrixXd effective_space = null_space(Z.transpose());
    for (const Eigen::VectorXd& x : sparse_basis(effective_space, static_cast<int>(null.cols()))) {
      out.redundant_directions.push_back(combination_text(x, involved_names));
    }
    out.warnings.push_back(
        fmt::format("the grouping is redundant ({} parameters for {} identifiable combinations): {} enter the "
                    "dynamics only as {}; redundant directions (changing the torque not at all): {}. A "
                    "controller may adapt all of them (the redundant directions drift), but identification "
                    "and parameter comparisons must use the {} combinations",
                    u, r, fmt::join(involved_names, ", "), fmt::join(out.effective_combinations, ", "),
                    fmt::join(out.redundant_directions, ", "), r));
  }
  return out;
}

}  // namespace dyncc::base
