// expand and substitute: value-preserving (checked against the independent shadow),
// idempotent / consistent, and exact on hand-checkable cases.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "random_expr.hpp"
#include "sym/expand.hpp"
#include "sym/print.hpp"
#include "sym/substitute.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::sym {
namespace {

using test::Generator;
using test::Point;
using test::Sample;

#define EXPECT_SAME(a, b) EXPECT_EQ((a), (b)) << "  " << to_string(a) << "\n  vs " << to_string(b)

// Expanded: no product anywhere (also inside function arguments) has a sum raised to a
// positive power, and no sum has a sum as a term.
bool fully_expanded(Expr e, std::string& why) {
  for (const Expr a : e.args()) {
    if (!fully_expanded(a, why)) return false;
  }
  if (e.kind() == Kind::Mul) {
    for (std::size_t i = 0; i < e.args().size(); ++i) {
      if (e.args()[i].kind() == Kind::Add && !e.weights()[i].is_negative()) {
        why = to_string(e);
        return false;
      }
    }
  }
  return true;
}

std::int64_t binomial(int n, int k) {  // multiplicative formula, independent of Pascal's rule
  std::int64_t r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

Rational weight_of(Expr sum, Expr term) {
  for (std::size_t i = 0; i < sum.args().size(); ++i) {
    if (sum.args()[i] == term) return sum.weights()[i];
  }
  return Rational(0);
}

TEST(SymExpand, PreservesValueOnRandomExpressions) {
  Generator gen(0xE4A0);
  for (int n = 0; n < 300; ++n) {
    const Sample s = gen.expression(2 + n % 2);
    const Expr x = expand(s.expr);
    for (int k = 0; k < 3; ++k) {
      const Point p = gen.point();
      const double expected = s(p);
      const double got = test::engine_eval(x, p);
      EXPECT_TRUE(test::close(got, expected, 1e-8))
          << to_string(s.expr) << "\n  expanded " << to_string(x) << "\n  " << got << " vs " << expected;
    }
  }
}

TEST(SymExpand, IsIdempotentAndFullyDistributed) {
  Generator gen(0x1DE4);
  for (int n = 0; n < 300; ++n) {
    const Sample s = gen.expression(2 + n % 2);
    const Expr once = expand(s.expr);
    EXPECT_SAME(expand(once), once);
    std::string why;
    EXPECT_TRUE(fully_expanded(once, why)) << to_string(s.expr) << "\n  not distributed: " << why;
  }
}

TEST(SymExpand, BinomialCoefficients) {
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  for (int n = 1; n <= 20; ++n) {
    const Expr e = expand(pow(x + y, n));
    ASSERT_EQ(e.kind(), Kind::Add) << n;
    EXPECT_EQ(e.args().size(), static_cast<std::size_t>(n) + 1);
    for (int k = 0; k <= n; ++k) {
      EXPECT_EQ(weight_of(e, pow(x, k) * pow(y, n - k)), Rational(binomial(n, k))) << "(x+y)^" << n << ", x^" << k;
    }
  }
  // (a + b)^3 for non-symbol atoms, against the hand-written binomial.
  const Expr a = sin(symbol("q1"));
  const Expr b = x * y;
  EXPECT_SAME(expand(pow(a + b, 3)), pow(a, 3) + Expr(3) * pow(a, 2) * b + Expr(3) * a * pow(b, 2) + pow(b, 3));
  EXPECT_SAME(expand(pow(x - y, 2)), x * x - Expr(2) * x * y + y * y);
  EXPECT_SAME(expand((x + y) * (x - y)), x * x - y * y);
  // The largest middle coefficient that fits in 64 bits.
  const Expr big = expand(pow(x + y, 64));
  EXPECT_EQ(weight_of(big, pow(x, 32) * pow(y, 32)), Rational(INT64_C(1832624140942590534)));
  // 2^64 does not fit: the coefficient overflow must be reported, not wrapped.
  EXPECT_THROW(expand(pow(x + Expr(2) * y, 64)), RationalOverflow);
}

TEST(SymExpand, MultinomialCount) {
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  const Expr z = symbol("z");
  const Expr e = expand(pow(x + y + z, 4));
  EXPECT_EQ(e.args().size(), 15U);  // monomials of degree 4 in 3 variables: C(6, 2)
  EXPECT_SAME(substitute(e, {{x, Expr(1)}, {y, Expr(1)}, {z, Expr(1)}}), Expr(81));
  EXPECT_SAME(substitute(e, {{x, Expr(1)}, {y, Expr(-1)}, {z, Expr(1)}}), Expr(1));
}

TEST(SymExpand, KeepsNegativePowersAndExpandsArguments) {
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  const Expr d = pow(x + Expr(1), -2);
  EXPECT_SAME(expand(d * (x + y)), x * d + y * d);
  EXPECT_SAME(expand(sin(pow(x + Expr(1), 2))), sin(x * x + Expr(2) * x + Expr(1)));
  EXPECT_SAME(expand(sqrt(Expr(1) + pow(x + y, 2))), sqrt(Expr(1) + x * x + Expr(2) * x * y + y * y));
  // sqrt(u)^2 == u appears only after multiplying out; the result must still be expanded.
  const Expr r = sqrt(Expr(1) + x * x);
  EXPECT_SAME(expand(pow(r + Expr(1), 2) * (x + Expr(2))),
              Expr(2) * x * r + Expr(4) * r + x * x * x + Expr(2) * x * x + Expr(2) * x + Expr(4));
}

TEST(SymSubstitute, MatchesEvaluationAtSubstitutedValues) {
  Generator gen(0x5B57);
  const Expr x = symbol("x");
  const Expr q1 = symbol("q1");
  int overflowed = 0;
  for (int n = 0; n < 300; ++n) {
    Sample e;
    Sample a;
    Sample b;
    Expr s;
    try {
      e = gen.expression(3);
      a = gen.expression(2);
      b = gen.expression(2);
      s = substitute(e.expr, {{x, a.expr}, {q1, b.expr}});
    } catch (const RationalOverflow&) {
      ++overflowed;  // e.g. (6250000/1408969)^6 does not fit in 64 bits: nothing to compare
      continue;
    }
    for (int k = 0; k < 2; ++k) {
      const Point p = gen.point();
      Point moved = p;
      moved[0] = a(p);
      moved[3] = b(p);
      const double expected = e(moved);
      const double got = test::engine_eval(s, p);
      EXPECT_TRUE(test::close(got, expected, 1e-8))
          << to_string(e.expr) << " with x -> " << to_string(a.expr) << ", q1 -> " << to_string(b.expr) << ": " << got
          << " vs " << expected;
    }
  }
  EXPECT_LT(overflowed, 30);  // the property was checked on the great majority of samples
}

TEST(SymSubstitute, ExactRationalValuesOfPolynomials) {
  // A random polynomial evaluated exactly: by substitution in the engine and by Rational
  // arithmetic here.
  Generator gen(0x9011);
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  for (int n = 0; n < 100; ++n) {
    const Rational xv(gen.uniform(-7, 7), gen.uniform(1, 6));
    const Rational yv(gen.uniform(-7, 7), gen.uniform(1, 6));
    Expr poly(0);
    Rational expected(0);
    for (int t = 0; t < 6; ++t) {
      const Rational c(gen.uniform(-9, 9), gen.uniform(1, 4));
      const int i = gen.uniform(0, 4);
      const int j = gen.uniform(0, 4);
      poly = poly + number(c) * pow(x, i) * pow(y, j);
      expected += c * xv.pow(i) * yv.pow(j);
    }
    EXPECT_SAME(substitute(poly, {{x, number(xv)}, {y, number(yv)}}), number(expected));
  }
}

TEST(SymSubstitute, IdentityAndSimultaneousReplacement) {
  Generator gen(0x1D17);
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  for (int n = 0; n < 100; ++n) {
    const Expr e = gen.expression(3).expr;
    EXPECT_SAME(substitute(e, {}), e);
    EXPECT_SAME(substitute(e, {{x, x}}), e);
    EXPECT_SAME(substitute(e, {{symbol("absent_symbol"), Expr(5)}}), e);
    // Values are not substituted again: swapping twice is the identity.
    const Expr swapped = substitute(e, {{x, y}, {y, x}});
    EXPECT_SAME(substitute(swapped, {{x, y}, {y, x}}), e);
  }
  EXPECT_SAME(substitute(x - Expr(2) * y, {{x, y}, {y, x}}), y - Expr(2) * x);
  // Non-symbol keys are matched structurally.
  const Expr s = symbol("s");
  const Expr e = pow(sin(x), 2) + y * pow(cos(x), 2);
  EXPECT_SAME(substitute(e, {{sin(x), s}}), s * s + y * pow(cos(x), 2));
  EXPECT_THROW(substitute(Expr(1) / x, {{x, Expr(0)}}), std::domain_error);
}

TEST(SymSubstitute, ShiftAndShiftBackIsTheSameFunction) {
  Generator gen(0x5F17);
  const Expr x = symbol("x");
  for (int n = 0; n < 100; ++n) {
    const Sample e = gen.trig_polynomial(3);
    const Expr shifted = substitute(e.expr, {{x, x + Expr(1)}});
    const Expr back = substitute(shifted, {{x, x - Expr(1)}});
    const ZeroTestResult z = test_zero(back - e.expr);
    EXPECT_EQ(z.verdict, ZeroVerdict::Zero) << to_string(e.expr) << "\n  back: " << to_string(back);
    const Point p = gen.point();
    Point p1 = p;
    p1[0] += 1.0;
    EXPECT_TRUE(test::close(test::engine_eval(shifted, p), e(p1), 1e-9));
  }
}

}  // namespace
}  // namespace dyncc::sym
