// Exact rational numbers for expression coefficients.
//
// Why int64 and not arbitrary precision: coefficients in robot dynamics stay small (D-H constants
// are kept as named symbols until the end), so machine integers are fast and enough. Every
// operation is overflow-checked and throws RationalOverflow rather than returning a wrong value.
//
// The range is symmetric: numerators lie in [-(2^63 - 1), 2^63 - 1], so -2^63 is out of range.
// Negation and abs() are then total, and every value prints as a literal that reads back (the
// parser reads "-9223372036854775808" as the negation of 2^63, which does not fit); with -2^63
// allowed, a product whose coefficient was -2^63 could not be printed at all (the printer takes
// the magnitude), found by fuzz_expression.
#pragma once

#include <compare>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace dyncc::sym {

// 128-bit intermediates make overflow checks exact; __extension__ keeps -Wpedantic quiet.
__extension__ using Int128 = __int128;

struct RationalOverflow : std::overflow_error {
  using std::overflow_error::overflow_error;
};

class Rational {
 public:
  static constexpr std::int64_t kMaxNumerator = INT64_MAX;
  static constexpr std::int64_t kMinNumerator = -INT64_MAX;

  constexpr Rational() = default;
  // Throws RationalOverflow for n = -2^63 (outside the symmetric range).
  constexpr Rational(std::int64_t n) : num_(n) {  // NOLINT(google-explicit-constructor)
    if (n < kMinNumerator) throw RationalOverflow("exact rational coefficient overflows 64 bits");
  }
  Rational(std::int64_t n, std::int64_t d);

  [[nodiscard]] std::int64_t num() const { return num_; }
  [[nodiscard]] std::int64_t den() const { return den_; }
  [[nodiscard]] bool is_zero() const { return num_ == 0; }
  [[nodiscard]] bool is_one() const { return num_ == 1 && den_ == 1; }
  [[nodiscard]] bool is_minus_one() const { return num_ == -1 && den_ == 1; }
  [[nodiscard]] bool is_integer() const { return den_ == 1; }
  [[nodiscard]] bool is_negative() const { return num_ < 0; }
  [[nodiscard]] double to_double() const { return static_cast<double>(num_) / static_cast<double>(den_); }

  /// Parses a decimal literal exactly: "0.180" -> 9/50, "1e-3" -> 1/1000, "12" -> 12.
  /// Returns false when the text is not a decimal literal or does not fit.
  static bool parse_decimal(std::string_view text, Rational& out);

  /// Shortest text that parses back to the same value: a terminating decimal when the
  /// denominator is 2^a*5^b (e.g. "0.18"), otherwise "p/q".
  [[nodiscard]] std::string to_string() const;

  friend Rational operator+(const Rational& a, const Rational& b);
  friend Rational operator-(const Rational& a, const Rational& b);
  friend Rational operator*(const Rational& a, const Rational& b);
  friend Rational operator/(const Rational& a, const Rational& b);
  Rational operator-() const;  // never overflows: the range is symmetric
  Rational& operator+=(const Rational& b) { return *this = *this + b; }
  Rational& operator*=(const Rational& b) { return *this = *this * b; }
  [[nodiscard]] Rational pow(int exponent) const;
  [[nodiscard]] Rational abs() const { return num_ < 0 ? -*this : *this; }

  friend bool operator==(const Rational& a, const Rational& b) = default;
  friend std::strong_ordering operator<=>(const Rational& a, const Rational& b);

  [[nodiscard]] std::size_t hash() const;

 private:
  static Rational from_wide(Int128 n, Int128 d);
  std::int64_t num_ = 0;
  std::int64_t den_ = 1;
};

}  // namespace dyncc::sym
