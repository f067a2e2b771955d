// Exact rationals: every operation agrees with an independent 128-bit reference, overflow
// throws instead of wrapping, and text round-trips.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <string>

#include "random_expr.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"
#include "sym/rational.hpp"

namespace dyncc::sym {
namespace {

constexpr std::int64_t kMax = INT64_MAX;
constexpr std::int64_t kMin = INT64_MIN;  // outside the symmetric range [-kMax, kMax]

// ---- reference: normalise an exact 128-bit fraction, or report that it does not fit ----
struct Ref {
  std::int64_t num;
  std::int64_t den;
};

Int128 gcd(Int128 a, Int128 b) {
  if (a < 0) a = -a;
  if (b < 0) b = -b;
  while (b != 0) {
    const Int128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}

std::optional<Ref> reference(Int128 n, Int128 d) {
  if (d < 0) {
    n = -n;
    d = -d;
  }
  const Int128 g = gcd(n, d);
  if (g > 1) {
    n /= g;
    d /= g;
  }
  if (n < -kMax || n > kMax || d > kMax) return std::nullopt;
  return Ref{static_cast<std::int64_t>(n), static_cast<std::int64_t>(d)};
}

std::string show(const Rational& r) { return std::to_string(r.num()) + "/" + std::to_string(r.den()); }

class RandomRationals {
 public:
  explicit RandomRationals(std::uint64_t seed) : rng_(seed) {}

  std::int64_t integer() {
    switch (std::uniform_int_distribution<int>(0, 5)(rng_)) {
      case 0: return std::uniform_int_distribution<std::int64_t>(-20, 20)(rng_);
      case 1: return std::uniform_int_distribution<std::int64_t>(-(INT64_C(1) << 31), INT64_C(1) << 31)(rng_);
      case 2: return std::uniform_int_distribution<std::int64_t>(-(INT64_C(1) << 62), INT64_C(1) << 62)(rng_);
      case 3: return std::uniform_int_distribution<std::int64_t>(kMin, kMax)(rng_);
      case 4: {
        const std::int64_t extremes[] = {
            kMax, kMin, kMax - 1, kMin + 1, INT64_C(1) << 62, -(INT64_C(1) << 62), INT64_C(3037000499)};
        return extremes[std::uniform_int_distribution<int>(0, 6)(rng_)];
      }
      default: return std::uniform_int_distribution<std::int64_t>(-1000000, 1000000)(rng_);
    }
  }

  Rational rational() {
    std::int64_t n = integer();
    if (n == kMin) n = -kMax;  // Rational(kMin) throws (OverflowThrowsInsteadOfWrapping)
    std::int64_t d = integer();
    if (d == 0) d = 1;
    if (d == kMin) d = kMax;  // -kMin does not fit: the normalised value would overflow
    const auto ref = reference(n, d);
    if (!ref) return Rational(n);
    return Rational(n, d);
  }

 private:
  std::mt19937_64 rng_;
};

void expect_matches(const char* op, const Rational& a, const Rational& b, Int128 n, Int128 d,
                    const std::function<Rational()>& compute) {
  const auto ref = reference(n, d);
  if (ref) {
    Rational r;
    ASSERT_NO_THROW(r = compute()) << show(a) << " " << op << " " << show(b) << " fits in 64 bits";
    EXPECT_EQ(r.num(), ref->num) << show(a) << " " << op << " " << show(b);
    EXPECT_EQ(r.den(), ref->den) << show(a) << " " << op << " " << show(b);
  } else {
    EXPECT_THROW(compute(), RationalOverflow) << show(a) << " " << op << " " << show(b) << " does not fit";
  }
}

TEST(SymRational, ArithmeticMatchesA128BitReference) {
  RandomRationals gen(0x4A7);
  for (int i = 0; i < 20000; ++i) {
    const Rational a = gen.rational();
    const Rational b = gen.rational();
    const Int128 an = a.num();
    const Int128 ad = a.den();
    const Int128 bn = b.num();
    const Int128 bd = b.den();
    expect_matches("+", a, b, an * bd + bn * ad, ad * bd, [&] { return a + b; });
    expect_matches("-", a, b, an * bd - bn * ad, ad * bd, [&] { return a - b; });
    expect_matches("*", a, b, an * bn, ad * bd, [&] { return a * b; });
    if (b.is_zero()) {
      EXPECT_THROW(a / b, std::domain_error);
    } else {
      expect_matches("/", a, b, an * bd, ad * bn, [&] { return a / b; });
    }
    const bool less = an * bd < bn * ad;
    EXPECT_EQ(a < b, less) << show(a) << " < " << show(b);
    EXPECT_EQ(a == b, an == bn && ad == bd);
  }
}

TEST(SymRational, OverflowThrowsInsteadOfWrapping) {
  EXPECT_THROW(Rational(kMax) + Rational(1), RationalOverflow);
  EXPECT_THROW(Rational(-kMax) - Rational(2), RationalOverflow);
  EXPECT_THROW((void)Rational(kMin), RationalOverflow);  // the range is symmetric: -2^63 is out
  EXPECT_THROW(Rational(-kMax) - Rational(1), RationalOverflow);
  EXPECT_THROW(Rational(-kMax) + Rational(-1), RationalOverflow);
  EXPECT_THROW(Rational(kMin / 2) * Rational(2), RationalOverflow);
  EXPECT_THROW((void)Rational(-2).pow(63), RationalOverflow);
  EXPECT_THROW(Rational(kMax) * Rational(2), RationalOverflow);
  EXPECT_THROW(Rational(1, kMin), RationalOverflow);  // the denominator 2^63 does not fit
  EXPECT_THROW(Rational(kMin, -1), RationalOverflow);
  EXPECT_THROW((void)Rational(2).pow(63), RationalOverflow);
  EXPECT_THROW((void)Rational(1, 2).pow(63), RationalOverflow);
  EXPECT_THROW((void)Rational(3, 7).pow(-40), RationalOverflow);
  EXPECT_THROW(Rational(1, 0), std::domain_error);
  EXPECT_THROW((void)Rational(0).pow(-1), std::domain_error);
  // ... and results that fit are exact, including the ends of the range; negation never throws.
  EXPECT_EQ(-Rational(-kMax), Rational(kMax));
  EXPECT_EQ(Rational(-kMax).abs(), Rational(kMax));
  EXPECT_EQ(Rational(-kMax) + Rational(kMax), Rational(0));
  EXPECT_EQ(Rational(-1) - Rational(-kMax), Rational(kMax - 1));
  EXPECT_EQ(Rational(kMax) - Rational(kMax - 1), Rational(1));
  EXPECT_EQ(Rational(1 - kMax) / Rational(-1), Rational(kMax - 1));
  EXPECT_EQ(Rational(kMin / 2) / Rational(-1), Rational(INT64_C(1) << 62));
  EXPECT_EQ(Rational(kMax, 3) * Rational(3), Rational(kMax));
  EXPECT_EQ(Rational(1).pow(INT_MIN), Rational(1));
  EXPECT_EQ(Rational(-1).pow(INT_MIN), Rational(1));
  EXPECT_THROW((void)Rational(2).pow(INT_MIN), RationalOverflow);
}

TEST(SymRational, PowerMatchesRepeatedMultiplication) {
  RandomRationals gen(0x90E);
  std::mt19937_64 rng(7);
  for (int i = 0; i < 3000; ++i) {
    const Rational base = gen.rational();
    const int k = std::uniform_int_distribution<int>(-70, 70)(rng);
    if (base.is_zero() && k < 0) {
      EXPECT_THROW((void)base.pow(k), std::domain_error);
      continue;
    }
    // Reference: |num|^|k| and den^|k| by repeated 128-bit multiplication; once a magnitude
    // exceeds 2^63 it can only grow, so the result does not fit.
    Int128 n = 1;
    Int128 d = 1;
    bool fits = true;
    for (int j = 0; j < std::abs(k) && fits; ++j) {
      n *= base.num();
      d *= base.den();
      const Int128 limit = static_cast<Int128>(1) << 63;
      fits = (n < 0 ? -n : n) <= limit && d <= limit;
    }
    if (k < 0) std::swap(n, d);
    const auto ref = fits ? reference(n, d) : std::nullopt;
    if (ref) {
      const Rational r = base.pow(k);
      EXPECT_EQ(r.num(), ref->num) << show(base) << "^" << k;
      EXPECT_EQ(r.den(), ref->den) << show(base) << "^" << k;
    } else {
      EXPECT_THROW((void)base.pow(k), RationalOverflow) << show(base) << "^" << k;
    }
  }
}

TEST(SymRational, OverflowInExpressionsThrows) {
  const Expr x = symbol("x");
  EXPECT_THROW(number(Rational(kMax)) + Expr(1), RationalOverflow);
  EXPECT_THROW(number(Rational(kMax)) * x * Expr(2), RationalOverflow);
  EXPECT_THROW(pow(Expr(2) * x, 63), RationalOverflow);
  EXPECT_THROW(pow(Expr(-2) * x, 63), RationalOverflow);  // -2^63: the range is symmetric
  EXPECT_NO_THROW(pow(Expr(-2) * x, 62));
  EXPECT_THROW(x * Rational(1, kMax) * Rational(1, 3), RationalOverflow);
  EXPECT_THROW(x + number(Rational(kMax)) * x, RationalOverflow);  // coefficient 2^63
  // Exponents are used as int throughout the engine: a merged exponent beyond int range is an
  // overflow, not a silently truncated power.
  EXPECT_EQ(pow(pow(x, 1 << 15), 1 << 15), pow(x, 1 << 30));
  EXPECT_THROW(pow(pow(x, 1 << 30), 4), RationalOverflow);
  EXPECT_THROW(pow(x, 1 << 30) * pow(x, 1 << 30), RationalOverflow);
  EXPECT_THROW(pow(Expr(1) + x, 1 << 30) * pow(Expr(1) + x, 1 << 30), RationalOverflow);
}

TEST(SymRational, ExactSquareRootsNearTheEndOfTheRange) {
  // sqrt of a Number is folded only when numerator and denominator are perfect squares.
  const std::int64_t r = 3037000499;  // floor(sqrt(2^63 - 1))
  EXPECT_EQ(sqrt(Expr(r * r)), Expr(r));
  EXPECT_EQ(sqrt(number(Rational(1, r * r))), number(Rational(1, r)));
  EXPECT_EQ(sqrt(number(Rational(4, r * r))), number(Rational(2, r)));
  for (const std::int64_t v : {kMax, r * r + 1, r * r - 1, kMax - 1}) {
    const Expr s = sqrt(Expr(v));
    EXPECT_EQ(s.kind(), Kind::Sqrt) << v;
    EXPECT_NEAR(test::engine_eval(s, {}), std::sqrt(static_cast<double>(v)), 1.0) << v;
  }
  std::mt19937_64 rng(0x5A);
  for (int i = 0; i < 2000; ++i) {
    const std::int64_t k = std::uniform_int_distribution<std::int64_t>(1, r)(rng);
    EXPECT_EQ(sqrt(Expr(k * k)), Expr(k)) << k;
    EXPECT_EQ(sqrt(Expr(k * k - 1)).kind(), k == 1 ? Kind::Number : Kind::Sqrt) << k;
  }
}

TEST(SymRational, ExtremeMultiplesOfPiInsideFunctions) {
  // k*pi with a huge denominator: reducing k modulo 2 must not overflow.
  const Expr x = symbol("x");
  for (const Rational& k : {Rational(1, kMax), Rational(kMax - 1, kMax), Rational(kMax, 2), Rational(kMin + 1, 3),
                            Rational(-kMax, kMax - 1)}) {
    const Expr s = sin(number(k) * pi() + x);
    const Expr c = cos(number(k) * pi());
    const double kd = k.to_double();
    // sin(k pi + x) with k pi reduced exactly: compare with the exactly reduced double angle.
    const Rational reduced = k - Rational(2) * Rational(static_cast<std::int64_t>(std::floor(kd / 2)));
    test::Point p{};
    p[0] = 0.25;
    EXPECT_NEAR(test::engine_eval(s, p), std::sin(reduced.to_double() * std::numbers::pi + 0.25), 1e-6) << show(k);
    EXPECT_NEAR(test::engine_eval(c, p), std::cos(reduced.to_double() * std::numbers::pi), 1e-6) << show(k);
  }
}

TEST(SymRational, TextRoundTrip) {
  RandomRationals gen(0x7E7);
  for (int i = 0; i < 5000; ++i) {
    const Rational r = gen.rational();
    const std::string text = r.to_string();
    const ParseResult p = parse(text);
    ASSERT_TRUE(p.ok()) << text << ": " << p.error.message;
    EXPECT_EQ(*p.expr, number(r)) << text;
    // Denominators 2^a 5^b print as terminating decimals, shortest form, read back exactly.
    std::int64_t d = r.den();
    int digits = 0;
    int twos = 0;
    int fives = 0;
    while (d % 2 == 0) {
      d /= 2;
      ++twos;
    }
    while (d % 5 == 0) {
      d /= 5;
      ++fives;
    }
    digits = std::max(twos, fives);
    if (d == 1 && digits <= 18) {
      EXPECT_EQ(text.find('/'), std::string::npos) << text;
      if (!r.is_integer()) {
        EXPECT_NE(text.back(), '0') << text;
        Rational back;
        ASSERT_TRUE(Rational::parse_decimal(r.is_negative() ? text.substr(1) : text, back)) << text;
        EXPECT_EQ(back, r.abs()) << text;
      }
    }
  }
}

TEST(SymRational, ParseDecimal) {
  struct Case {
    const char* text = "";
    bool ok = false;
    Rational value;
  };
  const Case cases[] = {
      {"0.180", true, Rational(9, 50)},
      {"1e-3", true, Rational(1, 1000)},
      {"12", true, Rational(12)},
      {"1.5E2", true, Rational(150)},
      {"1e+2", true, Rational(100)},
      {".25", true, Rational(1, 4)},
      {"5.", true, Rational(5)},
      {"0.000000000000000001", true, Rational(1, 1000000000000000000)},
      {"9223372036854775807", true, Rational(kMax)},
      {"9223372036854775808", false, Rational(0)},
      {"1e-19", false, Rational(0)},
      {"1e19", false, Rational(0)},
      {"", false, Rational(0)},
      {".", false, Rational(0)},
      {"1e", false, Rational(0)},
      {"e5", false, Rational(0)},
      {"1.2.3", false, Rational(0)},
      {"-1", false, Rational(0)},
      {"1e41", false, Rational(0)},
      {"0x10", false, Rational(0)},
      {"1 ", false, Rational(0)},
  };
  for (const Case& c : cases) {
    Rational out(42);
    EXPECT_EQ(Rational::parse_decimal(c.text, out), c.ok) << "'" << c.text << "'";
    if (c.ok) {
      EXPECT_EQ(out, c.value) << c.text;
    }
  }
  EXPECT_EQ(Rational(6, -4), Rational(-3, 2));
  EXPECT_EQ(Rational(6, -4).den(), 2);
  EXPECT_EQ(Rational(0, -5), Rational(0));
  EXPECT_EQ(Rational(0, -5).den(), 1);
}

}  // namespace
}  // namespace dyncc::sym
