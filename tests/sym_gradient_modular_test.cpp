// Reverse-mode gradient against forward derivatives, and exact evaluation over GF(p): field
// arithmetic against 128-bit references, CRT + rational reconstruction, and agreement of the
// randomised modular identity test with the trig normal form (two independent procedures).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "random_expr.hpp"
#include "sym/diff.hpp"
#include "sym/expand.hpp"
#include "sym/modular.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"
#include "sym/substitute.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::sym {
namespace {

using test::Generator;
using test::Point;
using test::Sample;

TEST(SymGradient, MatchesForwardDerivatives) {
  Generator gen(0x6AD);
  const std::vector<Expr>& vars = test::all_symbols();
  for (int n = 0; n < 200; ++n) {
    const Sample s = gen.expression(2 + n % 2);
    const std::vector<Expr> g = gradient(s.expr, vars);
    ASSERT_EQ(g.size(), vars.size());
    const Point p = gen.point();
    for (std::size_t i = 0; i < vars.size(); ++i) {
      const Expr d = diff(s.expr, vars[i]);
      if (!depends_on(s.expr, vars[i])) {
        EXPECT_TRUE(g[i].is_zero()) << to_string(s.expr) << " by " << vars[i].name();
      }
      const double a = test::engine_eval(g[i], p);
      const double b = test::engine_eval(d, p);
      EXPECT_TRUE(test::close(a, b, 1e-9)) << to_string(s.expr) << " by " << vars[i].name() << ": " << a << " vs " << b;
      EXPECT_NE(test_zero(g[i] - d).verdict, ZeroVerdict::NonZero) << to_string(s.expr) << " by " << vars[i].name();
    }
  }
}

TEST(SymGradient, ProvablyEqualForTrigPolynomials) {
  Generator gen(0x6AE);
  const std::vector<Expr>& vars = test::all_symbols();
  for (int n = 0; n < 60; ++n) {
    const Sample s = gen.trig_polynomial(2);
    const std::vector<Expr> g = gradient(s.expr, vars);
    for (std::size_t i = 0; i < vars.size(); ++i) {
      EXPECT_EQ(test_zero(g[i] - diff(s.expr, vars[i])).verdict, ZeroVerdict::Zero)
          << to_string(s.expr) << " by " << vars[i].name();
    }
  }
}

// ---- the prime fields ----

class SymModularField : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(SymModularField, ArithmeticMatches128BitReference) {
  const std::uint64_t p = GetParam();
  const PrimeField f(p);
  std::mt19937_64 rng(p);
  std::uniform_int_distribution<std::uint64_t> any(0, p - 1);
  for (int i = 0; i < 2000; ++i) {
    const std::uint64_t a = any(rng);
    const std::uint64_t b = any(rng);
    EXPECT_EQ(f.add(a, b), static_cast<std::uint64_t>((static_cast<UInt128>(a) + b) % p));
    EXPECT_EQ(f.sub(a, b), static_cast<std::uint64_t>((static_cast<UInt128>(a) + p - b) % p));
    EXPECT_EQ(f.mul(a, b), static_cast<std::uint64_t>(static_cast<UInt128>(a) * b % p));
    EXPECT_EQ(f.add(a, f.neg(a)), 0U);
    if (a != 0) {
      EXPECT_EQ(f.mul(a, f.inv(a)), 1U);
      EXPECT_EQ(f.pow(a, p - 1), 1U);  // Fermat
    }
    const std::int64_t num = static_cast<std::int64_t>(rng() >> 1U) * (i % 2 == 0 ? 1 : -1);
    const std::int64_t den = static_cast<std::int64_t>(rng() % 1000000007ULL) + 1;
    const Rational r(num, den);
    // from(r) is the field element x with x * den == num.
    EXPECT_EQ(f.mul(f.from(r), f.from_int(r.den())), f.from_int(r.num()));
  }
  EXPECT_THROW((void)f.inv(0), std::domain_error);
  EXPECT_EQ(f.from_int(-1), p - 1);
  EXPECT_EQ(f.from_int(INT64_MIN), (p - static_cast<std::uint64_t>((UInt128{1} << 63U) % p)) % p);
  // Points on the unit circle are exact.
  for (int i = 0; i < 50; ++i) {
    const ModularPoint pt = random_point(f, 3, rng);
    for (std::size_t j = 0; j < 3; ++j) EXPECT_EQ(f.add(f.mul(pt.sin[j], pt.sin[j]), f.mul(pt.cos[j], pt.cos[j])), 1U);
  }
}

INSTANTIATE_TEST_SUITE_P(BothPrimes, SymModularField, ::testing::Values(PrimeField::kPrime1, PrimeField::kPrime2));

TEST(SymModular, CrtAndRationalReconstruction) {
  const std::uint64_t p1 = PrimeField::kPrime1;
  const std::uint64_t p2 = PrimeField::kPrime2;
  const PrimeField f1(p1);
  const PrimeField f2(p2);
  const UInt128 m = static_cast<UInt128>(p1) * p2;
  std::mt19937_64 rng(0xC27);
  for (int i = 0; i < 2000; ++i) {
    // CRT: the unique residue mod p1*p2.
    const UInt128 x = ((static_cast<UInt128>(rng()) << 64U) | rng()) % m;
    const UInt128 c = crt(static_cast<std::uint64_t>(x % p1), p1, static_cast<std::uint64_t>(x % p2), p2);
    EXPECT_TRUE(c == x);
    // Reconstruction finds every rational with |num|, den well inside sqrt(m/2) ~ 2^60.
    const auto num = static_cast<std::int64_t>(rng() >> 8U) * (i % 3 == 0 ? -1 : 1);
    const auto den = static_cast<std::int64_t>((rng() >> 8U) | 1U);
    const Rational r(num, den);
    const UInt128 a = crt(f1.from(r), p1, f2.from(r), p2);
    const std::optional<Rational> back = rational_reconstruct(a, m);
    ASSERT_TRUE(back.has_value()) << r.num() << "/" << r.den();
    EXPECT_EQ(*back, r);
    // Whatever comes back for a random residue is congruent to it.
    const UInt128 y = ((static_cast<UInt128>(rng()) << 64U) | rng()) % m;
    if (const auto q = rational_reconstruct(y, m)) {
      EXPECT_EQ(f1.from(*q), static_cast<std::uint64_t>(y % p1));
      EXPECT_EQ(f2.from(*q), static_cast<std::uint64_t>(y % p2));
    }
  }
}

// Exact values of polynomials at integer points: the modular evaluation against exact
// substitution.
TEST(SymModular, PolynomialValuesAreExact) {
  Generator gen(0x9017, test::GeneratorOptions{.division = false, .sqrt = false, .atan2 = false});
  const PrimeField f(PrimeField::kPrime1);
  const std::vector<Expr>& vars = test::all_symbols();
  std::mt19937_64 rng(3);
  for (int n = 0; n < 100; ++n) {
    Expr poly(0);
    for (int t = 0; t < 5; ++t)
      poly = poly + gen.rational().expr * pow(gen.leaf().expr, gen.uniform(0, 3)) * gen.leaf().expr;
    ModularPoint pt = random_point(f, vars.size(), rng);
    Substitution at;
    for (std::size_t i = 0; i < vars.size(); ++i) {
      const std::int64_t v = gen.uniform(-9, 9);
      pt.value[i] = f.from_int(v);
      at.emplace(vars[i], Expr(v));
    }
    const Expr outs[1] = {poly};
    const Expr exact = substitute(poly, at);
    ASSERT_TRUE(exact.is_number()) << to_string(exact);
    EXPECT_EQ(ModularFunction(outs, vars).evaluate(f, pt)[0], f.from(exact.value())) << to_string(poly);
  }
}

// e vanishes at three random points in both fields <=> e is identically zero (except with
// probability ~degree/p per point, Schwartz-Zippel).
bool modular_zero(Expr e) {
  const std::vector<Expr>& vars = test::all_symbols();
  const Expr outs[1] = {e};
  const ModularFunction mf(outs, vars);
  std::mt19937_64 rng(e.hash());
  bool zero = true;
  for (const std::uint64_t prime : {PrimeField::kPrime1, PrimeField::kPrime2}) {
    const PrimeField f(prime);
    for (int k = 0; k < 3; ++k) zero = zero && mf.evaluate(f, random_point(f, vars.size(), rng))[0] == 0;
  }
  return zero;
}

TEST(SymModular, AgreesWithTheTrigNormalForm) {
  Generator gen(0x40D, test::GeneratorOptions{.integer_angles = true});
  int zeros = 0;
  int nonzeros = 0;
  for (int n = 0; n < 150; ++n) {
    const Sample a = gen.trig_polynomial(2 + n % 2);
    Expr e;
    switch (n % 3) {
      case 0: e = a.expr - expand(a.expr); break;                                                    // identically zero
      case 1: e = a.expr - expand(a.expr) + gen.trig_polynomial(0).expr * Rational(1, 1000); break;  // not
      default: e = a.expr - gen.trig_polynomial(2).expr; break;                                      // usually not
    }
    const bool vanishes = modular_zero(e);
    const ZeroTestResult z = test_zero(e);
    ASSERT_TRUE(z.proved) << to_string(e) << ": " << z.note;
    EXPECT_EQ(z.verdict == ZeroVerdict::Zero, vanishes) << to_string(e);
    (vanishes ? zeros : nonzeros) += 1;
  }
  EXPECT_GE(zeros, 50);
  EXPECT_GE(nonzeros, 50);
}

TEST(SymModular, RejectsWhatItCannotEvaluateExactly) {
  const std::vector<Expr>& vars = test::all_symbols();
  const Expr x = symbol("x");
  for (const char* text : {"sqrt(x)", "atan2(x, y)", "sin(x/2)", "pi*x", "sin(x*y)", "w + x"}) {
    const Expr outs[1] = {parse_or_throw(text)};
    EXPECT_THROW(ModularFunction(outs, vars), NotModular) << text;
  }
  const Expr ok[1] = {sin(Expr(2) * x - symbol("y")) * x};
  EXPECT_NO_THROW(ModularFunction(ok, vars));
  // A constant angle inside sin/cos gets its own exact point on the circle, so identities that
  // hold for every value of it (here sin^2 + cos^2 = 1 and an angle sum) evaluate to exactly 0.
  const Expr constant_angle[1] = {
      parse_or_throw("sin(x + 1)^2 + cos(x + 1)^2 - 1 + sin(2*x + pi/3) - sin(2*x)*cos(pi/3) - cos(2*x)*sin(pi/3)")};
  const ModularFunction f(constant_angle, vars);
  const PrimeField field(PrimeField::kPrime1);
  std::mt19937_64 rng(5);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(f.evaluate(field, random_point(field, f.circle_count(), rng))[0], 0U);
}

}  // namespace
}  // namespace dyncc::sym
