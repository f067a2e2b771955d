// Derivatives: checked against central finite differences of an independently evaluated
// shadow, mixed partials commute, and the memoised Differentiator agrees with a fresh diff.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <unordered_set>

#include "random_expr.hpp"
#include "sym/diff.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::sym {
namespace {

using test::Generator;
using test::Point;
using test::Sample;

// Fourth-order central difference of the shadow along symbol i: error O(h^4) + O(eps/h).
double finite_difference(const Sample& s, Point p, std::size_t i, double h) {
  const double x0 = p[i];
  auto at = [&](double dx) {
    p[i] = x0 + dx;
    return s(p);
  };
  return (at(-2 * h) - 8 * at(-h) + 8 * at(h) - at(2 * h)) / (12 * h);
}

// d/d(si) d/d(sj) by the mixed central difference (error O(h^2)).
double mixed_difference(const Sample& s, Point p, std::size_t i, std::size_t j, double h) {
  const double xi = p[i];
  const double xj = p[j];
  auto at = [&](double di, double dj) {
    p[i] = xi + di;
    p[j] = xj + dj;
    return s(p);
  };
  return (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4 * h * h);
}

std::string describe(const Sample& s) { return to_string(s.expr); }

TEST(SymDiff, MatchesFiniteDifferencesOnRandomExpressions) {
  Generator gen(0xD1FF);
  int checked = 0;
  for (int n = 0; n < 500; ++n) {
    const Sample s = gen.expression(2 + n % 3);
    const std::size_t i = gen.symbol_index();
    const Expr var = test::all_symbols()[i];
    const Expr d = diff(s.expr, var);
    for (int k = 0; k < 3; ++k) {
      const Point p = gen.point();
      const double analytic = test::engine_eval(d, p);
      const double numeric = finite_difference(s, p, i, 1e-3);
      ASSERT_TRUE(std::isfinite(analytic)) << "expression " << n << ": " << describe(s);
      EXPECT_TRUE(test::close(analytic, numeric, 1e-6))
          << "expression " << n << ": d/d" << var.name() << " " << describe(s) << "\n  derivative " << to_string(d)
          << "\n  analytic " << analytic << " vs finite difference " << numeric;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 1500);
}

TEST(SymDiff, DerivativeByAbsentSymbolIsZeroNode) {
  Generator gen(0xAB5E, test::GeneratorOptions{.num_symbols = 3});  // only x, y, z
  for (int n = 0; n < 200; ++n) {
    const Sample s = gen.expression(3);
    for (const char* name : {"q1", "q2", "q3"}) EXPECT_TRUE(diff(s.expr, symbol(name)).is_zero()) << describe(s);
  }
}

TEST(SymDiff, SecondDerivativesCommute) {
  Generator gen(0x5EC0);
  int proved = 0;
  for (int n = 0; n < 150; ++n) {
    const Sample s = gen.expression(2 + n % 2);
    const std::size_t i = gen.symbol_index();
    std::size_t j = gen.symbol_index();
    if (j == i) j = (i + 1) % test::kNumSymbols;
    const Expr xi = test::all_symbols()[i];
    const Expr xj = test::all_symbols()[j];
    const Expr dij = diff(diff(s.expr, xi), xj);
    const Expr dji = diff(diff(s.expr, xj), xi);
    for (int k = 0; k < 2; ++k) {
      const Point p = gen.point();
      const double a = test::engine_eval(dij, p);
      const double b = test::engine_eval(dji, p);
      EXPECT_TRUE(test::close(a, b, 1e-9)) << describe(s) << ": " << a << " vs " << b;
      const double fd = mixed_difference(s, p, i, j, 1e-3);
      EXPECT_TRUE(test::close(a, fd, 1e-4)) << describe(s) << ": analytic " << a << " vs finite difference " << fd;
    }
    // The zero test may not decide sqrt/atan2/division, but it must never call the difference non-zero.
    const ZeroTestResult z = test_zero(dij - dji);
    EXPECT_NE(z.verdict, ZeroVerdict::NonZero) << describe(s) << ": witness value " << z.witness_value;
    if (z.verdict == ZeroVerdict::Zero) ++proved;
  }
  // Mixed partials are equal in the differential ring of opaque atoms, so the normal form
  // should prove nearly all of them.
  EXPECT_GE(proved, 140);
}

TEST(SymDiff, SecondDerivativesCommuteProvablyForTrigPolynomials) {
  Generator gen(0x7216);
  for (int n = 0; n < 100; ++n) {
    const Sample s = gen.trig_polynomial(2 + n % 2);
    const Expr x = test::all_symbols()[gen.symbol_index()];
    const Expr y = test::all_symbols()[gen.symbol_index()];
    const ZeroTestResult z = test_zero(diff(diff(s.expr, x), y) - diff(diff(s.expr, y), x));
    EXPECT_EQ(z.verdict, ZeroVerdict::Zero) << describe(s);
    EXPECT_TRUE(z.proved);
  }
}

TEST(SymDiff, MemoisedDifferentiatorGivesTheSameNodeAsFreshDiff) {
  Generator gen(0x3E30);
  for (const std::size_t i : {0U, 3U}) {
    const Expr var = test::all_symbols()[i];
    Differentiator d(var);  // one memo across every expression and subexpression below
    for (int n = 0; n < 100; ++n) {
      const Sample s = gen.expression(3);
      // Every node of the DAG, so the memo is hit in many orders.
      std::vector<Expr> nodes{s.expr};
      std::unordered_set<const void*> seen;
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        for (const Expr a : nodes[k].args()) {
          if (seen.insert(a.node()).second) nodes.push_back(a);
        }
      }
      for (const Expr e : nodes) EXPECT_EQ(d(e), diff(e, var)) << to_string(e);
      EXPECT_EQ(d(s.expr), diff(s.expr, var)) << describe(s);  // a memo hit now
    }
  }
}

TEST(SymDiff, SumAndProductRules) {
  Generator gen(0x9A0D);
  const Expr x = symbol("x");
  for (int n = 0; n < 100; ++n) {
    const Sample a = gen.trig_polynomial(2);
    const Sample b = gen.trig_polynomial(2);
    const Rational c(gen.uniform(-5, 5), gen.uniform(1, 4));
    EXPECT_EQ(diff(a.expr + number(c) * b.expr, x), diff(a.expr, x) + number(c) * diff(b.expr, x))
        << describe(a) << " | " << describe(b);
    const Expr product_rule = diff(a.expr * b.expr, x) - (diff(a.expr, x) * b.expr + a.expr * diff(b.expr, x));
    EXPECT_EQ(test_zero(product_rule).verdict, ZeroVerdict::Zero) << describe(a) << " | " << describe(b);
  }
}

TEST(SymDiff, HandDerivedDerivatives) {
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  struct Case {
    Expr e;
    Expr expected;  // derived by hand
  };
  const Case cases[] = {
      {pow(x, 5), Expr(5) * pow(x, 4)},
      {pow(x, -3), Expr(-3) * pow(x, -4)},
      {pow(sin(x), 2), Expr(2) * sin(x) * cos(x)},
      {cos(Expr(2) * x + Expr(1)), Expr(-2) * sin(Expr(2) * x + Expr(1))},
      {sin(x * y), y * cos(x * y)},
      {sqrt(Expr(1) + x * x), x / sqrt(Expr(1) + x * x)},
      {atan2(y, x), -y / (x * x + y * y)},
      {atan2(x, y), y / (x * x + y * y)},
      {Expr(1) / (Expr(1) + x * x), Expr(-2) * x / pow(Expr(1) + x * x, 2)},
      {x * sin(x), sin(x) + x * cos(x)},
      {pi() * x, pi()},
      {Expr(7), Expr(0)},
      {y, Expr(0)},
  };
  for (const Case& c : cases)
    EXPECT_EQ(diff(c.e, x), c.expected) << to_string(c.e) << " -> " << to_string(diff(c.e, x));
}

TEST(SymDiff, OnlySymbolsAreVariables) {
  EXPECT_THROW(diff(symbol("x"), Expr(2)), std::invalid_argument);
  EXPECT_THROW(diff(symbol("x"), pi()), std::invalid_argument);
  EXPECT_THROW(Differentiator(symbol("x") + symbol("y")), std::invalid_argument);
}

}  // namespace
}  // namespace dyncc::sym
