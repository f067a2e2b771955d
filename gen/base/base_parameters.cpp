#include "base/base_parameters.hpp"

#include <cmath>

#include "base/rational_fit.hpp"
#include "sym/expand.hpp"
#include "sym/substitute.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::base {
namespace {

constexpr double kRankTolerance = 1e-9;  // relative residual below which a column adds no rank

Eigen::MatrixXd stacked_regressor(const dyn::NumericModel& numeric, int samples) {
  const auto n = static_cast<Eigen::Index>(numeric.dof());
  const auto p = static_cast<Eigen::Index>(numeric.parameter_count());
  Eigen::MatrixXd W(samples * n, p);
  for (int s = 0; s < samples; ++s) {
    const dyn::State st = dyn::random_state(numeric.dof(), 1000U + static_cast<std::uint64_t>(s));
    W.middleRows(s * n, n) = numeric.regressor(st);
  }
  return W;
}

// Columns met first are kept. Link by link, with the mass LAST within a link: a link's mass then
// folds into its first moments and into the parent's (MZ3R = m3*z3 + 0.055*m3,
// MX2R = m2*x2 + 0.18*m3 + ...), the textbook regrouping, instead of dividing by offsets.
std::vector<int> processing_order(const dyn::StandardParameters& params) {
  std::vector<int> order;
  for (const auto& link : params.of_link) {
    for (std::size_t k = 1; k < link.size(); ++k) {
      if (link[k] >= 0) order.push_back(link[k]);
    }
    if (link[0] >= 0) order.push_back(link[0]);
  }
  for (std::size_t i = 0; i < params.list.size(); ++i) {
    if (params.list[i].link < 0) order.push_back(static_cast<int>(i));
  }
  return order;
}

}  // namespace

BaseParameterSet find_base_parameters(const robot::RobotDescription& robot, const dyn::DynamicModel& model,
                                      const dyn::Regressor& regressor, const dyn::NumericModel& numeric,
                                      const BaseParameterOptions& options) {
  const auto p = static_cast<Eigen::Index>(numeric.parameter_count());
  const auto n = static_cast<Eigen::Index>(numeric.dof());
  const int samples = options.samples > 0 ? options.samples : static_cast<int>(2 * p / std::max<Eigen::Index>(n, 1) + 20);
  const Eigen::MatrixXd W = stacked_regressor(numeric, samples);

  // Greedy rank-revealing selection in parameter order (modified Gram-Schmidt, done twice).
  std::vector<int> kept;
  std::vector<Eigen::VectorXd> basis;
  BaseParameterSet out;
  std::vector<int> dependent;
  for (const int col : processing_order(model.params)) {
    const auto l = static_cast<Eigen::Index>(col);
    const double norm = W.col(l).norm();
    if (norm < 1e-12) {
      out.no_effect.push_back(static_cast<int>(l));
      continue;
    }
    Eigen::VectorXd r = W.col(l) / norm;
    for (int pass = 0; pass < 2; ++pass) {
      for (const Eigen::VectorXd& b : basis) r -= b.dot(r) * b;
    }
    if (r.norm() > kRankTolerance * 1e3) {
      kept.push_back(static_cast<int>(l));
      basis.push_back(r.normalized());
    } else {
      dependent.push_back(static_cast<int>(l));
    }
  }

  const auto r = static_cast<Eigen::Index>(kept.size());
  Eigen::MatrixXd WB(W.rows(), r);
  for (Eigen::Index b = 0; b < r; ++b) WB.col(b) = W.col(kept[static_cast<std::size_t>(b)]);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(WB);

  out.map = Eigen::MatrixXd::Zero(r, p);
  std::vector<std::vector<std::pair<int, sym::Rational>>> combos(static_cast<std::size_t>(r));
  for (Eigen::Index b = 0; b < r; ++b) {
    out.map(b, kept[static_cast<std::size_t>(b)]) = 1.0;
    combos[static_cast<std::size_t>(b)].emplace_back(kept[static_cast<std::size_t>(b)], sym::Rational(1));
  }

  const sym::Substitution constants = robot.constant_values();
  for (const int d : dependent) {
    const Eigen::VectorXd beta = qr.solve(W.col(d));
    const double residual = (WB * beta - W.col(d)).norm() / W.col(d).norm();
    out.relative_residual = std::max(out.relative_residual, residual);
    std::vector<std::pair<sym::Rational, sym::Expr>> identity_terms;  // Y_d - sum beta Y_b per row
    bool exact_here = true;
    for (Eigen::Index b = 0; b < r; ++b) {
      if (std::abs(beta[b]) < 1e-11) continue;
      const auto rational = rational_near(beta[b], 1e-8, 1e-11);
      out.map(b, d) = rational ? rational->to_double() : beta[b];
      if (rational) {
        combos[static_cast<std::size_t>(b)].emplace_back(d, *rational);
      } else {
        exact_here = false;
      }
    }
    if (!exact_here) {
      out.exact = false;
      out.proved = false;
      out.note = "some regrouping coefficients are not simple rationals (kept as floating point)";
      continue;
    }
    if (!options.prove) continue;
    // Proof: for every row i, Y_id - sum_b beta_b Y_ib is identically zero.
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      std::vector<std::pair<sym::Rational, sym::Expr>> terms{{sym::Rational(1), regressor.rows[i][static_cast<std::size_t>(d)]}};
      for (Eigen::Index b = 0; b < r; ++b) {
        for (const auto& [idx, coef] : combos[static_cast<std::size_t>(b)]) {
          if (idx == d) terms.emplace_back(-coef, regressor.rows[i][static_cast<std::size_t>(kept[static_cast<std::size_t>(b)])]);
        }
      }
      const sym::Expr gap = sym::substitute(sym::linear_combination(terms), constants);
      const sym::ZeroTestResult z = sym::test_zero(gap);
      if (z.verdict != sym::ZeroVerdict::Zero) {
        out.proved = false;
        out.note = "regrouping of " + model.params.list[static_cast<std::size_t>(d)].name + " could not be proved exactly";
      }
    }
  }

  // Definitions in the description's names, with constants as exact numbers.
  const sym::Substitution definitions = model.params.definitions();
  for (Eigen::Index b = 0; b < r; ++b) {
    BaseParameter bp;
    bp.kept = kept[static_cast<std::size_t>(b)];
    bp.combination = combos[static_cast<std::size_t>(b)];
    bp.name = model.params.list[static_cast<std::size_t>(bp.kept)].name + (bp.combination.size() > 1 ? "R" : "");
    std::vector<std::pair<sym::Rational, sym::Expr>> terms;
    for (const auto& [idx, coef] : bp.combination) terms.emplace_back(coef, model.params.list[static_cast<std::size_t>(idx)].definition);
    bp.definition = sym::expand(sym::substitute(sym::linear_combination(terms), constants));
    out.list.push_back(std::move(bp));
  }
  return out;
}

Eigen::MatrixXd base_regressor(const BaseParameterSet& base, const Eigen::MatrixXd& full) {
  Eigen::MatrixXd Yb(full.rows(), static_cast<Eigen::Index>(base.list.size()));
  for (std::size_t b = 0; b < base.list.size(); ++b) Yb.col(static_cast<Eigen::Index>(b)) = full.col(base.list[b].kept);
  return Yb;
}

}  // namespace dyncc::base
