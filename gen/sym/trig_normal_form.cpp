#include "sym/trig_normal_form.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <stdexcept>
#include <unordered_map>

namespace dyncc::sym {
namespace {

constexpr int kMaxMultiple = 64;  // largest integer multiple of a basis angle we expand

// ---- sparse polynomials over numbered variables ----
// A monomial is a sorted list of (variable << 32 | exponent).
using Monomial = std::vector<std::uint64_t>;

struct MonomialHash {
  std::size_t operator()(const Monomial& m) const {
    std::size_t h = 0x84222325CBF29CE4ULL;
    for (const std::uint64_t v : m) h = (h ^ v) * 0x100000001B3ULL;
    return h;
  }
};

using Poly = std::unordered_map<Monomial, Rational, MonomialHash>;

std::uint32_t var_of(std::uint64_t packed) { return static_cast<std::uint32_t>(packed >> 32U); }
std::uint32_t exp_of(std::uint64_t packed) { return static_cast<std::uint32_t>(packed & 0xFFFFFFFFULL); }
std::uint64_t pack(std::uint32_t var, std::uint32_t exp) { return (static_cast<std::uint64_t>(var) << 32U) | exp; }

Monomial multiply_monomials(const Monomial& a, const Monomial& b) {
  Monomial out;
  out.reserve(a.size() + b.size());
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && var_of(a[i]) < var_of(b[j]))) {
      out.push_back(a[i++]);
    } else if (i == a.size() || var_of(b[j]) < var_of(a[i])) {
      out.push_back(b[j++]);
    } else {
      const std::uint64_t e = static_cast<std::uint64_t>(exp_of(a[i])) + exp_of(b[j]);
      if (e > 100000) throw std::overflow_error("polynomial degree too large for the trigonometric normal form");
      out.push_back(pack(var_of(a[i]), static_cast<std::uint32_t>(e)));
      ++i;
      ++j;
    }
  }
  return out;
}

void add_term(Poly& p, const Monomial& m, const Rational& c) {
  if (c.is_zero()) return;
  auto [it, inserted] = p.try_emplace(m, c);
  if (!inserted) {
    it->second += c;
    if (it->second.is_zero()) p.erase(it);
  }
}

void add_scaled(Poly& into, const Poly& p, const Rational& scale) {
  for (const auto& [m, c] : p) add_term(into, m, c * scale);
}

Poly constant_poly(const Rational& c) {
  Poly p;
  if (!c.is_zero()) p.emplace(Monomial{}, c);
  return p;
}

Poly variable_poly(std::uint32_t var) {
  Poly p;
  p.emplace(Monomial{pack(var, 1)}, Rational(1));
  return p;
}

// ---- the variables: plain atoms and (sin, cos) pairs of basis angles ----
struct Angle {
  Expr atom;              // the angle is atom / scale
  Rational scale{1};      // lcm of coefficient denominators of atom across all arguments
  std::uint32_t sin_var;  // variable numbers of sin(y) and cos(y)
  std::uint32_t cos_var;
};

class NormalFormBuilder {
 public:
  NormalFormBuilder(Expr root, std::size_t work_budget) : work_budget_(work_budget) { collect_angles(root); }

  Poly run(Expr e) { return to_poly(e); }

  Expr to_expr(const Poly& p) {
    std::vector<std::pair<Rational, Expr>> terms;
    terms.reserve(p.size());
    for (const auto& [m, c] : p) {
      std::vector<Expr> factors;
      for (const std::uint64_t v : m) factors.push_back(pow(var_expr_[var_of(v)], static_cast<int>(exp_of(v))));
      terms.emplace_back(c, mul(factors));
    }
    return linear_combination(terms);
  }

  [[nodiscard]] bool exact() const { return exact_; }
  [[nodiscard]] const std::string& note() const { return note_; }

 private:
  void mark_inexact(const std::string& why) {
    if (exact_) note_ = why;
    exact_ = false;
  }

  std::uint32_t new_var(Expr printed) {
    var_expr_.push_back(printed);
    is_sin_of_angle_.push_back(-1);
    return static_cast<std::uint32_t>(var_expr_.size() - 1);
  }

  std::uint32_t plain_var(Expr atom) {
    if (const auto it = plain_vars_.find(atom); it != plain_vars_.end()) return it->second;
    const std::uint32_t v = new_var(atom);
    plain_vars_.emplace(atom, v);
    return v;
  }

  // Linear decomposition of a trig argument into (coefficient, angle atom) pairs; the
  // rational constant part uses the atom 1.
  static std::vector<std::pair<Rational, Expr>> decompose(Expr arg) {
    std::vector<std::pair<Rational, Expr>> out;
    if (arg.kind() == Kind::Add) {
      if (!arg.value().is_zero()) out.emplace_back(arg.value(), Expr(1));
      for (std::size_t i = 0; i < arg.args().size(); ++i) out.emplace_back(arg.weights()[i], arg.args()[i]);
    } else {
      auto [c, rest] = split_coefficient(arg);
      out.emplace_back(c, rest);
    }
    return out;
  }

  static bool is_polynomial_monomial(Expr atom) {
    if (atom.kind() == Kind::Symbol || atom.is_one()) return true;
    if (atom.kind() != Kind::Mul) return false;
    for (std::size_t i = 0; i < atom.args().size(); ++i) {
      if (atom.args()[i].kind() != Kind::Symbol || atom.weights()[i].is_negative()) return false;
    }
    return true;
  }

  void collect_angles(Expr root) {
    std::unordered_map<const Node*, bool> seen;
    std::vector<Expr> stack{root};
    std::unordered_map<Expr, Rational> lcm_of;
    std::vector<Expr> order;
    while (!stack.empty()) {
      const Expr e = stack.back();
      stack.pop_back();
      if (!seen.emplace(e.node(), true).second) continue;
      if (e.kind() == Kind::Sin || e.kind() == Kind::Cos) {
        for (const auto& [c, atom] : decompose(e.args()[0])) {
          auto [it, inserted] = lcm_of.try_emplace(atom, Rational(1));
          if (inserted) order.push_back(atom);
          const std::int64_t l = it->second.num();
          const std::int64_t d = c.den();
          it->second = Rational(std::lcm(l, d));
          if (!is_polynomial_monomial(atom)) {
            mark_inexact(atom.kind() == Kind::Constant
                             ? "a trigonometric argument contains a multiple of pi other than k*pi/2"
                             : "a trigonometric argument is not a linear combination of symbols");
          }
        }
      }
      for (const Expr a : e.args()) stack.push_back(a);
    }
    for (const Expr atom : order) {
      Angle a{atom, lcm_of.at(atom), 0, 0};
      const Expr y = atom / number(a.scale);
      a.sin_var = new_var(make_sin(y));
      a.cos_var = new_var(make_cos(y));
      angle_index_.emplace(atom, angles_.size());
      angles_.push_back(a);
      is_sin_of_angle_[a.sin_var] = static_cast<int>(angles_.size() - 1);
    }
  }

  static Expr make_sin(Expr y) { return sin(y); }
  static Expr make_cos(Expr y) { return cos(y); }

  [[nodiscard]] bool reducible(std::uint32_t var) const {
    return is_sin_of_angle_[var] >= 0 || square_of_.contains(var);
  }

  // Replaces sin(y)^k (k >= 2) by sin(y)^(k mod 2) * (1 - cos(y)^2)^(k div 2), and
  // sqrt(u)^k by sqrt(u)^(k mod 2) * u^(k div 2).
  Poly reduce(Poly p) {
    for (;;) {
      spend(p.size());  // one pass lowers each monomial's sin^2 by one: s^60 takes 30 passes
      bool changed = false;
      Poly out;
      out.reserve(p.size());
      for (const auto& [m, c] : p) {
        std::size_t hit = m.size();
        for (std::size_t k = 0; k < m.size(); ++k) {
          if (exp_of(m[k]) >= 2 && reducible(var_of(m[k]))) {
            hit = k;
            break;
          }
        }
        if (hit == m.size()) {
          add_term(out, m, c);
          continue;
        }
        changed = true;
        const std::uint32_t var = var_of(m[hit]);
        Monomial rest = m;
        const std::uint32_t e = exp_of(m[hit]) - 2;
        if (e == 0) {
          rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(hit));
        } else {
          rest[hit] = pack(var, e);
        }
        if (is_sin_of_angle_[var] >= 0) {
          const Angle& a = angles_[static_cast<std::size_t>(is_sin_of_angle_[var])];
          add_term(out, rest, c);  // s^2 * rest = rest - c^2 * rest
          add_term(out, multiply_monomials(rest, Monomial{pack(a.cos_var, 2)}), -c);
        } else {
          for (const auto& [mu, cu] : square_of_.at(var)) add_term(out, multiply_monomials(rest, mu), c * cu);
        }
      }
      p = std::move(out);
      if (!changed) return p;
    }
  }

  void spend(std::size_t work) {
    work_ += work;
    if (work_ > work_budget_) throw std::overflow_error("expression too large for the trigonometric normal form");
  }

  Poly multiply(const Poly& a, const Poly& b) {
    // A budget on monomial products, so that an expression whose normal form would be huge
    // (sin of a sum of 14 angles squared has 2^28 products) ends in the documented
    // overflow_error (callers fall back to sampling) instead of minutes of work and bad_alloc.
    spend(a.size() * b.size());
    Poly out;
    out.reserve(a.size() * b.size());
    for (const auto& [ma, ca] : a) {
      for (const auto& [mb, cb] : b) add_term(out, multiply_monomials(ma, mb), ca * cb);
    }
    return reduce(std::move(out));
  }

  Poly power(const Poly& base, int n) {
    Poly result = constant_poly(Rational(1));
    Poly b = base;
    while (n > 0) {
      if ((n & 1) != 0) result = multiply(result, b);
      n >>= 1;
      if (n > 0) b = multiply(b, b);
    }
    return result;
  }

  // (cos(n*y), sin(n*y)) for integer n, memoised per angle.
  const std::pair<Poly, Poly>& multiple_angle(std::size_t angle, std::int64_t n) {
    const auto key = std::make_pair(angle, n);
    if (const auto it = multiples_.find(key); it != multiples_.end()) return it->second;
    std::pair<Poly, Poly> value;
    const Angle& a = angles_[angle];
    if (n == 0) {
      value = {constant_poly(Rational(1)), Poly{}};
    } else if (n == 1) {
      value = {variable_poly(a.cos_var), variable_poly(a.sin_var)};
    } else if (n < 0) {
      const auto& pos = multiple_angle(angle, -n);
      Poly neg_sin;
      add_scaled(neg_sin, pos.second, Rational(-1));
      value = {pos.first, neg_sin};
    } else {
      // (c + i s)^n = (c + i s)^(n-1) * (c + i s)
      const auto prev = multiple_angle(angle, n - 1);
      const Poly c = variable_poly(a.cos_var);
      const Poly s = variable_poly(a.sin_var);
      Poly re = multiply(prev.first, c);
      add_scaled(re, multiply(prev.second, s), Rational(-1));
      Poly im = multiply(prev.first, s);
      add_scaled(im, multiply(prev.second, c), Rational(1));
      value = {std::move(re), std::move(im)};
    }
    return multiples_.emplace(key, std::move(value)).first->second;
  }

  // (cos(arg), sin(arg)) as polynomials.
  std::pair<Poly, Poly> trig_of(Expr arg) {
    Poly re = constant_poly(Rational(1));
    Poly im;
    for (const auto& [c, atom] : decompose(arg)) {
      const std::size_t j = angle_index_.at(atom);
      const Rational n = c * angles_[j].scale;
      if (!n.is_integer() || n.num() > kMaxMultiple || n.num() < -kMaxMultiple) {
        throw std::overflow_error("angle multiple too large for the trigonometric normal form");
      }
      const auto& [cn, sn] = multiple_angle(j, n.num());
      // (re + i im) * (cn + i sn)
      Poly new_re = multiply(re, cn);
      add_scaled(new_re, multiply(im, sn), Rational(-1));
      Poly new_im = multiply(re, sn);
      add_scaled(new_im, multiply(im, cn), Rational(1));
      re = std::move(new_re);
      im = std::move(new_im);
    }
    return {std::move(re), std::move(im)};
  }

  Poly to_poly(Expr e) {
    if (const auto it = memo_.find(e.node()); it != memo_.end()) return it->second;
    Poly result;
    switch (e.kind()) {
      case Kind::Number: result = constant_poly(e.value()); break;
      case Kind::Symbol:
      case Kind::Constant: result = variable_poly(plain_var(e)); break;
      case Kind::Add: {
        result = constant_poly(e.value());
        for (std::size_t i = 0; i < e.args().size(); ++i) add_scaled(result, to_poly(e.args()[i]), e.weights()[i]);
        break;
      }
      case Kind::Mul: {
        result = constant_poly(e.value());
        for (std::size_t i = 0; i < e.args().size(); ++i) {
          const std::int64_t n = e.weights()[i].num();
          if (n > 0) {
            result = multiply(result, power(to_poly(e.args()[i]), static_cast<int>(n)));
          } else {
            mark_inexact("the expression divides by a non-constant");
            result = multiply(result, power(variable_poly(plain_var(pow(e.args()[i], -1))), static_cast<int>(-n)));
          }
        }
        break;
      }
      case Kind::Sin: result = trig_of(e.args()[0]).second; break;
      case Kind::Cos: result = trig_of(e.args()[0]).first; break;
      case Kind::Sqrt: {
        // An opaque atom r with the relation r^2 = u, so that e.g. (sqrt(u) + 1)^2 - u - 2*sqrt(u) - 1
        // reduces to 0. (The relations r^2 - u have pairwise coprime leading terms with each
        // other and with s^2 + c^2 - 1, so they stay a Groebner basis.)
        mark_inexact("the expression contains sqrt or atan2");
        const std::uint32_t v = plain_var(e);
        if (!square_of_.contains(v)) {
          Poly u = to_poly(e.args()[0]);
          square_of_.emplace(v, std::move(u));
        }
        result = variable_poly(v);
        break;
      }
      case Kind::Atan2:
        mark_inexact("the expression contains sqrt or atan2");
        result = variable_poly(plain_var(e));
        break;
    }
    return memo_.emplace(e.node(), std::move(result)).first->second;
  }

  struct PairHash {
    std::size_t operator()(const std::pair<std::size_t, std::int64_t>& k) const {
      return k.first * 0x9E3779B97F4A7C15ULL ^ static_cast<std::size_t>(k.second);
    }
  };

  std::vector<Expr> var_expr_;
  std::vector<int> is_sin_of_angle_;
  std::unordered_map<Expr, std::uint32_t> plain_vars_;
  std::vector<Angle> angles_;
  std::unordered_map<Expr, std::size_t> angle_index_;
  std::unordered_map<std::pair<std::size_t, std::int64_t>, std::pair<Poly, Poly>, PairHash> multiples_;
  std::unordered_map<const Node*, Poly> memo_;
  std::unordered_map<std::uint32_t, Poly> square_of_;  // sqrt(u)'s variable -> u
  bool exact_ = true;
  std::string note_;
  std::size_t work_budget_;
  std::size_t work_ = 0;  // monomial operations so far
};

// A value and a bound on its rounding error (first-order running error analysis). Sampling
// uses it to tell a real non-zero value from rounding noise: an expression that is identically
// zero but outside the decidable class, like (sqrt((x+10)^2) - sqrt(x^2+20x+100))*(x+10)^8,
// evaluates to ~1e-6 at random points, and an absolute threshold reported that noise as a
// witness that the expression is "not identically zero".
struct Bounded {
  double value = 0.0;
  double error = 0.0;
};

class BoundedEvaluator {
 public:
  BoundedEvaluator(const std::vector<Expr>& symbols, const std::vector<double>& point) {
    for (std::size_t i = 0; i < symbols.size(); ++i) memo_.emplace(symbols[i].node(), Bounded{point[i], 0.0});
  }

  Bounded operator()(Expr e) {
    if (const auto it = memo_.find(e.node()); it != memo_.end()) return it->second;
    constexpr double eps = std::numeric_limits<double>::epsilon();
    constexpr double inf = std::numeric_limits<double>::infinity();
    const auto args = e.args();
    Bounded r;
    switch (e.kind()) {
      case Kind::Number:
        r.value = e.value().to_double();
        r.error = eps * std::abs(r.value);
        break;
      case Kind::Constant:
        r.value = std::numbers::pi;
        r.error = eps * r.value;
        break;
      case Kind::Symbol: r = {std::numeric_limits<double>::quiet_NaN(), inf}; break;  // every symbol is an input
      case Kind::Add: {
        r.value = e.value().to_double();
        double magnitude = std::abs(r.value);
        for (std::size_t i = 0; i < args.size(); ++i) {
          const Bounded a = (*this)(args[i]);
          const double w = e.weights()[i].to_double();
          r.value += w * a.value;
          r.error += std::abs(w) * a.error;
          magnitude += std::abs(w * a.value);
        }
        // Each weight, product and partial sum rounds once.
        r.error += 3.0 * static_cast<double>(args.size() + 1) * eps * magnitude;
        break;
      }
      case Kind::Mul: {
        r.value = e.value().to_double();
        double relative = eps;
        bool exact_zero = false;
        for (std::size_t i = 0; i < args.size(); ++i) {
          const Bounded a = (*this)(args[i]);
          const double n = e.weights()[i].to_double();
          r.value *= std::pow(a.value, n);
          if (a.value == 0.0) {
            exact_zero = exact_zero || (a.error == 0.0 && n > 0);
            relative = inf;
          } else {
            relative += std::abs(n) * (a.error / std::abs(a.value)) + (std::abs(n) + 1.0) * eps;
          }
        }
        r.error = exact_zero ? 0.0 : std::abs(r.value) * relative;
        if (std::isnan(r.error)) r.error = inf;
        break;
      }
      case Kind::Sin:
      case Kind::Cos: {
        const Bounded a = (*this)(args[0]);
        r.value = e.kind() == Kind::Sin ? std::sin(a.value) : std::cos(a.value);
        r.error = a.error + eps;  // |derivative| <= 1
        break;
      }
      case Kind::Sqrt: {
        const Bounded a = (*this)(args[0]);
        r.value = std::sqrt(a.value);
        r.error = a.error == 0.0 ? eps * r.value : (r.value > 0.0 ? a.error / (2.0 * r.value) + eps * r.value : inf);
        break;
      }
      case Kind::Atan2: {
        const Bounded y = (*this)(args[0]);
        const Bounded x = (*this)(args[1]);
        r.value = std::atan2(y.value, x.value);
        const double d = x.value * x.value + y.value * y.value;
        r.error =
            d > 0.0 ? (std::abs(x.value) * y.error + std::abs(y.value) * x.error) / d + eps * std::abs(r.value) : inf;
        break;
      }
    }
    memo_.emplace(e.node(), r);
    return r;
  }

 private:
  std::unordered_map<const Node*, Bounded> memo_;
};

// Samples e at pseudo-random points and keeps the most convincing one: a value clearly above
// its rounding error bound if there is one (returns true then), the largest |value| otherwise.
bool find_witness(Expr e, ZeroTestResult& result) {
  constexpr double kSafety = 4.0;  // |value| must exceed this multiple of its error bound
  const std::vector<Expr> symbols = free_symbols(e);
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> dist(-2.0, 2.0);
  std::vector<double> point(symbols.size());
  double best = -1.0;
  bool best_significant = false;
  for (int trial = 0; trial < 32; ++trial) {
    for (double& v : point) v = std::round(dist(rng) * 1000.0) / 1000.0;  // short, reproducible numbers
    const Bounded b = BoundedEvaluator(symbols, point)(e);
    if (!std::isfinite(b.value)) continue;
    const bool significant = std::abs(b.value) > kSafety * b.error;
    if ((significant && !best_significant) || (significant == best_significant && std::abs(b.value) > best)) {
      best = std::abs(b.value);
      best_significant = significant;
      result.witness_value = b.value;
      result.witness.clear();
      for (std::size_t i = 0; i < symbols.size(); ++i) result.witness.emplace_back(symbols[i].name(), point[i]);
    }
  }
  return best_significant;
}

}  // namespace

TrigNormalForm trig_normal_form(Expr e, std::size_t work_budget) {
  NormalFormBuilder builder(e, work_budget);
  const Poly p = builder.run(e);
  return {builder.to_expr(p), builder.exact(), p.size()};
}

ZeroTestResult test_zero(Expr e, std::size_t work_budget) {
  ZeroTestResult result;
  if (e.is_zero()) {
    result.verdict = ZeroVerdict::Zero;
    result.proved = true;
    return result;
  }
  try {
    NormalFormBuilder builder(e, work_budget);
    const Poly p = builder.run(e);
    if (p.empty()) {
      result.verdict = ZeroVerdict::Zero;
      result.proved = true;  // zero under opaque atoms is zero for every value of the atoms
      return result;
    }
    const bool significant = find_witness(e, result);
    if (builder.exact()) {
      result.verdict = ZeroVerdict::NonZero;
      result.proved = true;
      return result;
    }
    result.note = builder.note();
    result.verdict = significant ? ZeroVerdict::NonZero : ZeroVerdict::Unknown;
  } catch (const std::overflow_error& ex) {
    // Not decidable exactly: fall back to sampling, which can only show non-zero.
    result.note = ex.what();
    result.verdict = find_witness(e, result) ? ZeroVerdict::NonZero : ZeroVerdict::Unknown;
  }
  return result;
}

}  // namespace dyncc::sym
