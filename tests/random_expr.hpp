// Seeded, deterministic random expressions for the sym property tests.
//
// Every generated expression comes with a Shadow: an independent record of how it was built,
// evaluated with <cmath> alone. Numeric checks compare the engine (canonical form, diff,
// expand, substitute, CompiledFunction) against the shadow, so a test never trusts the engine
// to check itself.
//
// Domain: everything generated is finite and smooth for every real point. Division and negative
// powers only use expressions bounded away from 0 (1 + a^2, 2 + sin(a), sqrt(1 + a^2), ...),
// sqrt only takes such positive expressions, and atan2 always has one argument that is
// positive, so there is no branch cut and finite differences are valid everywhere.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "sym/evaluate.hpp"
#include "sym/expr.hpp"
#include "sym/rational.hpp"

namespace dyncc::sym::test {

inline constexpr std::size_t kNumSymbols = 6;
using Point = std::array<double, kNumSymbols>;

inline const std::array<std::string, kNumSymbols>& symbol_names() {
  static const std::array<std::string, kNumSymbols> names = {"x", "y", "z", "q1", "q2", "q3"};
  return names;
}

/// The six symbols, in the order of Point.
inline const std::vector<Expr>& all_symbols() {
  static const std::vector<Expr> symbols = [] {
    std::vector<Expr> s;
    for (const std::string& n : symbol_names()) s.push_back(symbol(n));
    return s;
  }();
  return symbols;
}

// ---- the independent shadow ----

struct Shadow {
  enum class Op : std::uint8_t { Num, Var, Add, Sub, Mul, Div, Neg, Pow, Sin, Cos, Sqrt, Atan2 };
  Op op = Op::Num;
  double num = 0.0;  // Num: the value
  Rational exact;    // Num: the exact value (for rebuilding)
  int index = 0;     // Var: symbol index into Point; Pow: the exponent
  std::shared_ptr<const Shadow> a;
  std::shared_ptr<const Shadow> b;
};
using ShadowPtr = std::shared_ptr<const Shadow>;

inline double eval_shadow(const Shadow& s, const Point& p) {
  using Op = Shadow::Op;
  switch (s.op) {
    case Op::Num: return s.num;
    case Op::Var: return p[static_cast<std::size_t>(s.index)];
    case Op::Add: return eval_shadow(*s.a, p) + eval_shadow(*s.b, p);
    case Op::Sub: return eval_shadow(*s.a, p) - eval_shadow(*s.b, p);
    case Op::Mul: return eval_shadow(*s.a, p) * eval_shadow(*s.b, p);
    case Op::Div: return eval_shadow(*s.a, p) / eval_shadow(*s.b, p);
    case Op::Neg: return -eval_shadow(*s.a, p);
    case Op::Pow: return std::pow(eval_shadow(*s.a, p), s.index);
    case Op::Sin: return std::sin(eval_shadow(*s.a, p));
    case Op::Cos: return std::cos(eval_shadow(*s.a, p));
    case Op::Sqrt: return std::sqrt(eval_shadow(*s.a, p));
    case Op::Atan2: return std::atan2(eval_shadow(*s.a, p), eval_shadow(*s.b, p));
  }
  return 0.0;
}

/// An expression built twice: once through the engine, once as a shadow.
struct Sample {
  Expr expr;
  ShadowPtr shadow;
  [[nodiscard]] double operator()(const Point& p) const { return eval_shadow(*shadow, p); }
};

namespace detail {
inline ShadowPtr node(Shadow::Op op, ShadowPtr a = nullptr, ShadowPtr b = nullptr, int index = 0,
                      const Rational& exact = Rational(0)) {
  auto s = std::make_shared<Shadow>();
  s->op = op;
  s->a = std::move(a);
  s->b = std::move(b);
  s->index = index;
  s->exact = exact;
  s->num = exact.to_double();
  return s;
}
}  // namespace detail

inline Sample num(const Rational& r) { return {number(r), detail::node(Shadow::Op::Num, nullptr, nullptr, 0, r)}; }
inline Sample var(std::size_t i) {
  return {all_symbols().at(i), detail::node(Shadow::Op::Var, nullptr, nullptr, static_cast<int>(i))};
}
inline Sample operator+(const Sample& a, const Sample& b) {
  return {a.expr + b.expr, detail::node(Shadow::Op::Add, a.shadow, b.shadow)};
}
inline Sample operator-(const Sample& a, const Sample& b) {
  return {a.expr - b.expr, detail::node(Shadow::Op::Sub, a.shadow, b.shadow)};
}
inline Sample operator*(const Sample& a, const Sample& b) {
  return {a.expr * b.expr, detail::node(Shadow::Op::Mul, a.shadow, b.shadow)};
}
inline Sample operator/(const Sample& a, const Sample& b) {
  return {a.expr / b.expr, detail::node(Shadow::Op::Div, a.shadow, b.shadow)};
}
inline Sample operator-(const Sample& a) { return {-a.expr, detail::node(Shadow::Op::Neg, a.shadow)}; }
inline Sample pow(const Sample& a, int k) {
  return {sym::pow(a.expr, k), detail::node(Shadow::Op::Pow, a.shadow, nullptr, k)};
}
inline Sample sin(const Sample& a) { return {sym::sin(a.expr), detail::node(Shadow::Op::Sin, a.shadow)}; }
inline Sample cos(const Sample& a) { return {sym::cos(a.expr), detail::node(Shadow::Op::Cos, a.shadow)}; }
inline Sample sqrt(const Sample& a) { return {sym::sqrt(a.expr), detail::node(Shadow::Op::Sqrt, a.shadow)}; }
inline Sample atan2(const Sample& y, const Sample& x) {
  return {sym::atan2(y.expr, x.expr), detail::node(Shadow::Op::Atan2, y.shadow, x.shadow)};
}

// ---- the generator ----

struct GeneratorOptions {
  std::size_t num_symbols = kNumSymbols;  // use the first n of x, y, z, q1, q2, q3
  bool division = true;                   // a / (non-vanishing) and negative powers of it
  bool sqrt = true;                       // sqrt of positive expressions
  bool atan2 = true;                      // atan2 with a positive argument
  int max_exponent = 3;                   // integer powers 2..max_exponent
  bool integer_angles = false;            // trig arguments: integer combinations, no constant
};

class Generator {
 public:
  explicit Generator(std::uint64_t seed, GeneratorOptions options = {}) : rng_(seed), options_(options) {}

  std::mt19937_64& rng() { return rng_; }
  int uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

  Point point(double lo = -1.5, double hi = 1.5) {
    Point p{};
    for (double& v : p) v = real(lo, hi);
    return p;
  }

  std::size_t symbol_index() {
    return static_cast<std::size_t>(uniform(0, static_cast<int>(options_.num_symbols) - 1));
  }

  /// A small non-zero rational p/q.
  Sample rational() {
    int p = uniform(-6, 6);
    if (p == 0) p = 1;
    return num(Rational(p, uniform(1, 5)));
  }

  Sample leaf() { return chance(0.75) ? var(symbol_index()) : rational(); }

  /// A general expression of the given depth (all operations of GeneratorOptions).
  // Every draw is sequenced (braced initialisers, separate statements): in `f() + g()` the order
  // is unspecified, and g++ and clang differ, so a failing seed did not reproduce across compilers.
  Sample expression(int depth) {
    if (depth <= 0) return leaf();
    const int d = depth - 1;
    switch (uniform(0, 13)) {
      case 0:
      case 1: {
        const auto [l, r] = std::tuple{expression(d), expression(d)};
        return l + r;
      }
      case 2: {
        const auto [l, r] = std::tuple{expression(d), expression(d)};
        return l - r;
      }
      case 3:
      case 4: {
        const auto [l, r] = std::tuple{expression(d), expression(d)};
        return l * r;
      }
      case 5: {
        const Sample l = expression(d);
        return options_.division ? l / positive(d) : l * leaf();
      }
      case 6: {
        const Sample base = expression(d);
        return pow(base, uniform(2, options_.max_exponent));
      }
      case 7: {
        if (!options_.division) return -expression(d);
        const Sample base = positive(d);
        return pow(base, -uniform(1, 2));
      }
      case 8: return sin(expression(d));
      case 9: return cos(expression(d));
      case 10: {
        if (options_.sqrt) return sqrt(positive(d));
        const Sample l = sin(expression(d));
        return l * leaf();
      }
      case 11: {
        if (!options_.atan2) {
          const Sample l = cos(expression(d));
          return l + leaf();
        }
        if (chance(0.5)) {
          const auto [y, x] = std::tuple{expression(d), positive(d)};
          return atan2(y, x);
        }
        const auto [y, x] = std::tuple{positive(d), expression(d)};
        return atan2(y, x);
      }
      case 12: {
        const Sample c = rational();
        return c * expression(d);
      }
      default: return -expression(d);
    }
  }

  /// An expression bounded away from 0 everywhere (each case is >= 1/2, a product of k of them
  /// >= 2^-k), so it can divide and go under sqrt.
  Sample positive(int depth) {
    const int d = depth > 0 ? depth - 1 : 0;
    switch (uniform(0, 6)) {
      case 0: {
        const auto [n, m] = std::tuple{uniform(1, 7), uniform(1, 2)};
        return num(Rational(n, m));
      }
      case 1: return num(Rational(1)) + pow(expression(d), 2);
      case 2: return num(Rational(2)) + sin(expression(d));
      case 3: return num(Rational(2)) - cos(expression(d));
      case 4:
        return options_.sqrt ? sqrt(num(Rational(1)) + pow(expression(d), 2))
                             : num(Rational(3, 2)) + cos(expression(d));
      case 5: {
        const auto [l, r] = std::tuple{expression(d), expression(d)};
        return num(Rational(1, 2)) + pow(l, 2) + pow(r, 4);
      }
      default: {
        if (depth <= 0) return num(Rational(5, 4));
        const auto [l, r] = std::tuple{positive(d), positive(d)};
        return l * r;
      }
    }
  }

  /// A rational linear combination of one or two symbols (and maybe a rational constant): a
  /// trig argument of the decidable class. (The normal form grows exponentially with the number
  /// of angles in a product, so arguments stay short to keep the tests fast.)
  Sample linear_angle() {
    if (options_.integer_angles) {
      const int k = uniform(1, 3);
      Sample a = num(Rational(k)) * var(symbol_index());
      if (chance(0.5)) {
        const int j = chance(0.5) ? -1 : 2;
        a = a + num(Rational(j)) * var(symbol_index());
      }
      return a;
    }
    const Sample c = rational_small();
    Sample a = c * var(symbol_index());
    if (chance(0.5)) {
      if (chance(0.5)) {
        const Sample c2 = rational_small();
        a = a + c2 * var(symbol_index());
      } else {
        a = a - var(symbol_index());
      }
    }
    if (chance(0.2)) {
      const auto [n, m] = std::tuple{uniform(1, 3), uniform(1, 2)};
      a = a + num(Rational(n, m));
    }
    return a;
  }

  /// A polynomial in symbols and in sin/cos of linear angles: the class the zero test decides.
  Sample trig_polynomial(int depth) {
    if (depth <= 0) {
      switch (uniform(0, 4)) {
        case 0: return var(symbol_index());
        case 1: return rational();
        case 2: return cos(linear_angle());
        default: return sin(linear_angle());
      }
    }
    const int d = depth - 1;
    switch (uniform(0, 7)) {
      case 0:
      case 1: {
        const auto [l, r] = std::tuple{trig_polynomial(d), trig_polynomial(d)};
        return l + r;
      }
      case 2: {
        const auto [l, r] = std::tuple{trig_polynomial(d), trig_polynomial(d)};
        return l - r;
      }
      case 3:
      case 4: {
        const auto [l, r] = std::tuple{trig_polynomial(d), trig_polynomial(d)};
        return l * r;
      }
      case 5: return pow(trig_polynomial(d), 2);
      case 6: {
        const Sample c = rational();
        return c * trig_polynomial(d);
      }
      default: {
        const Sample l = sin(linear_angle());
        return l * trig_polynomial(d);
      }
    }
  }

 private:
  Sample rational_small() {
    static constexpr std::array<std::pair<int, int>, 8> kChoices = {
        {{1, 1}, {1, 1}, {2, 1}, {-1, 1}, {1, 2}, {3, 2}, {-2, 1}, {1, 3}}};
    const auto [p, q] = kChoices.at(static_cast<std::size_t>(uniform(0, 7)));
    return num(Rational(p, q));
  }

  std::mt19937_64 rng_;
  GeneratorOptions options_;
};

// ---- an equal expression built through different identities ----

/// Rebuilds the shadowed expression through textbook identities (commuted operands, the
/// binomial theorem, angle sums, double angles at half the argument). The result is equal as a
/// function but built along another path. Arguments of sqrt/atan2 and denominators are kept as
/// built, so the opaque atoms of the zero test are the same nodes on both sides.
class Rewriter {
 public:
  explicit Rewriter(std::uint64_t seed) : rng_(seed) {}

  Expr operator()(const Sample& s) { return run(s.shadow); }

 private:
  using Op = Shadow::Op;

  bool coin() { return std::bernoulli_distribution(0.5)(rng_); }

  // The engine expression of a shadow, built directly (no rewriting).
  static Expr plain(const ShadowPtr& s) {
    switch (s->op) {
      case Op::Num: return number(s->exact);
      case Op::Var: return all_symbols().at(static_cast<std::size_t>(s->index));
      case Op::Add: return plain(s->a) + plain(s->b);
      case Op::Sub: return plain(s->a) - plain(s->b);
      case Op::Mul: return plain(s->a) * plain(s->b);
      case Op::Div: return plain(s->a) / plain(s->b);
      case Op::Neg: return -plain(s->a);
      case Op::Pow: return sym::pow(plain(s->a), s->index);
      case Op::Sin: return sym::sin(plain(s->a));
      case Op::Cos: return sym::cos(plain(s->a));
      case Op::Sqrt: return sym::sqrt(plain(s->a));
      case Op::Atan2: return sym::atan2(plain(s->a), plain(s->b));
    }
    return Expr(0);
  }

  Expr run(const ShadowPtr& s) {
    switch (s->op) {
      case Op::Num:
      case Op::Var: return plain(s);
      case Op::Add: {
        if (coin()) {
          const auto [b, a] = std::tuple{run(s->b), run(s->a)};
          return b + a;
        }
        const auto [a, b] = std::tuple{run(s->a), run(s->b)};
        return a - (-b);
      }
      case Op::Sub: {
        if (coin()) {
          const auto [b, a] = std::tuple{run(s->b), run(s->a)};
          return -(b - a);
        }
        const auto [a, b] = std::tuple{run(s->a), run(s->b)};
        return a + Expr(-1) * b;
      }
      case Op::Mul: {
        if (coin()) {
          const auto [b, a] = std::tuple{run(s->b), run(s->a)};
          return b * a;
        }
        const auto [a, b] = std::tuple{run(s->a), run(s->b)};
        return -((-a) * b);
      }
      case Op::Div: return run(s->a) * sym::pow(plain(s->b), -1);
      case Op::Neg: return Expr(-1) * run(s->a);
      case Op::Pow: return power(s);
      case Op::Sin:
      case Op::Cos: return trig(s);
      case Op::Sqrt:
      case Op::Atan2: return plain(s);
    }
    return Expr(0);
  }

  Expr power(const ShadowPtr& s) {
    const int k = s->index;
    if (k < 0) return sym::pow(plain(s->a), k);  // a denominator: keep the atom
    const ShadowPtr& base = s->a;
    if (base->op == Op::Add || base->op == Op::Sub) {
      // Binomial theorem with coefficients from Pascal's rule.
      const Expr u = run(base->a);
      const Expr v = base->op == Op::Add ? run(base->b) : -run(base->b);
      std::vector<std::int64_t> c{1};
      for (int n = 1; n <= k; ++n) {
        std::vector<std::int64_t> next(static_cast<std::size_t>(n) + 1, 1);
        for (int j = 1; j < n; ++j)
          next[static_cast<std::size_t>(j)] = c[static_cast<std::size_t>(j) - 1] + c[static_cast<std::size_t>(j)];
        c = std::move(next);
      }
      Expr sum(0);
      for (int j = 0; j <= k; ++j)
        sum = sum + Expr(c[static_cast<std::size_t>(j)]) * sym::pow(u, j) * sym::pow(v, k - j);
      return sum;
    }
    Expr product(1);
    for (int j = 0; j < k; ++j) product = product * run(base);
    return product;
  }

  Expr trig(const ShadowPtr& s) {
    const bool is_sin = s->op == Op::Sin;
    const ShadowPtr& arg = s->a;
    if ((arg->op == Op::Add || arg->op == Op::Sub) && coin()) {
      // sin(u +- v) = sin u cos v +- cos u sin v;  cos(u +- v) = cos u cos v -+ sin u sin v
      const Expr u = plain(arg->a);
      const Expr v = plain(arg->b);
      const Expr sign(arg->op == Op::Add ? 1 : -1);
      if (is_sin) return sym::sin(u) * sym::cos(v) + sign * sym::cos(u) * sym::sin(v);
      return sym::cos(u) * sym::cos(v) - sign * sym::sin(u) * sym::sin(v);
    }
    // Double angle at half the argument.
    const Expr half = plain(arg) / Expr(2);
    if (is_sin) return Expr(2) * sym::sin(half) * sym::cos(half);
    return coin() ? Expr(1) - Expr(2) * sym::pow(sym::sin(half), 2)
                  : sym::pow(sym::cos(half), 2) - sym::pow(sym::sin(half), 2);
  }

  std::mt19937_64 rng_;
};

// ---- numeric helpers ----

/// Evaluates engine expressions at a Point (all six symbols are inputs).
inline double engine_eval(Expr e, const Point& p) {
  const Expr outs[1] = {e};
  return CompiledFunction(outs, all_symbols())(p)[0];
}

/// |a - b| <= rtol * max(1, |a|, |b|)
inline bool close(double a, double b, double rtol) {
  const double scale = std::max({1.0, std::abs(a), std::abs(b)});
  return std::abs(a - b) <= rtol * scale;
}

}  // namespace dyncc::sym::test
