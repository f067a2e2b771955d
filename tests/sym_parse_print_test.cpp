// Parser and printer: printing then parsing gives back the same node, malformed input gets an
// error at the right column (never a crash), and numbers are read exactly.
#include <gtest/gtest.h>

#include <string>

#include "random_expr.hpp"
#include "sym/diff.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"

namespace dyncc::sym {
namespace {

using test::Generator;

TEST(SymParsePrint, RoundTripOfRandomExpressions) {
  Generator gen(0x9A45);
  for (int n = 0; n < 500; ++n) {
    const Expr e = n % 4 == 3 ? gen.trig_polynomial(3).expr : gen.expression(2 + n % 3).expr;
    const std::string text = to_string(e);
    const ParseResult r = parse(text);
    ASSERT_TRUE(r.ok()) << text << "\n  column " << r.error.column << ": " << r.error.message;
    EXPECT_EQ(*r.expr, e) << text << "\n  reparsed as " << to_string(*r.expr);
  }
}

TEST(SymParsePrint, RoundTripOfSpecialForms) {
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  const Expr cases[] = {
      Expr(0),
      Expr(-7),
      number(Rational(-1, 3)),
      number(Rational(9, 50)),
      number(Rational(INT64_MAX)),
      number(Rational(1, INT64_MAX)),
      number(Rational(-INT64_MAX, 7)),
      pi(),
      -x,
      -(x * y),
      Rational(-2, 3) / (x * y),
      Rational(1, 3) * pow(x, -2),
      Expr(3) / (x + y),
      -pow(x + y, 3),
      pow(x + y, -2) * pow(y, 2),
      sqrt(x) * x,
      Expr(1) / sqrt(Expr(1) + x * x),
      sin(x + pi() / Expr(3)),
      cos(Expr(2) * x - Rational(1, 7)),
      atan2(Expr(-1), x),
      atan2(-x, Expr(1) - y),
      pow(x, 64) * pow(y, -64),
      pow(x, 66),  // merged exponents may exceed the parser's limit of 64
      pow(x, 4097) * pow(y, -130),
      Expr(3) / pow(x + y, 128),
      pow(sqrt(x + Expr(1)), 131),
      sin(pow(x, 2)) + number(Rational(1, 1000000)) * y - Rational(5, 2),
      symbol("q10") * symbol("q2") + symbol("a_b"),
  };
  for (const Expr e : cases) {
    const std::string text = to_string(e);
    const ParseResult r = parse(text);
    ASSERT_TRUE(r.ok()) << text << ": column " << r.error.column << ": " << r.error.message;
    EXPECT_EQ(*r.expr, e) << text << " reparsed as " << to_string(*r.expr);
  }
}

struct ErrorCase {
  std::string text;
  std::size_t column;
  std::string message_part;
};

TEST(SymParsePrint, ErrorColumns) {
  const std::string deep = std::string(500, '(') + "x" + std::string(500, ')');
  const ErrorCase cases[] = {
      {"1/(x", 5, "expected ')' to close '(' at column 3"},
      {"2x", 2, "2*x"},
      {"x +", 4, "found the end"},
      {"sin x", 5, "expected '(' after function 'sin'"},
      {"foo(x)", 1, "unknown function 'foo'"},
      {"x^y", 3, "exponent must be a number"},
      {"x^0.3", 3, "integer or a half-integer"},
      {"1/0", 2, "division by zero"},
      {"x/(y - y)", 2, "division by zero"},
      {"x^1000", 3, "too large"},
      {"", 1, "found nothing"},
      {"   ", 4, "found nothing"},
      {"x $ y", 3, "found '$'"},
      {"x)", 2, "unmatched ')'"},
      {"(x + y))", 8, "unmatched ')'"},
      {"sin(x, y)", 1, "takes 1 argument, found 2"},
      {"atan2(x)", 1, "takes 2 arguments, found 1"},
      {"sin()", 1, "takes 1 argument, found 0"},
      {"cos(x", 6, "expected ',' or ')'"},
      {"sqrt(-4)", 1, "square root of a negative number"},
      {"(-4)^0.5", 5, "square root of a negative number"},
      {"0^-1", 2, "division by zero"},
      {"2^64", 2, "overflows"},
      {"99999999999999999999", 1, "out-of-range number"},
      {"1.2.3", 1, "malformed"},
      {"x * * y", 5, "found '*'"},
      {deep, 101, "nested deeper"},
      {std::string(5000, '-') + "x", 200, "nested deeper"},  // one level per '-', after the outer expression
      {"x^4^31", 3, "too large"},
      {"2**7777777777477777426", 4, "too large"},
      {"1e-19", 1, "out-of-range number"},
      {"(((((x^64)^64)^64)^64)^64)^64", 27, "exponent out of range"},  // x^(2^36)
      {"x" + std::string(300, '^'), 3, "expected a number"},
  };
  for (const ErrorCase& c : cases) {
    const ParseResult r = parse(c.text);
    const std::string shown = c.text.size() > 40 ? c.text.substr(0, 40) + "..." : c.text;
    ASSERT_FALSE(r.ok()) << "'" << shown << "' parsed as " << to_string(*r.expr);
    EXPECT_EQ(r.error.column, c.column) << "'" << shown << "': " << r.error.message;
    EXPECT_NE(r.error.message.find(c.message_part), std::string::npos) << "'" << shown << "': " << r.error.message;
  }
  EXPECT_THROW(parse_or_throw("1/(x"), std::invalid_argument);
}

// Inputs found by fuzz/fuzz_expression.cpp (fuzz/crashes), checked with the fuzzer's contract:
// parse never throws, errors have a column in [1, size + 1] and a message, accepted input prints
// back to the same node, and diff by each symbol works.
TEST(SymParsePrint, FuzzReproducers) {
  const std::string inputs[] = {
      "(((((x^64)^64)^64)^64)^64)^64",
      std::string("(a +(b)^4 ^31 - 3*a^2*b\0- 3", 27),
      "888888*88888**7777777777477777426*7777426",
      "x^4^31",
      "cos(pi/ +03-1.*ata-an2t1)",
      "cos(pi/3 - x)",
      "(x^2)^33",
      // A coefficient of -2^63 (an int64 but outside Rational's symmetric range) used to be
      // built, and printing it threw (the printer takes the magnitude): now it is an overflow.
      "(-9223372036854775807-1)*x",
      "-4611686018427387904*2*x",
      "-4611686018427387904*2",
      "-9223372036854775807*x-x",
      "(-1-9223372036854775807)/3*x",
      "-9223372036854775807*x",
  };
  for (const std::string& text : inputs) {
    ParseResult r;
    ASSERT_NO_THROW(r = parse(text)) << text;
    if (!r.ok()) {
      EXPECT_GE(r.error.column, 1U) << text;
      EXPECT_LE(r.error.column, text.size() + 1) << text;
      EXPECT_FALSE(r.error.message.empty()) << text;
      continue;
    }
    const std::string printed = to_string(*r.expr);
    const ParseResult back = parse(printed);
    ASSERT_TRUE(back.ok()) << text << " printed as " << printed << ": " << back.error.message;
    EXPECT_EQ(*back.expr, *r.expr) << text << " printed as " << printed;
    for (const Expr s : free_symbols(*r.expr)) EXPECT_NO_THROW((void)diff(*r.expr, s)) << text;
  }
  const Expr x = symbol("x");
  EXPECT_FALSE(parse("-4611686018427387904*2").ok());
  EXPECT_EQ(to_string(parse_or_throw("-9223372036854775807*x")), "-9223372036854775807*x");
  EXPECT_EQ(parse_or_throw("(x^2)^33"), pow(x, 66));
  EXPECT_EQ(parse_or_throw("cos(pi/3 - x)"), parse_or_throw("cos(x - pi/3)"));
  // 64^5 = 2^30 still fits in int: the derivative keeps the exact exponent.
  const Expr big = parse_or_throw("((((x^64)^64)^64)^64)^64");
  EXPECT_EQ(big, pow(x, 1 << 30));
  EXPECT_EQ(diff(big, x), Expr(1 << 30) * pow(x, (1 << 30) - 1));
}

TEST(SymParsePrint, DeepButLegalNestingParses) {
  const std::string text = std::string(90, '(') + "x" + std::string(90, ')');
  EXPECT_EQ(parse_or_throw(text), symbol("x"));
  std::string calls = "x";
  for (int i = 0; i < 60; ++i) calls.insert(0, "sin(").append(")");
  EXPECT_TRUE(parse(calls).ok());
}

TEST(SymParsePrint, NumbersAreExact) {
  EXPECT_EQ(parse_or_throw("0.180"), number(Rational(9, 50)));
  EXPECT_EQ(parse_or_throw("1e-3"), number(Rational(1, 1000)));
  EXPECT_EQ(parse_or_throw("2.5E2"), Expr(250));
  EXPECT_EQ(parse_or_throw("1e+2"), Expr(100));
  EXPECT_EQ(parse_or_throw(".5"), number(Rational(1, 2)));
  EXPECT_EQ(parse_or_throw("007"), Expr(7));
  EXPECT_EQ(parse_or_throw("1/3"), number(Rational(1, 3)));
  EXPECT_EQ(parse_or_throw("0.1 + 0.2"), parse_or_throw("0.3"));
  EXPECT_EQ(parse_or_throw("9223372036854775807"), number(Rational(INT64_MAX)));
  EXPECT_EQ(parse_or_throw("1e-18"), number(Rational(1, 1000000000000000000)));
}

TEST(SymParsePrint, GrammarAndPrecedence) {
  const Expr x = symbol("x");
  const Expr y = symbol("y");
  EXPECT_EQ(parse_or_throw("x**2"), pow(x, 2));
  EXPECT_EQ(parse_or_throw("x^-1"), Expr(1) / x);
  EXPECT_EQ(parse_or_throw("2^-2"), number(Rational(1, 4)));
  EXPECT_EQ(parse_or_throw("2^3^2"), Expr(512));  // right-associative
  EXPECT_EQ(parse_or_throw("-2^2"), Expr(-4));    // unary minus binds looser than ^
  EXPECT_EQ(parse_or_throw("x - y - x"), -y);     // left-associative
  EXPECT_EQ(parse_or_throw("8/2/2"), Expr(2));
  EXPECT_EQ(parse_or_throw("x^0.5"), sqrt(x));
  EXPECT_EQ(parse_or_throw("x^1.5"), x * sqrt(x));
  EXPECT_EQ(parse_or_throw("x^(1/2)"), sqrt(x));
  EXPECT_EQ(parse_or_throw("x^(-1/2)"), Expr(1) / sqrt(x));
  EXPECT_EQ(parse_or_throw(" \tx+\ty "), x + y);
  EXPECT_EQ(parse_or_throw("+x"), x);
  EXPECT_EQ(parse_or_throw("pi"), pi());
  EXPECT_EQ(parse_or_throw("cos(pi)"), Expr(-1));
  EXPECT_EQ(parse_or_throw("atan2(y, x)"), atan2(y, x));
  EXPECT_EQ(parse_or_throw("2*x*y/(4*x)"), y / Expr(2));
}

TEST(SymParsePrint, SymbolUsesAreReportedWithColumns) {
  const ParseResult r = parse("x + sin(q10) * x");
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.symbols.size(), 3U);
  EXPECT_EQ(r.symbols[0].name, "x");
  EXPECT_EQ(r.symbols[0].column, 1U);
  EXPECT_EQ(r.symbols[1].name, "q10");
  EXPECT_EQ(r.symbols[1].column, 9U);
  EXPECT_EQ(r.symbols[2].column, 16U);
  EXPECT_TRUE(parse("pi*2").symbols.empty());
}

TEST(SymParsePrint, LatexUsesSubscriptsAndFractions) {
  const std::string s = to_latex(parse_or_throw("sin(q12)/3 + pi"));
  EXPECT_NE(s.find("q_{12}"), std::string::npos) << s;
  EXPECT_NE(s.find("\\frac"), std::string::npos) << s;
  EXPECT_NE(s.find("\\sin"), std::string::npos) << s;
  EXPECT_NE(s.find("\\pi"), std::string::npos) << s;
}

}  // namespace
}  // namespace dyncc::sym
