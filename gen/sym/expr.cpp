#include "sym/expr.hpp"

#include <algorithm>
#include <deque>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "sym/node.hpp"
#include "sym/wide_gcd.hpp"

namespace dyncc::sym {
namespace {

std::size_t mix(std::size_t h, std::size_t v) {
  // 64-bit hash combine (boost-style with a better multiplier); deterministic by construction.
  h ^= v + 0x9E3779B97F4A7C15ULL + (h << 12U) + (h >> 4U);
  return h * 0xFF51AFD7ED558CCDULL;
}

std::size_t fnv1a(std::string_view s) {
  std::size_t h = 1469598103934665603ULL;
  for (const char c : s) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return h;
}

std::size_t compute_hash(const Node& n) {
  std::size_t h = mix(0x51ED270B27D3F1A5ULL, static_cast<std::size_t>(n.kind));
  h = mix(h, n.value.hash());
  if (!n.name.empty()) h = mix(h, fnv1a(n.name));
  for (const Expr a : n.args) h = mix(h, a.hash());
  for (const Rational& w : n.weights) h = mix(h, w.hash());
  return h;
}

struct NodePtrHash {
  std::size_t operator()(const Node* n) const { return n->hash; }
};
struct NodePtrEq {
  bool operator()(const Node* a, const Node* b) const {
    return a->kind == b->kind && a->hash == b->hash && a->value == b->value && a->name == b->name &&
           a->args == b->args && a->weights == b->weights;
  }
};

struct Pool {
  std::deque<Node> storage;
  std::unordered_set<const Node*, NodePtrHash, NodePtrEq> table;
  Pool() { table.reserve(1U << 16U); }
};

Pool& pool() {
  static Pool* const instance = new Pool();  // never destroyed: nodes outlive every static user
  return *instance;
}

const Node* zero_node() {
  static const Node* const zero = number(Rational(0)).node();
  return zero;
}

// Deep structural comparison; only reached when two distinct nodes share a 64-bit hash.
int structural_compare(Expr a, Expr b) {
  if (a == b) return 0;
  const Node& x = *a.node();
  const Node& y = *b.node();
  if (x.kind != y.kind) return x.kind < y.kind ? -1 : 1;
  if (x.value != y.value) return x.value < y.value ? -1 : 1;
  if (x.name != y.name) return x.name < y.name ? -1 : 1;
  if (x.args.size() != y.args.size()) return x.args.size() < y.args.size() ? -1 : 1;
  for (std::size_t i = 0; i < x.args.size(); ++i) {
    const int c = canonical_less(x.args[i], y.args[i]) ? -1 : (canonical_less(y.args[i], x.args[i]) ? 1 : 0);
    if (c != 0) return c;
  }
  for (std::size_t i = 0; i < x.weights.size(); ++i) {
    if (x.weights[i] != y.weights[i]) return x.weights[i] < y.weights[i] ? -1 : 1;
  }
  return 0;
}

using WeightedList = std::vector<std::pair<Expr, Rational>>;

// Sorts by canonical order and merges equal expressions by adding their weights; drops zeros.
void sort_and_merge(WeightedList& list) {
  std::sort(list.begin(), list.end(), [](const auto& l, const auto& r) { return canonical_less(l.first, r.first); });
  std::size_t out = 0;
  for (std::size_t i = 0; i < list.size();) {
    Rational w = list[i].second;
    std::size_t j = i + 1;
    while (j < list.size() && list[j].first == list[i].first) w += list[j++].second;
    if (!w.is_zero()) list[out++] = {list[i].first, w};
    i = j;
  }
  list.resize(out);
}

Expr make_mul_node(const Rational& coef, const WeightedList& factors) {
  Node n;
  n.kind = Kind::Mul;
  n.value = coef;
  n.args.reserve(factors.size());
  n.weights.reserve(factors.size());
  for (const auto& [base, exp] : factors) {
    n.args.push_back(base);
    n.weights.push_back(exp);
  }
  return intern(std::move(n));
}

// Adds e (times scale) into an Add accumulator.
void accumulate_term(Expr e, const Rational& scale, Rational& constant, WeightedList& terms) {
  switch (e.kind()) {
    case Kind::Number: constant += scale * e.value(); return;
    case Kind::Add:
      constant += scale * e.value();
      for (std::size_t i = 0; i < e.args().size(); ++i) terms.emplace_back(e.args()[i], scale * e.weights()[i]);
      return;
    default: {
      auto [c, rest] = split_coefficient(e);
      terms.emplace_back(rest, scale * c);
      return;
    }
  }
}

Expr build_add(Rational constant, WeightedList& terms) {
  sort_and_merge(terms);
  if (terms.empty()) return number(constant);
  if (constant.is_zero() && terms.size() == 1) return number(terms[0].second) * terms[0].first;
  Node n;
  n.kind = Kind::Add;
  n.value = constant;
  n.args.reserve(terms.size());
  n.weights.reserve(terms.size());
  for (const auto& [t, c] : terms) {
    n.args.push_back(t);
    n.weights.push_back(c);
  }
  return intern(std::move(n));
}

// Exponents are stored as Rationals but used as int (pow, diff, expand, the normal form):
// merged exponents such as ((x^64)^64)^64... must stay in int range instead of being truncated.
int checked_exponent(const Rational& exponent) {
  if (exponent.num() > std::numeric_limits<int>::max() || exponent.num() < -std::numeric_limits<int>::max()) {
    throw RationalOverflow("exponent out of range");
  }
  return static_cast<int>(exponent.num());
}

// A sum used as a factor is stored primitive: its coefficients (and constant) have no common
// rational factor and its first term is positive; the content c (sum == c * primitive) moves
// into the product's coefficient. Without this, (2*x + 2*y)*z and 2*((x + y)*z) were distinct
// nodes (multiplication was not associative on nodes), as were (y - x)*z and -((x - y)*z), and
// "q/(3*(s + 2))" did not parse back to the node it was printed from.
struct PrimitivePart {
  Rational content;
  Expr sum;
  bool exact = true;  // false: the sum's primitive form does not fit 64-bit coefficients
};

PrimitivePart primitive_part(Expr sum) {
  constexpr Int128 kMax = std::numeric_limits<std::int64_t>::max();
  Int128 g = 0;  // gcd of the numerators
  Int128 l = 1;  // lcm of the denominators; 0 once it does not fit (then they stay as they are)
  auto visit = [&](const Rational& w) {
    if (w.is_zero()) return;
    g = wide_gcd(g, w.num());
    if (l != 0) {
      l = l / wide_gcd(l, w.den()) * w.den();
      if (l > kMax) l = 0;
    }
  };
  visit(sum.value());
  for (const Rational& w : sum.weights()) visit(w);
  if (g > kMax) g = 1;  // every numerator is INT64_MIN
  const bool lcm_fits = l != 0;
  if (l == 0) l = 1;
  Rational content(static_cast<std::int64_t>(g), static_cast<std::int64_t>(l));
  if (sum.weights()[0].is_negative()) content = -content;
  const auto divided_by = [&sum](const Rational& c) {
    Node n;
    n.kind = Kind::Add;
    n.value = sum.value() / c;
    n.weights.reserve(sum.weights().size());
    for (const Rational& w : sum.weights()) n.weights.push_back(w / c);
    n.args.assign(sum.args().begin(), sum.args().end());  // same terms, so the same canonical order
    return n;
  };
  if (content.is_one()) return {content, sum, lcm_fits};
  if (lcm_fits) {
    try {
      return {content, intern(divided_by(content)), true};
    } catch (const RationalOverflow&) {
    }
  }
  // Extreme coefficients (clearing the denominators overflows): take out the sign and the gcd of
  // the numerators only. build_mul then moves a product's coefficient into such a sum (see
  // distribute_into_inexact_sum), so 2*(s*sqrt(s)) and (2*s)*sqrt(s) still meet in one node.
  Rational integer_content(static_cast<std::int64_t>(g));
  if (sum.weights()[0].is_negative()) integer_content = -integer_content;
  if (integer_content.is_one()) return {integer_content, sum, false};
  try {
    return {integer_content, intern(divided_by(integer_content)), false};
  } catch (const RationalOverflow&) {
    return {Rational(1), sum, false};
  }
}

// A product c * s * rest with s a sum whose primitive form does not fit (so its content cannot be
// taken out and kept in c): c goes into s instead, the form that parsing "c*s*rest" left to right
// produces (c*s is distributed before rest is multiplied in). Only the first such sum.
void distribute_into_inexact_sum(Rational& coef, WeightedList& factors) {
  if (coef.is_one()) return;
  for (auto& [base, exp] : factors) {
    if (base.kind() != Kind::Add || !exp.is_one() || primitive_part(base).exact) continue;
    try {
      WeightedList terms;
      terms.reserve(base.args().size());
      for (std::size_t i = 0; i < base.args().size(); ++i) terms.emplace_back(base.args()[i], coef * base.weights()[i]);
      base = build_add(coef * base.value(), terms);
      coef = Rational(1);
      sort_and_merge(factors);
    } catch (const RationalOverflow&) {
    }
    return;
  }
}

void accumulate_factor(Expr e, const Rational& exponent, Rational& coef, WeightedList& factors) {
  switch (e.kind()) {
    case Kind::Number: {
      if (!exponent.is_integer()) throw std::domain_error("non-integer power of a number");
      if (e.value().is_zero() && exponent.is_negative()) throw std::domain_error("division by zero");
      coef *= e.value().pow(checked_exponent(exponent));
      return;
    }
    case Kind::Mul:
      coef *= e.value().pow(checked_exponent(exponent));
      for (std::size_t i = 0; i < e.args().size(); ++i) factors.emplace_back(e.args()[i], e.weights()[i] * exponent);
      return;
    case Kind::Add: {
      const PrimitivePart part = primitive_part(e);
      coef *= part.content.pow(checked_exponent(exponent));
      factors.emplace_back(part.sum, exponent);
      return;
    }
    default: factors.emplace_back(e, exponent); return;
  }
}

// sqrt(u)^k * u^m with k and m of opposite signs (sqrt(u)/u, u*sqrt(u)^-1) is rewritten as
// sqrt(u)^(k + 2m), which the pull-out rule in build_mul then splits as u^w * sqrt(u)^r with w and
// r of one sign. Without it, 1/sqrt(u) and sqrt(u)/u were different nodes, so (a/d)*d != a for
// a = 1/sqrt(u), d = sqrt(u). Only sums and atoms as u (a product u is split into its factors).
bool merge_sqrt_with_its_square(Rational& coef, WeightedList& factors) {
  for (auto& [base, k] : factors) {
    if (base.kind() != Kind::Sqrt || k.is_zero()) continue;
    const Expr u = base.args()[0];
    if (u.kind() == Kind::Mul || u.kind() == Kind::Number) continue;
    const PrimitivePart part = u.kind() == Kind::Add ? primitive_part(u) : PrimitivePart{Rational(1), u};
    const Rational& content = part.content;
    const Expr stored = part.sum;
    for (auto& [other, m] : factors) {
      if (other != stored || m.is_zero() || k.is_negative() == m.is_negative()) continue;
      // stored^m = (u / content)^m
      coef = coef / content.pow(checked_exponent(m));
      k += m * Rational(2);
      m = Rational(0);
      return true;
    }
  }
  return false;
}

Expr build_mul(Rational coef, WeightedList& factors) {
  if (coef.is_zero()) return Expr(0);
  for (;;) {
    sort_and_merge(factors);
    // sqrt(u)^e with |e| >= 2: pull whole powers of u out so sqrt(u)^2 == u.
    bool changed = false;
    for (std::size_t i = 0; i < factors.size(); ++i) {
      auto& [base, exp] = factors[i];
      if (base.kind() == Kind::Sqrt && (exp.num() >= 2 || exp.num() <= -2)) {
        const std::int64_t whole = exp.num() / 2;
        const Expr u = base.args()[0];
        exp = Rational(exp.num() - 2 * whole);
        accumulate_factor(u, Rational(whole), coef, factors);
        changed = true;
        break;
      }
    }
    if (!changed) changed = merge_sqrt_with_its_square(coef, factors);
    if (!changed) break;
  }
  for (const auto& [base, exp] : factors) checked_exponent(exp);
  if (coef.is_zero()) return Expr(0);
  distribute_into_inexact_sum(coef, factors);
  if (factors.empty()) return number(coef);
  if (factors.size() == 1 && factors[0].second.is_one()) {
    const Expr base = factors[0].first;
    if (coef.is_one()) return base;
    if (base.kind() == Kind::Add) {  // distribute a number over a sum
      Rational constant = coef * base.value();
      WeightedList terms;
      terms.reserve(base.args().size());
      for (std::size_t i = 0; i < base.args().size(); ++i) terms.emplace_back(base.args()[i], coef * base.weights()[i]);
      return build_add(constant, terms);
    }
  }
  return make_mul_node(coef, factors);
}

// Splits arg into rest + k*pi with k rational.
std::pair<Expr, Rational> split_pi_multiple(Expr arg) {
  const Expr p = pi();
  if (arg == p) return {Expr(0), Rational(1)};
  if (arg.kind() == Kind::Mul && arg.args().size() == 1 && arg.args()[0] == p && arg.weights()[0].is_one()) {
    return {Expr(0), arg.value()};
  }
  if (arg.kind() == Kind::Add) {
    for (std::size_t i = 0; i < arg.args().size(); ++i) {
      if (arg.args()[i] == p) return {arg - number(arg.weights()[i]) * p, arg.weights()[i]};
    }
  }
  return {arg, Rational(0)};
}

// k modulo 2, in (-1, 1]; exact in 128 bits (2*den may not fit in int64), and the result
// always fits because |numerator| <= den.
Rational reduce_mod_two(const Rational& k) {
  const Int128 d = k.den();
  Int128 r = static_cast<Int128>(k.num()) % (2 * d);
  if (r < 0) r += 2 * d;  // [0, 2d)
  if (r > d) r -= 2 * d;  // (-d, d]
  return Rational(static_cast<std::int64_t>(r), k.den());
}

enum class TrigKind : std::uint8_t { Sin, Cos };

Expr make_function(Kind kind, std::vector<Expr> args) {
  Node n;
  n.kind = kind;
  n.args = std::move(args);
  return intern(std::move(n));
}

// sin/cos(rest + k*pi) in canonical form. The sign of the argument is normalised first
// (odd/even symmetry) and only then is k reduced, so f(-a) and f(a) always meet the same
// reduction. (Reducing k into [0, 2) first and flipping the sign afterwards turned sin(-(x + pi/3))
// into -sin(x - 5*pi/3), a different node from -sin(x + pi/3), and cos(pi/3 - x) did not survive
// a print/parse round trip.) Exact multiples of pi/2 are pulled out; other rational multiples
// stay in the argument, reduced into (-1, 1]. They are deliberately not rewritten by quarter
// turns (sin(x + 2*pi/3) -> cos(x + pi/6)): the zero test treats pi/L as a free basis angle, and
// such value-specific rewrites would make identities like the angle-sum formula at pi/3
// unprovable.
Expr trig(TrigKind which, Expr arg) {
  auto [rest, k] = split_pi_multiple(arg);
  bool negate = false;
  if (has_negative_sign(rest)) {  // sin(-a) = -sin(a), cos(-a) = cos(a)
    rest = -rest;
    k = -k;
    negate = which == TrigKind::Sin;
  }
  k = reduce_mod_two(k);
  if (rest.is_zero() && k.is_negative()) {  // a pure multiple of pi: the sign of k decides
    k = -k;
    if (which == TrigKind::Sin) negate = !negate;
  }
  const Int128 twice_num = static_cast<Int128>(k.num()) * 2;
  if (twice_num % k.den() != 0) {  // not a multiple of pi/2
    const Expr e = make_function(which == TrigKind::Sin ? Kind::Sin : Kind::Cos, {rest + number(k) * pi()});
    return negate ? -e : e;
  }
  // f(r + q*pi/2) = +-g(r), g = f for even q and the other function for odd q (k in (-1, 1]).
  const int q = static_cast<int>(((twice_num / k.den()) % 4 + 4) % 4);
  const bool use_sin = (which == TrigKind::Sin) == (q % 2 == 0);
  if (which == TrigKind::Sin ? q >= 2 : (q == 1 || q == 2)) negate = !negate;
  Expr result;
  if (rest.is_zero()) {
    result = use_sin ? Expr(0) : Expr(1);
  } else {
    result = make_function(use_sin ? Kind::Sin : Kind::Cos, {rest});
  }
  return negate ? -result : result;
}

bool rational_sqrt(const Rational& v, Rational& out) {
  auto isqrt = [](std::int64_t n, std::int64_t& r) {
    if (n < 0) return false;
    // Squares in 128 bits: near INT64_MAX, (x + 1)^2 overflowed int64, which looped forever
    // (sqrt(9223372036854775807) hung) and could report a non-square as a perfect square.
    auto x = static_cast<Int128>(__builtin_sqrt(static_cast<double>(n)));
    while (x > 0 && x * x > n) --x;
    while ((x + 1) * (x + 1) <= n) ++x;
    r = static_cast<std::int64_t>(x);
    return x * x == n;
  };
  std::int64_t n = 0;
  std::int64_t d = 0;
  if (!isqrt(v.num(), n) || !isqrt(v.den(), d)) return false;
  out = Rational(n, d);
  return true;
}

}  // namespace

Expr intern(Node&& node) {
  node.hash = compute_hash(node);
  Pool& p = pool();
  if (const auto it = p.table.find(&node); it != p.table.end()) return Expr(*it);
  p.storage.push_back(std::move(node));
  const Node* stored = &p.storage.back();
  p.table.insert(stored);
  return Expr(stored);
}

Expr::Expr() : node_(zero_node()) {}
Expr::Expr(int value) : Expr(number(Rational(value))) {}
Expr::Expr(std::int64_t value) : Expr(number(Rational(value))) {}
Expr::Expr(const Rational& value) : Expr(number(value)) {}

Kind Expr::kind() const { return node_->kind; }
std::size_t Expr::hash() const { return node_->hash; }
bool Expr::is_zero() const { return node_->kind == Kind::Number && node_->value.is_zero(); }
bool Expr::is_one() const { return node_->kind == Kind::Number && node_->value.is_one(); }
const Rational& Expr::value() const { return node_->value; }
const std::string& Expr::name() const { return node_->name; }
std::span<const Expr> Expr::args() const { return node_->args; }
std::span<const Rational> Expr::weights() const { return node_->weights; }

std::size_t Expr::dag_size() const {
  std::unordered_set<const Node*> seen;
  std::vector<const Node*> stack{node_};
  while (!stack.empty()) {
    const Node* n = stack.back();
    stack.pop_back();
    if (!seen.insert(n).second) continue;
    for (const Expr a : n->args) stack.push_back(a.node());
  }
  return seen.size();
}

Expr number(const Rational& value) {
  Node n;
  n.kind = Kind::Number;
  n.value = value;
  return intern(std::move(n));
}

Expr symbol(std::string_view name) {
  if (name == "pi") return pi();
  Node n;
  n.kind = Kind::Symbol;
  n.name = std::string(name);
  return intern(std::move(n));
}

Expr pi() {
  static const Expr p = [] {
    Node n;
    n.kind = Kind::Constant;
    n.name = "pi";
    return intern(std::move(n));
  }();
  return p;
}

Expr add(std::span<const Expr> terms) {
  Rational constant;
  WeightedList list;
  list.reserve(terms.size() + 4);
  for (const Expr t : terms) accumulate_term(t, Rational(1), constant, list);
  return build_add(constant, list);
}

Expr linear_combination(std::span<const std::pair<Rational, Expr>> terms, const Rational& constant) {
  Rational c = constant;
  WeightedList list;
  list.reserve(terms.size() + 4);
  for (const auto& [w, t] : terms) {
    if (!w.is_zero()) accumulate_term(t, w, c, list);
  }
  return build_add(c, list);
}

Expr mul(std::span<const Expr> factors) {
  Rational coef(1);
  WeightedList list;
  list.reserve(factors.size() + 4);
  for (const Expr f : factors) {
    if (f.is_zero()) return Expr(0);
    accumulate_factor(f, Rational(1), coef, list);
  }
  return build_mul(coef, list);
}

Expr pow(Expr base, int exponent) {
  if (exponent == 0) return Expr(1);
  if (exponent == 1) return base;
  if (base.is_zero()) {
    if (exponent < 0) throw std::domain_error("division by zero");
    return Expr(0);
  }
  Rational coef(1);
  WeightedList list;
  accumulate_factor(base, Rational(exponent), coef, list);
  return build_mul(coef, list);
}

Expr sin(Expr arg) { return trig(TrigKind::Sin, arg); }
Expr cos(Expr arg) { return trig(TrigKind::Cos, arg); }

Expr sqrt(Expr arg) {
  if (arg.is_number()) {
    if (arg.value().is_negative()) throw std::domain_error("square root of a negative number");
    Rational r;
    if (rational_sqrt(arg.value(), r)) return number(r);
  }
  return make_function(Kind::Sqrt, {arg});
}

Expr atan2(Expr y, Expr x) {
  if (y.is_zero() && x.is_number() && !x.value().is_negative() && !x.is_zero()) return Expr(0);
  return make_function(Kind::Atan2, {y, x});
}

Expr operator+(Expr a, Expr b) {
  if (a.is_zero()) return b;
  if (b.is_zero()) return a;
  if (a.is_number() && b.is_number()) return number(a.value() + b.value());
  const Expr ops[2] = {a, b};
  return add(ops);
}

Expr operator-(Expr a) {
  if (a.is_number()) return number(-a.value());
  Rational coef(-1);
  WeightedList list;
  accumulate_factor(a, Rational(1), coef, list);
  return build_mul(coef, list);
}

Expr operator-(Expr a, Expr b) { return a + (-b); }

Expr operator*(Expr a, Expr b) {
  if (a.is_zero() || b.is_zero()) return Expr(0);
  if (a.is_one()) return b;
  if (b.is_one()) return a;
  if (a.is_number() && b.is_number()) return number(a.value() * b.value());
  const Expr ops[2] = {a, b};
  return mul(ops);
}

Expr operator/(Expr a, Expr b) {
  if (b.is_zero()) throw std::domain_error("division by zero");
  return a * pow(b, -1);
}

std::pair<Rational, Expr> split_coefficient(Expr e) {
  if (e.is_number()) return {e.value(), Expr(1)};
  if (e.kind() != Kind::Mul || e.value().is_one()) return {Rational(1), e};
  const auto args = e.args();
  const auto weights = e.weights();
  if (args.size() == 1 && weights[0].is_one()) return {e.value(), args[0]};
  WeightedList factors;
  factors.reserve(args.size());
  for (std::size_t i = 0; i < args.size(); ++i) factors.emplace_back(args[i], weights[i]);
  return {e.value(), make_mul_node(Rational(1), factors)};
}

bool has_negative_sign(Expr e) {
  switch (e.kind()) {
    case Kind::Number:
    case Kind::Mul: return e.value().is_negative();
    case Kind::Add: return e.weights()[0].is_negative();
    default: return false;
  }
}

bool canonical_less(Expr a, Expr b) {
  if (a == b) return false;
  if (a.hash() != b.hash()) return a.hash() < b.hash();
  return structural_compare(a, b) < 0;
}

bool natural_less(std::string_view a, std::string_view b) {
  std::size_t i = 0;
  std::size_t j = 0;
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      std::size_t i2 = i;
      std::size_t j2 = j;
      while (i2 < a.size() && a[i2] == '0') ++i2;
      while (j2 < b.size() && b[j2] == '0') ++j2;
      std::size_t ie = i2;
      std::size_t je = j2;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      if (ie - i2 != je - j2) return ie - i2 < je - j2;
      const int c = a.substr(i2, ie - i2).compare(b.substr(j2, je - j2));
      if (c != 0) return c < 0;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

std::vector<Expr> free_symbols(Expr e) {
  std::unordered_set<const Node*> seen;
  std::vector<Expr> stack{e};
  std::vector<Expr> found;
  while (!stack.empty()) {
    const Expr x = stack.back();
    stack.pop_back();
    if (!seen.insert(x.node()).second) continue;
    if (x.kind() == Kind::Symbol) found.push_back(x);
    for (const Expr a : x.args()) stack.push_back(a);
  }
  std::sort(found.begin(), found.end(), [](Expr l, Expr r) { return natural_less(l.name(), r.name()); });
  return found;
}

bool depends_on(Expr e, Expr sym) {
  std::unordered_map<const Node*, bool> memo;
  std::function<bool(Expr)> rec = [&](Expr x) -> bool {
    if (x == sym) return true;
    if (x.args().empty()) return false;
    if (const auto it = memo.find(x.node()); it != memo.end()) return it->second;
    bool r = false;
    for (const Expr a : x.args()) {
      if (rec(a)) {
        r = true;
        break;
      }
    }
    memo[x.node()] = r;
    return r;
  };
  return rec(e);
}

std::size_t pool_size() { return pool().storage.size(); }

}  // namespace dyncc::sym
