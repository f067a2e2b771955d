#include "codegen/lower.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace dyncc::codegen {

namespace {
// Above this multiple, sin(k*x) is computed directly: the recursion would cost more than a call.
constexpr std::int64_t kLargestExpandedMultiple = 8;
}  // namespace

Lowering::Lowering(Program& program, std::unordered_map<sym::Expr, std::string> inputs)
    : program_(program), inputs_(std::move(inputs)) {}

void Lowering::define(const sym::Bindings& bindings) {
  for (const auto& [symbol, definition] : bindings.list()) definitions_[symbol] = definition;
}

ValueId Lowering::operator()(sym::Expr e) {
  if (const auto it = memo_.find(e); it != memo_.end()) return it->second;
  ValueId v = -1;
  switch (e.kind()) {
    case sym::Kind::Number: v = program_.constant(e.value().to_double()); break;
    case sym::Kind::Constant: v = program_.constant(std::numbers::pi); break;
    case sym::Kind::Symbol: {
      if (const auto def = definitions_.find(e); def != definitions_.end()) {
        v = (*this)(def->second);
        break;
      }
      const auto it = inputs_.find(e);
      if (it == inputs_.end()) throw std::logic_error("codegen: symbol " + e.name() + " is not an input");
      v = program_.input(it->second);
      break;
    }
    case sym::Kind::Add: v = lower_sum(e); break;
    case sym::Kind::Mul: v = lower_product(e); break;
    case sym::Kind::Sin: v = sin_of(e.args()[0]); break;
    case sym::Kind::Cos: v = cos_of(e.args()[0]); break;
    case sym::Kind::Sqrt: v = program_.sqrt((*this)(e.args()[0])); break;
    case sym::Kind::Atan2: {
      // Operands lowered in a fixed order: value numbers must not depend on the compiler's
      // (unspecified) order of evaluating function arguments, or the output would.
      const ValueId y = (*this)(e.args()[0]);
      const ValueId x = (*this)(e.args()[1]);
      v = program_.atan2(y, x);
      break;
    }
  }
  memo_.emplace(e, v);
  return v;
}

ValueId Lowering::lower_sum(sym::Expr e) {
  std::vector<Monomial> terms;
  const auto args = e.args();
  const auto weights = e.weights();
  for (std::size_t i = 0; i < args.size(); ++i) {
    Monomial m;
    m.coefficient = weights[i];
    const sym::Expr t = args[i];
    bool integral = t.kind() == sym::Kind::Mul;
    if (integral) {
      for (const sym::Rational& x : t.weights()) integral = integral && x.is_integer() && x.num() > 0;
    }
    if (integral) {
      m.coefficient = m.coefficient * t.value();
      for (std::size_t k = 0; k < t.args().size(); ++k) m.factors.emplace_back(t.args()[k], t.weights()[k].num());
    } else {
      m.factors.emplace_back(t, 1);
    }
    terms.push_back(std::move(m));
  }
  if (!e.value().is_zero()) terms.push_back(Monomial{e.value(), {}});
  const Signed s = factorize(std::move(terms));
  return s.negative ? program_.neg(s.value) : s.value;
}

// Greedy multivariate Horner: take out the factor that occurs in the most terms,
// f*(terms with f, divided by f) + (terms without f), until no factor is shared.
Lowering::Signed Lowering::factorize(std::vector<Monomial> terms) {
  std::unordered_map<sym::Expr, int> occurrences;
  for (const Monomial& m : terms) {
    for (const auto& [base, exponent] : m.factors) ++occurrences[base];
  }
  sym::Expr best;
  int best_count = 1;
  for (const auto& [base, count] : occurrences) {
    if (count > best_count || (count == best_count && count > 1 && sym::canonical_less(base, best))) {
      best = base;
      best_count = count;
    }
  }
  if (best_count < 2) return plain_sum(terms);
  std::vector<Monomial> with, without;
  for (Monomial& m : terms) {
    const auto it = std::find_if(m.factors.begin(), m.factors.end(), [&](const auto& f) { return f.first == best; });
    if (it == m.factors.end()) {
      without.push_back(std::move(m));
      continue;
    }
    if (--it->second == 0) m.factors.erase(it);
    with.push_back(std::move(m));
  }
  const Signed inner = factorize(std::move(with));
  const Signed taken{program_.mul((*this)(best), inner.value), inner.negative};
  if (without.empty()) return taken;
  const Signed rest = factorize(std::move(without));
  if (taken.negative == rest.negative) return {program_.add(taken.value, rest.value), taken.negative};
  return taken.negative ? Signed{program_.sub(rest.value, taken.value), false}
                        : Signed{program_.sub(taken.value, rest.value), false};
}

ValueId Lowering::monomial_body(const Monomial& m) {
  std::vector<ValueId> factors;
  for (const auto& [base, exponent] : m.factors) factors.push_back(program_.integer_power((*this)(base), exponent));
  return product_of(factors);
}

// Terms grouped by the magnitude of their coefficient, so 0.18*x + 0.18*y costs one
// multiplication by 0.18; positive parts are added, negative ones subtracted.
Lowering::Signed Lowering::plain_sum(const std::vector<Monomial>& terms) {
  std::vector<sym::Rational> magnitudes;
  for (const Monomial& m : terms) {
    const sym::Rational c = m.coefficient.abs();
    if (std::find(magnitudes.begin(), magnitudes.end(), c) == magnitudes.end()) magnitudes.push_back(c);
  }
  std::vector<ValueId> positive, negative;
  for (const sym::Rational& c : magnitudes) {
    std::vector<ValueId> pos, neg;
    for (const Monomial& m : terms) {
      if (m.coefficient.abs() == c) (m.coefficient.is_negative() ? neg : pos).push_back(monomial_body(m));
    }
    ValueId acc = -1;
    bool acc_negative = false;
    for (const ValueId t : pos) acc = acc < 0 ? t : program_.add(acc, t);
    for (const ValueId t : neg) {
      if (acc < 0) {
        acc = t;
        acc_negative = true;
      } else {
        acc = acc_negative ? program_.add(acc, t) : program_.sub(acc, t);
      }
    }
    const ValueId scaled = c.is_one() ? acc : program_.mul(program_.constant(c.to_double()), acc);
    (acc_negative ? negative : positive).push_back(scaled);
  }
  ValueId acc = -1;
  for (const ValueId t : positive) acc = acc < 0 ? t : program_.add(acc, t);
  if (acc < 0) {
    for (const ValueId t : negative) acc = acc < 0 ? t : program_.add(acc, t);
    return {acc < 0 ? program_.constant(0.0) : acc, true};
  }
  for (const ValueId t : negative) acc = program_.sub(acc, t);
  return {acc, false};
}

// Factors in order of creation: the coordinates' sines and cosines and the inputs are created
// first, so monomials that share them share the leading partial products.
ValueId Lowering::product_of(std::vector<ValueId> factors) {
  std::sort(factors.begin(), factors.end());
  ValueId acc = -1;
  for (const ValueId f : factors) acc = acc < 0 ? f : program_.mul(acc, f);
  return acc < 0 ? program_.constant(1.0) : acc;
}

ValueId Lowering::lower_product(sym::Expr e) {
  std::vector<ValueId> numerator, denominator;
  const auto bases = e.args();
  const auto exponents = e.weights();
  for (std::size_t i = 0; i < bases.size(); ++i) {
    const sym::Rational x = exponents[i];
    const ValueId base = (*this)(bases[i]);
    if (!x.is_integer()) {
      numerator.push_back(program_.real_power(base, x.to_double()));
      continue;
    }
    const std::int64_t n = x.num();
    const ValueId power = program_.integer_power(base, static_cast<int>(n < 0 ? -n : n));
    (n < 0 ? denominator : numerator).push_back(power);
  }
  ValueId value = product_of(numerator);
  if (!denominator.empty()) value = program_.div(value, product_of(denominator));
  const sym::Rational c = e.value();
  if (c.is_one()) return value;
  if (c.is_minus_one()) return program_.neg(value);
  return program_.mul(program_.constant(c.to_double()), value);
}

ValueId Lowering::sin_of(sym::Expr angle) {
  if (const auto it = sin_memo_.find(angle); it != sin_memo_.end()) return it->second;
  const ValueId v = trig_of(angle, true);
  sin_memo_.emplace(angle, v);
  return v;
}

ValueId Lowering::cos_of(sym::Expr angle) {
  if (const auto it = cos_memo_.find(angle); it != cos_memo_.end()) return it->second;
  const ValueId v = trig_of(angle, false);
  cos_memo_.emplace(angle, v);
  return v;
}

// sin(a + b) = sa*cb + ca*sb, cos(a + b) = ca*cb - sa*sb; the products made one after the other
// (not as two arguments of one call, whose evaluation order the compiler chooses).
ValueId Lowering::angle_sum(ValueId sa, ValueId ca, ValueId sb, ValueId cb, bool want_sin) {
  if (want_sin) {
    const ValueId first = program_.mul(sa, cb);
    const ValueId second = program_.mul(ca, sb);
    return program_.add(first, second);
  }
  const ValueId first = program_.mul(ca, cb);
  const ValueId second = program_.mul(sa, sb);
  return program_.sub(first, second);
}

ValueId Lowering::trig_of(sym::Expr angle, bool want_sin) {
  auto direct = [&] {
    const ValueId x = (*this)(angle);
    return want_sin ? program_.sin(x) : program_.cos(x);
  };
  // A sum of several angles: split off the first, sin(a + b) = sa*cb + ca*sb,
  // cos(a + b) = ca*cb - sa*sb.
  if (angle.kind() == sym::Kind::Add && (angle.args().size() + (angle.value().is_zero() ? 0 : 1)) >= 2) {
    const sym::Expr first = sym::Expr(angle.weights()[0]) * angle.args()[0];
    const sym::Expr rest = angle - first;
    const ValueId sa = sin_of(first), ca = cos_of(first), sb = sin_of(rest), cb = cos_of(rest);
    return angle_sum(sa, ca, sb, cb, want_sin);
  }
  // An integer multiple k*x: sin(k x) = sin((k-1) x) cos x + cos((k-1) x) sin x.
  const auto [k, x] = angle.kind() == sym::Kind::Add && angle.args().size() == 1 && angle.value().is_zero()
                          ? std::pair<sym::Rational, sym::Expr>{angle.weights()[0], angle.args()[0]}
                          : sym::split_coefficient(angle);
  if (!k.is_one() && k.is_integer() && !k.is_zero() && k.abs().num() <= kLargestExpandedMultiple &&
      !free_symbols(x).empty()) {
    if (k.is_negative()) {  // sin(-y) = -sin(y), cos(-y) = cos(y)
      const ValueId v = trig_of(sym::Expr(k.abs()) * x, want_sin);
      return want_sin ? program_.neg(v) : v;
    }
    const sym::Expr smaller = sym::Expr(k - sym::Rational(1)) * x;
    const ValueId sa = sin_of(smaller), ca = cos_of(smaller), sb = sin_of(x), cb = cos_of(x);
    return angle_sum(sa, ca, sb, cb, want_sin);
  }
  return direct();
}

}  // namespace dyncc::codegen
