#include "base/base_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "sym/expand.hpp"
#include "sym/modular.hpp"
#include "sym/substitute.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::base {
namespace {

// A dense matrix of GF(p) elements, row-major.
struct ModMatrix {
  std::size_t rows = 0, cols = 0;
  std::vector<std::uint64_t> data;
  [[nodiscard]] std::uint64_t at(std::size_t i, std::size_t j) const { return data[i * cols + j]; }
  std::uint64_t& at(std::size_t i, std::size_t j) { return data[i * cols + j]; }
  [[nodiscard]] std::vector<std::uint64_t> column(std::size_t j) const {
    std::vector<std::uint64_t> c(rows);
    for (std::size_t i = 0; i < rows; ++i) c[i] = at(i, j);
    return c;
  }
  [[nodiscard]] bool column_is_zero(std::size_t j) const {
    for (std::size_t i = 0; i < rows; ++i) {
      if (at(i, j) != 0) return false;
    }
    return true;
  }
};

// Regressor rows at random exact points. Friction columns (sgn(qd_k), v_k on row k) take an
// independent random value for sgn, which is all rank needs.
ModMatrix sample_regressor(const sym::ModularFunction& tape, const dyn::DynamicModel& model, const sym::PrimeField& f,
                           int samples, std::uint64_t seed) {
  const std::size_t n = model.q.size();
  const std::size_t p = model.params.list.size();
  ModMatrix W;
  W.rows = static_cast<std::size_t>(samples) * n;
  W.cols = p;
  W.data.assign(W.rows * W.cols, 0);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::uint64_t> uniform(1, f.prime() - 1);
  for (int s = 0; s < samples; ++s) {
    std::vector<std::uint64_t> values;
    sym::ModularPoint pt;
    for (;;) {
      pt = sym::random_point(f, tape.circle_count(), rng);
      try {
        values = tape.evaluate(f, pt);
        break;
      } catch (const std::domain_error&) {
        // a division by zero at this point: draw another
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t row = static_cast<std::size_t>(s) * n + i;
      for (std::size_t l = 0; l < p; ++l) W.at(row, l) = values[i * p + l];
      if (const int fc = model.params.coulomb_of[i]; fc >= 0) W.at(row, static_cast<std::size_t>(fc)) = uniform(rng);
      if (const int fv = model.params.viscous_of[i]; fv >= 0)
        W.at(row, static_cast<std::size_t>(fv)) = pt.value[2 * n + i];
    }
  }
  return W;
}

// Incremental column echelon form over GF(p): insert() reports whether a vector adds rank.
class Echelon {
 public:
  Echelon(const sym::PrimeField& f, std::size_t length) : f_(f), length_(length) {}
  bool insert(std::vector<std::uint64_t> v) {
    for (std::size_t k = 0; k < basis_.size(); ++k) {
      const std::uint64_t c = v[pivots_[k]];
      if (c == 0) continue;
      for (std::size_t i = 0; i < length_; ++i) v[i] = f_.sub(v[i], f_.mul(c, basis_[k][i]));
    }
    std::size_t pivot = length_;
    for (std::size_t i = 0; i < length_; ++i) {
      if (v[i] != 0) {
        pivot = i;
        break;
      }
    }
    if (pivot == length_) return false;
    const std::uint64_t inv = f_.inv(v[pivot]);
    for (std::uint64_t& x : v) x = f_.mul(x, inv);
    for (auto& b : basis_) {  // keep earlier vectors reduced at the new pivot
      const std::uint64_t c = b[pivot];
      if (c == 0) continue;
      for (std::size_t i = 0; i < length_; ++i) b[i] = f_.sub(b[i], f_.mul(c, v[i]));
    }
    basis_.push_back(std::move(v));
    pivots_.push_back(pivot);
    return true;
  }

 private:
  const sym::PrimeField& f_;
  std::size_t length_;
  std::vector<std::vector<std::uint64_t>> basis_;
  std::vector<std::size_t> pivots_;
};

// Solves W_B beta = W_d for every dependent column by Gauss-Jordan on [W_B | W_D].
std::vector<std::optional<std::vector<std::uint64_t>>> solve_columns(const sym::PrimeField& f, const ModMatrix& W,
                                                                     const std::vector<int>& kept,
                                                                     const std::vector<int>& dependent) {
  const std::size_t r = kept.size();
  const std::size_t m = dependent.size();
  std::vector<std::vector<std::uint64_t>> A(W.rows, std::vector<std::uint64_t>(r + m));
  for (std::size_t i = 0; i < W.rows; ++i) {
    for (std::size_t b = 0; b < r; ++b) A[i][b] = W.at(i, static_cast<std::size_t>(kept[b]));
    for (std::size_t j = 0; j < m; ++j) A[i][r + j] = W.at(i, static_cast<std::size_t>(dependent[j]));
  }
  std::size_t row = 0;
  bool full_rank = true;
  for (std::size_t col = 0; col < r; ++col) {
    std::size_t pivot = row;
    while (pivot < A.size() && A[pivot][col] == 0) ++pivot;
    if (pivot == A.size()) {
      full_rank = false;
      continue;
    }
    std::swap(A[row], A[pivot]);
    const std::uint64_t inv = f.inv(A[row][col]);
    for (std::uint64_t& x : A[row]) x = f.mul(x, inv);
    for (std::size_t i = 0; i < A.size(); ++i) {
      if (i == row || A[i][col] == 0) continue;
      const std::uint64_t c = A[i][col];
      for (std::size_t k = col; k < r + m; ++k) A[i][k] = f.sub(A[i][k], f.mul(c, A[row][k]));
    }
    ++row;
  }
  std::vector<std::optional<std::vector<std::uint64_t>>> out(m);
  if (!full_rank) return out;
  for (std::size_t j = 0; j < m; ++j) {
    bool consistent = true;
    for (std::size_t i = r; i < A.size(); ++i) consistent = consistent && A[i][r + j] == 0;
    if (!consistent) continue;
    std::vector<std::uint64_t> beta(r);
    for (std::size_t b = 0; b < r; ++b) beta[b] = A[b][r + j];
    out[j] = std::move(beta);
  }
  return out;
}

Eigen::MatrixXd base_regressor_columns(const Eigen::MatrixXd& W, const std::vector<int>& kept) {
  Eigen::MatrixXd WB(W.rows(), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t b = 0; b < kept.size(); ++b) WB.col(static_cast<Eigen::Index>(b)) = W.col(kept[b]);
  return WB;
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
  const std::size_t p = model.params.list.size();
  const std::size_t n = model.q.size();
  const int samples = options.samples > 0 ? options.samples : static_cast<int>(2 * p / std::max<std::size_t>(n, 1) + 8);
  BaseParameterSet out;

  // Exact sampled regressor over two primes.
  const sym::Substitution constants = robot.constant_values();
  std::vector<sym::Expr> entries;
  for (const auto& row : regressor.rows) {
    for (const sym::Expr e : row) entries.push_back(sym::substitute(e, constants));
  }
  std::vector<sym::Expr> inputs = model.q;
  for (const auto* v : {&model.qd, &model.v, &model.a}) inputs.insert(inputs.end(), v->begin(), v->end());
  const sym::ModularFunction tape(entries, inputs);
  const sym::PrimeField f1(sym::PrimeField::kPrime1);
  const sym::PrimeField f2(sym::PrimeField::kPrime2);
  const ModMatrix W1 = sample_regressor(tape, model, f1, samples, 11);
  const ModMatrix W2 = sample_regressor(tape, model, f2, samples, 12);

  // Greedy selection: a column is kept when it is independent of those kept before it.
  std::vector<int> kept;
  std::vector<int> dependent;
  {
    Echelon ech(f1, W1.rows);
    for (const int col : processing_order(model.params)) {
      if (W1.column_is_zero(static_cast<std::size_t>(col))) {
        out.no_effect.push_back(col);
      } else if (ech.insert(W1.column(static_cast<std::size_t>(col)))) {
        kept.push_back(col);
      } else {
        dependent.push_back(col);
      }
    }
  }
  std::sort(out.no_effect.begin(), out.no_effect.end());
  const std::size_t r = kept.size();
  out.map = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(p));
  std::vector<std::vector<std::pair<int, sym::Rational>>> combos(r);
  for (std::size_t b = 0; b < r; ++b) {
    out.map(static_cast<Eigen::Index>(b), kept[b]) = 1.0;
    combos[b].emplace_back(kept[b], sym::Rational(1));
  }

  // beta (W_B beta = w_d) modulo both primes, then the rational it stands for.
  const auto beta1 = solve_columns(f1, W1, kept, dependent);
  const auto beta2 = solve_columns(f2, W2, kept, dependent);
  std::vector<std::vector<sym::Rational>> beta(dependent.size(), std::vector<sym::Rational>(r));
  for (std::size_t j = 0; j < dependent.size(); ++j) {
    if (!beta1[j] || !beta2[j]) {
      out.exact = out.proved = false;
      out.note = "the sampled regressor is inconsistent between primes (unlucky sample)";
      continue;
    }
    for (std::size_t b = 0; b < r; ++b) {
      const auto x = sym::rational_reconstruct(sym::crt((*beta1[j])[b], f1.prime(), (*beta2[j])[b], f2.prime()),
                                               static_cast<sym::UInt128>(f1.prime()) * f2.prime());
      if (!x) {
        out.exact = out.proved = false;
        out.note = "a regrouping coefficient is not a rational of moderate size";
        continue;
      }
      beta[j][b] = *x;
      if (!x->is_zero()) {
        combos[b].emplace_back(dependent[j], *x);
        out.map(static_cast<Eigen::Index>(b), dependent[j]) = x->to_double();
      }
    }
  }

  // Proof of every regrouping identity Y_d == sum_b beta_db Y_b.
  if (out.exact) {
    bool undecided = false;
    if (options.prove && n <= options.symbolic_proof_max_dof) {
      out.proof = "proved symbolically (trigonometric normal form of every Y_d - sum_b beta_db Y_b)";
      for (std::size_t j = 0; j < dependent.size() && out.proved; ++j) {
        for (std::size_t i = 0; i < n; ++i) {
          std::vector<std::pair<sym::Rational, sym::Expr>> terms{
              {sym::Rational(1), entries[i * p + static_cast<std::size_t>(dependent[j])]}};
          for (std::size_t b = 0; b < r; ++b)
            terms.emplace_back(-beta[j][b], entries[i * p + static_cast<std::size_t>(kept[b])]);
          const sym::ZeroVerdict verdict = sym::test_zero(sym::linear_combination(terms)).verdict;
          if (verdict == sym::ZeroVerdict::Unknown) {
            undecided = true;  // outside the decidable class (e.g. alpha = pi/3): check exactly by sampling
          } else if (verdict != sym::ZeroVerdict::Zero) {
            out.proved = false;
            out.note = "regrouping of " + model.params.list[static_cast<std::size_t>(dependent[j])].name +
                       " is not an identity";
            break;
          }
        }
      }
    }
    if (options.prove && (n > options.symbolic_proof_max_dof || undecided)) {
      // Exact check at fresh random points of GF(2^61 - 1): a false identity survives one
      // point with probability below degree / 2^61.
      const ModMatrix check = sample_regressor(tape, model, f1, 4, 97);
      out.proof = "verified exactly at 4 fresh random points over GF(2^61 - 1) (Schwartz-Zippel)";
      for (std::size_t j = 0; j < dependent.size() && out.proved; ++j) {
        for (std::size_t row = 0; row < check.rows; ++row) {
          std::uint64_t acc = check.at(row, static_cast<std::size_t>(dependent[j]));
          for (std::size_t b = 0; b < r; ++b)
            acc = f1.sub(acc, f1.mul(f1.from(beta[j][b]), check.at(row, static_cast<std::size_t>(kept[b]))));
          if (acc != 0) {
            out.proved = false;
            out.note = "regrouping of " + model.params.list[static_cast<std::size_t>(dependent[j])].name +
                       " failed the exact check";
            break;
          }
        }
      }
    }
  }

  // Floating-point cross-check on ordinary random states.
  {
    const auto np = static_cast<Eigen::Index>(p);
    Eigen::MatrixXd W(static_cast<Eigen::Index>(5 * n), np);
    for (int s = 0; s < 5; ++s)
      W.middleRows(static_cast<Eigen::Index>(s) * static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n)) =
          numeric.regressor(dyn::random_state(n, 300U + static_cast<std::uint64_t>(s)));
    const Eigen::MatrixXd WB = base_regressor_columns(W, kept);
    for (const int d : dependent) {
      Eigen::VectorXd predicted = Eigen::VectorXd::Zero(W.rows());
      for (std::size_t b = 0; b < r; ++b)
        predicted += out.map(static_cast<Eigen::Index>(b), d) * WB.col(static_cast<Eigen::Index>(b));
      const double scale = std::max(W.col(d).norm(), 1e-300);
      out.relative_residual = std::max(out.relative_residual, (predicted - W.col(d)).norm() / scale);
    }
  }

  // Definitions in the description's names, with constants as exact numbers.
  for (std::size_t b = 0; b < r; ++b) {
    BaseParameter bp;
    bp.kept = kept[b];
    bp.combination = combos[b];
    bp.name = model.params.list[static_cast<std::size_t>(bp.kept)].name + (bp.combination.size() > 1 ? "R" : "");
    std::vector<std::pair<sym::Rational, sym::Expr>> terms;
    for (const auto& [idx, coef] : bp.combination)
      terms.emplace_back(coef, model.params.list[static_cast<std::size_t>(idx)].definition);
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
