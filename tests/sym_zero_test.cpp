// The zero test: identities are proved, non-identities are refuted with a witness that really
// evaluates to non-zero (checked here with <cmath>, not with the engine), and random
// expressions minus an equal copy built along another path are proved zero.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>

#include "random_expr.hpp"
#include "sym/expand.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"
#include "sym/simplify.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::sym {
namespace {

using test::Generator;
using test::Point;
using test::Sample;

using Values = std::map<std::string, double>;

Values witness_values(const ZeroTestResult& r) {
  Values v;
  for (const auto& [name, value] : r.witness) v[name] = value;
  return v;
}

Point witness_point(const ZeroTestResult& r) {
  Point p{};  // symbols the expression does not use do not matter
  for (const auto& [name, value] : r.witness) {
    for (std::size_t i = 0; i < test::kNumSymbols; ++i) {
      if (test::symbol_names()[i] == name) p[i] = value;
    }
  }
  return p;
}

void expect_proved_zero(Expr e, const std::string& what) {
  const ZeroTestResult r = test_zero(e);
  EXPECT_EQ(r.verdict, ZeroVerdict::Zero)
      << what << "\n  " << to_string(e) << "\n  normal form: " << to_string(trig_normal_form(e).expr);
  EXPECT_TRUE(r.proved) << what;
}

void expect_identity(const std::string& text) { expect_proved_zero(parse_or_throw(text), text); }

TEST(SymZero, TrigonometricIdentities) {
  const char* identities[] = {
      // angle sums and differences
      "sin(a + b) - (sin(a)*cos(b) + cos(a)*sin(b))",
      "cos(a + b) - (cos(a)*cos(b) - sin(a)*sin(b))",
      "sin(a - b) - (sin(a)*cos(b) - cos(a)*sin(b))",
      "cos(a - b) - (cos(a)*cos(b) + sin(a)*sin(b))",
      "sin(q3 - q2) - sin(q3)*cos(q2) + cos(q3)*sin(q2)",
      "sin(q1 + 2*q2 - q3) - (sin(q1 + 2*q2)*cos(q3) - cos(q1 + 2*q2)*sin(q3))",
      "cos(a + b + c) - (cos(a)*cos(b)*cos(c) - cos(a)*sin(b)*sin(c) - sin(a)*cos(b)*sin(c) - sin(a)*sin(b)*cos(c))",
      // double and triple angles
      "sin(2*x) - 2*sin(x)*cos(x)",
      "cos(2*x) - (cos(x)^2 - sin(x)^2)",
      "cos(2*x) - (1 - 2*sin(x)^2)",
      "cos(2*x) - (2*cos(x)^2 - 1)",
      "sin(3*x) - (3*sin(x) - 4*sin(x)^3)",
      "cos(3*x) - (4*cos(x)^3 - 3*cos(x))",
      "sin(x)^4 - (3 - 4*cos(2*x) + cos(4*x))/8",
      // half angles and other rational multiples
      "sin(q) - 2*sin(q/2)*cos(q/2)",
      "cos(q) - (1 - 2*sin(q/2)^2)",
      "sin(q/2)^2 - (1 - cos(q))/2",
      "cos(q/2)^2 - (1 + cos(q))/2",
      "sin(5*q/6) - (sin(q/2)*cos(q/3) + cos(q/2)*sin(q/3))",
      "sin(q/3)*cos(q/3) - sin(2*q/3)/2",
      // Pythagoras with products and symbolic coefficients
      "sin(x)^2 + cos(x)^2 - 1",
      "m1*l1^2*(sin(q1 + q2)^2 + cos(q1 + q2)^2) - m1*l1^2",
      "(a*sin(x) + b*cos(x))^2 + (a*cos(x) - b*sin(x))^2 - a^2 - b^2",
      "sin(x)^2*sin(y)^2 + sin(x)^2*cos(y)^2 + cos(x)^2 - 1",
      "(sin(a)*cos(b))^2 + (sin(a)*sin(b))^2 + cos(a)^2 - 1",
      "(sin(x)^2 + cos(x)^2)^5 - 1",
      "sin(x)^6 + cos(x)^6 - (1 - 3*sin(x)^2*cos(x)^2)",
      // constants inside arguments
      "sin(2*x + 1) - 2*sin(x + 1/2)*cos(x + 1/2)",
      "sin(x + 1) - (sin(x)*cos(1) + cos(x)*sin(1))",
      "cos(x + 0.5)^2 + sin(x + 0.5)^2 - 1",
      "sin(1)^2 + cos(1)^2 - 1",
      "sin(2) - 2*sin(1)*cos(1)",
      // multiples of pi/2 and of pi (D-H offsets)
      "sin(x + pi/2) - cos(x)",
      "cos(q1 - pi/2) - sin(q1)",
      "sin(x + pi/3) - (sin(x)*cos(pi/3) + cos(x)*sin(pi/3))",
      "sin(x + 2*pi/3) - (sin(x)*cos(2*pi/3) + cos(x)*sin(2*pi/3))",
      "cos(q + 4*pi/3) - (cos(q)*cos(4*pi/3) - sin(q)*sin(4*pi/3))",
      "sin(x + 2*pi/3) - (sin(x + pi/3)*cos(pi/3) + cos(x + pi/3)*sin(pi/3))",
      "sin(-x - pi/3) + sin(x + pi/3)",
      "cos(x - pi/6) - cos(pi/6 - x)",
      // outside the decidable class, but zero with the atoms treated as opaque
      "sqrt(x)^2 - x",
      "sqrt(1 + x^2)*(sin(y)^2 + cos(y)^2) - sqrt(1 + x^2)",
      "(sqrt(1 + x^2) + 1)^2 - (x^2 + 2 + 2*sqrt(1 + x^2))",
      "atan2(y, x)*(sin(2*z) - 2*sin(z)*cos(z))",
      "(x + y)/(1 + x^2) - x/(1 + x^2) - y/(1 + x^2)",
      "sin(x*y)^2 + cos(x*y)^2 - 1",
      "sin(2*x*y) - 2*sin(x*y)*cos(x*y)",
  };
  for (const char* text : identities) expect_identity(text);
}

TEST(SymZero, LagrangeIdentity) {
  // |u|^2 |v|^2 - (u.v)^2 - |u x v|^2 == 0 for unit vectors written with angles, and for
  // generic symbolic vectors.
  auto check = [](const std::array<Expr, 3>& u, const std::array<Expr, 3>& v) {
    auto dot = [](const std::array<Expr, 3>& a, const std::array<Expr, 3>& b) {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    const std::array<Expr, 3> c = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    expect_proved_zero(dot(u, u) * dot(v, v) - pow(dot(u, v), 2) - dot(c, c), "Lagrange identity");
  };
  const Expr a = symbol("a");
  const Expr b = symbol("b");
  const Expr c = symbol("c");
  const Expr d = symbol("d");
  check({sin(a) * cos(b), sin(a) * sin(b), cos(a)}, {sin(c) * cos(d), sin(c) * sin(d), cos(c)});
  check({sin(a) * cos(b), sin(a + b), Expr(2) * cos(a - b)}, {symbol("v1"), cos(c) * symbol("v2"), sin(d)});
  check({symbol("u1"), symbol("u2"), symbol("u3")}, {symbol("v1"), symbol("v2"), symbol("v3")});
}

using Matrix = std::array<std::array<Expr, 3>, 3>;

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix r;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  }
  return r;
}

// Rotation part of a standard Denavit-Hartenberg transform: Rz(theta) * Rx(alpha).
Matrix dh_rotation(Expr theta, Expr alpha) {
  const Expr ct = cos(theta);
  const Expr st = sin(theta);
  const Expr ca = cos(alpha);
  const Expr sa = sin(alpha);
  return {{{ct, -st * ca, st * sa}, {st, ct * ca, -ct * sa}, {Expr(0), sa, ca}}};
}

TEST(SymZero, DenavitHartenbergChainIsOrthogonal) {
  const Expr q1 = symbol("q1");
  const Expr q2 = symbol("q2");
  const Expr q3 = symbol("q3");
  const Expr half_pi = pi() / Expr(2);
  const std::array<std::array<Expr, 3>, 2> twists = {
      {{symbol("alpha1"), symbol("alpha2"), symbol("alpha3")}, {half_pi, Expr(0), -half_pi}}};
  for (const auto& alpha : twists) {
    const Matrix r =
        multiply(multiply(dh_rotation(q1, alpha[0]), dh_rotation(q2 + half_pi, alpha[1])), dh_rotation(q3, alpha[2]));
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = 0; j < 3; ++j) {
        const Expr rtr = r[0][i] * r[0][j] + r[1][i] * r[1][j] + r[2][i] * r[2][j];  // (R^T R)_ij
        expect_proved_zero(rtr - Expr(i == j ? 1 : 0), "(R^T R - I)_" + std::to_string(i) + std::to_string(j));
        const Expr rrt = r[i][0] * r[j][0] + r[i][1] * r[j][1] + r[i][2] * r[j][2];  // (R R^T)_ij
        expect_proved_zero(rrt - Expr(i == j ? 1 : 0), "(R R^T - I)_" + std::to_string(i) + std::to_string(j));
      }
    }
    // ... and the entries are not trivially zero: R itself is not the identity.
    EXPECT_EQ(test_zero(r[0][0] - Expr(1)).verdict, ZeroVerdict::NonZero);
  }
}

struct NonIdentity {
  std::string text;
  std::function<double(const Values&)> value;  // the same function, written with <cmath>
};

TEST(SymZero, NonIdentitiesHaveAnHonestWitness) {
  auto v = [](const Values& m, const char* name) { return m.at(name); };
  const NonIdentity cases[] = {
      {"sin(2*x) - 2*sin(x)", [&](const Values& m) { return std::sin(2 * v(m, "x")) - 2 * std::sin(v(m, "x")); }},
      {"sin(x + y) - sin(x) - sin(y)",
       [&](const Values& m) { return std::sin(v(m, "x") + v(m, "y")) - std::sin(v(m, "x")) - std::sin(v(m, "y")); }},
      {"cos(x)^2 - sin(x)^2 - 1",
       [&](const Values& m) { return std::pow(std::cos(v(m, "x")), 2) - std::pow(std::sin(v(m, "x")), 2) - 1; }},
      {"sin(q/2) - sin(q)/2", [&](const Values& m) { return std::sin(v(m, "q") / 2) - std::sin(v(m, "q")) / 2; }},
      {"sin(x + 1) - sin(x)*cos(1)",
       [&](const Values& m) { return std::sin(v(m, "x") + 1) - std::sin(v(m, "x")) * std::cos(1.0); }},
      {"sin(x)^2 + cos(x)^2 - 1 + x*y/1000", [&](const Values& m) { return v(m, "x") * v(m, "y") / 1000; }},
      {"m*(sin(q1)^2 + cos(q1)^2) - m - 0.001*q1", [&](const Values& m) { return -0.001 * v(m, "q1"); }},
      {"sin(q3 - q2) - sin(q3)*cos(q2) - cos(q3)*sin(q2)",
       [&](const Values& m) { return std::sin(v(m, "q3") - v(m, "q2")) - std::sin(v(m, "q3") + v(m, "q2")); }},
      {"x^2 - y^2", [&](const Values& m) { return v(m, "x") * v(m, "x") - v(m, "y") * v(m, "y"); }},
      {"sin(2) - 2*sin(1)", [](const Values&) { return std::sin(2.0) - 2 * std::sin(1.0); }},
      {"sin(x*y) - x*sin(y)",
       [&](const Values& m) { return std::sin(v(m, "x") * v(m, "y")) - v(m, "x") * std::sin(v(m, "y")); }},
  };
  for (const NonIdentity& c : cases) {
    const ZeroTestResult r = test_zero(parse_or_throw(c.text));
    EXPECT_EQ(r.verdict, ZeroVerdict::NonZero) << c.text;
    EXPECT_TRUE(r.proved) << c.text << ": " << r.note;
    const double value = c.value(witness_values(r));
    EXPECT_GT(std::abs(value), 1e-6) << c.text << ": the witness does not refute";
    EXPECT_NEAR(r.witness_value, value, 1e-9 * std::max(1.0, std::abs(value))) << c.text;
  }
}

TEST(SymZero, OutsideTheClassNonZeroIsShownByEvaluation) {
  auto v = [](const Values& m, const char* name) { return m.at(name); };
  const NonIdentity cases[] = {
      {"sqrt(x) - x", [&](const Values& m) { return std::sqrt(v(m, "x")) - v(m, "x"); }},
      {"sqrt(x^2) - x", [&](const Values& m) { return std::sqrt(v(m, "x") * v(m, "x")) - v(m, "x"); }},
      {"atan2(y, x) - y/x", [&](const Values& m) { return std::atan2(v(m, "y"), v(m, "x")) - v(m, "y") / v(m, "x"); }},
      {"1/(1 + x^2) - 1 + x^2",
       [&](const Values& m) { return 1 / (1 + v(m, "x") * v(m, "x")) - 1 + v(m, "x") * v(m, "x"); }},
  };
  for (const NonIdentity& c : cases) {
    const ZeroTestResult r = test_zero(parse_or_throw(c.text));
    EXPECT_EQ(r.verdict, ZeroVerdict::NonZero) << c.text;
    EXPECT_FALSE(r.proved) << c.text;
    EXPECT_FALSE(r.note.empty()) << c.text;
    const double value = c.value(witness_values(r));
    EXPECT_GT(std::abs(value), 1e-6) << c.text;
    EXPECT_NEAR(r.witness_value, value, 1e-9 * std::max(1.0, std::abs(value))) << c.text;
  }
}

// Sampling can only refute. Rounding noise on an expression that is identically zero but not
// provably so must leave the verdict undecided, never "not identically zero".
TEST(SymZero, RoundingNoiseIsNotAWitness) {
  const Expr x = symbol("x");
  const Expr u = pow(x + Expr(10), 2);
  const Expr big = pow(x + Expr(10), 8);
  const Expr cases[] = {
      sqrt(u) * big - sqrt(expand(u)) * big,
      (sqrt(u) - sqrt(expand(u))) * big,
      atan2(expand(pow(x + Expr(3), 5)), Expr(1) + x * x) * big - atan2(pow(x + Expr(3), 5), Expr(1) + x * x) * big,
  };
  for (const Expr e : cases) {
    const ZeroTestResult r = test_zero(e);
    EXPECT_NE(r.verdict, ZeroVerdict::NonZero) << to_string(e) << ": 'witness' value " << r.witness_value;
    EXPECT_FALSE(r.proved);
  }
}

TEST(SymZero, TooLargeForTheNormalFormFallsBackToSampling) {
  const Expr x = symbol("x");
  const Expr e = sin(Expr(100) * x) - Expr(2) * sin(Expr(50) * x) * cos(Expr(50) * x);
  EXPECT_THROW(trig_normal_form(e), std::overflow_error);
  const ZeroTestResult r = test_zero(e);
  EXPECT_EQ(r.verdict, ZeroVerdict::Unknown);
  EXPECT_FALSE(r.proved);
  EXPECT_FALSE(r.note.empty());
  const ZeroTestResult n = test_zero(sin(Expr(100) * x) - sin(Expr(99) * x));
  EXPECT_EQ(n.verdict, ZeroVerdict::NonZero);
  EXPECT_FALSE(n.proved);
  const double at = witness_values(n).at("x");
  EXPECT_NEAR(n.witness_value, std::sin(100 * at) - std::sin(99 * at), 1e-9);
  EXPECT_GT(std::abs(n.witness_value), 1e-3);
}

TEST(SymZero, TrigPolynomialMinusExpandIsZero) {
  Generator gen(0x2E40);
  for (int n = 0; n < 200; ++n) {
    const Sample s = gen.trig_polynomial(2 + n % 2);
    expect_proved_zero(s.expr - expand(s.expr), "e - expand(e)");
  }
}

TEST(SymZero, TrigPolynomialMinusRewrittenCopyIsZero) {
  Generator gen(0x2E41);
  test::Rewriter rewrite(0x2E42);
  for (int n = 0; n < 200; ++n) {
    const Sample s = gen.trig_polynomial(2 + n % 2);
    const Expr copy = rewrite(s);
    const Point p = gen.point();
    ASSERT_TRUE(test::close(test::engine_eval(copy, p), s(p), 1e-9))
        << "the rewrite itself is wrong: " << to_string(copy);
    expect_proved_zero(s.expr - copy, "e - rewritten(e)");
  }
}

TEST(SymZero, GeneralExpressionMinusRewrittenCopyIsZero) {
  // sqrt, atan2 and denominators are opaque atoms; the copy keeps them, so the difference is
  // still provably zero.
  Generator gen(0x2E43);
  test::Rewriter rewrite(0x2E44);
  for (int n = 0; n < 200; ++n) {
    const Sample s = gen.expression(2 + n % 2);
    const Expr copy = rewrite(s);
    const Point p = gen.point();
    ASSERT_TRUE(test::close(test::engine_eval(copy, p), s(p), 1e-9))
        << "the rewrite itself is wrong: " << to_string(copy);
    expect_proved_zero(s.expr - copy, "e - rewritten(e)");
  }
}

TEST(SymZero, GeneralExpressionMinusExpandIsNeverNonZero) {
  // expand rewrites inside sqrt/atan2 arguments, so the atoms differ and the difference may be
  // undecided; but it is identically zero, so "not identically zero" would be a wrong answer.
  Generator gen(0x2E45);
  for (int n = 0; n < 150; ++n) {
    const Sample s = gen.expression(2 + n % 2);
    const ZeroTestResult r = test_zero(s.expr - expand(s.expr));
    EXPECT_NE(r.verdict, ZeroVerdict::NonZero) << to_string(s.expr) << ": witness value " << r.witness_value;
  }
}

TEST(SymZero, PerturbedTrigPolynomialIsNonZero) {
  Generator gen(0x2E46);
  test::Rewriter rewrite(0x2E47);
  int fell_back = 0;
  for (int n = 0; n < 200; ++n) {
    const Sample s = gen.trig_polynomial(2 + n % 2);
    // A small term, in the class: eps * (monomial in a symbol and a sine).
    const Sample small = test::num(Rational(1, 1000)) * gen.trig_polynomial(0) * gen.trig_polynomial(0);
    if (small.expr.is_number() && small.expr.is_zero()) continue;
    const Expr e = s.expr - rewrite(s) + small.expr;
    const ZeroTestResult r = test_zero(e);
    EXPECT_EQ(r.verdict, ZeroVerdict::NonZero) << to_string(small.expr);
    if (!r.proved) {
      // Documented limit: 64-bit coefficients of the normal form can overflow (sin(28*y) with
      // y = q/12 after the half-angle rewrite); then the verdict comes from sampling.
      EXPECT_TRUE(r.note.find("overflow") != std::string::npos || r.note.find("too large") != std::string::npos)
          << r.note << "\n  " << to_string(s.expr) << "\n  + " << to_string(small.expr);
      ++fell_back;
    }
    const double expected = small(witness_point(r));  // s - rewrite(s) vanishes everywhere
    EXPECT_GT(std::abs(expected), 1e-9) << "witness does not refute " << to_string(small.expr);
    EXPECT_NEAR(r.witness_value, expected, 1e-9) << to_string(e);
  }
  EXPECT_LE(fell_back, 4);
}

TEST(SymZero, SimplifyIsEqualAndNeverLarger) {
  Generator gen(0x5141);
  for (int n = 0; n < 150; ++n) {
    const Sample s = n % 2 == 0 ? gen.trig_polynomial(3) : gen.expression(2);
    const Expr simple = simplify(s.expr);
    EXPECT_LE(simple.dag_size(), s.expr.dag_size());
    const Point p = gen.point();
    EXPECT_TRUE(test::close(test::engine_eval(simple, p), s(p), 1e-8))
        << to_string(s.expr) << " -> " << to_string(simple);
  }
  EXPECT_EQ(simplify(parse_or_throw("sin(x)^2 + cos(x)^2")), Expr(1));
  EXPECT_EQ(simplify(parse_or_throw("2*sin(x)*cos(x) - sin(2*x) + y")), symbol("y"));
}

// The normal form of sin(S)^2 + cos(S)^2 - 1 with S a sum of 14 angles has ~2^28 monomial
// products; without a work budget it ran for minutes and ended in bad_alloc (found by fuzzing).
TEST(SymZero, WorkBudgetEndsHugeNormalFormsInSampling) {
  std::vector<Expr> angles;
  for (char c = 'a'; c <= 'n'; ++c) angles.push_back(symbol(std::string(1, c)));
  const Expr s = add(angles);
  const Expr identity = pow(sin(s), 2) + pow(cos(s), 2) - Expr(1);
  EXPECT_THROW(trig_normal_form(identity), std::overflow_error);
  const ZeroTestResult r = test_zero(identity);
  EXPECT_EQ(r.verdict, ZeroVerdict::Unknown);  // sampling cannot prove zero, and finds no witness
  EXPECT_FALSE(r.proved);
  EXPECT_NE(r.note.find("too large"), std::string::npos) << r.note;

  // The budget is a parameter: a small identity is proved with the default budget and is
  // left undecided (never called non-zero) with a budget too small for it.
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  const Expr small = sin(x + y) - sin(x) * cos(y) - cos(x) * sin(y);
  EXPECT_EQ(test_zero(small).verdict, ZeroVerdict::Zero);
  EXPECT_EQ(test_zero(small, 2).verdict, ZeroVerdict::Unknown);
}

}  // namespace
}  // namespace dyncc::sym
