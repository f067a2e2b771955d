#include "sym/rational.hpp"

#include "sym/wide_gcd.hpp"

namespace dyncc::sym {
namespace {

// The symmetric range (see rational.hpp): -2^63 does not fit.
bool fits64(Int128 v) { return v >= Rational::kMinNumerator && v <= Rational::kMaxNumerator; }

}  // namespace

Int128 wide_gcd(Int128 a, Int128 b) {
  if (a < 0) a = -a;
  if (b < 0) b = -b;
  while (b != 0) {
    const Int128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}

Rational::Rational(std::int64_t n, std::int64_t d) { *this = from_wide(n, d); }

Rational Rational::from_wide(Int128 n, Int128 d) {
  if (d == 0) throw std::domain_error("division by zero");
  if (d < 0) {
    n = -n;
    d = -d;
  }
  const Int128 g = wide_gcd(n, d);
  if (g > 1) {
    n /= g;
    d /= g;
  }
  if (!fits64(n) || !fits64(d)) throw RationalOverflow("exact rational coefficient overflows 64 bits");
  Rational r;
  r.num_ = static_cast<std::int64_t>(n);
  r.den_ = static_cast<std::int64_t>(d);
  return r;
}

// The integer fast paths may produce -2^63 without a built-in overflow; Rational(s) rejects it.
Rational operator+(const Rational& a, const Rational& b) {
  if (a.den_ == 1 && b.den_ == 1) {
    std::int64_t s = 0;
    if (!__builtin_add_overflow(a.num_, b.num_, &s)) return Rational(s);
  }
  return Rational::from_wide(static_cast<Int128>(a.num_) * b.den_ + static_cast<Int128>(b.num_) * a.den_,
                             static_cast<Int128>(a.den_) * b.den_);
}

Rational operator-(const Rational& a, const Rational& b) {
  if (a.den_ == 1 && b.den_ == 1) {
    std::int64_t s = 0;
    if (!__builtin_sub_overflow(a.num_, b.num_, &s)) return Rational(s);
  }
  return Rational::from_wide(static_cast<Int128>(a.num_) * b.den_ - static_cast<Int128>(b.num_) * a.den_,
                             static_cast<Int128>(a.den_) * b.den_);
}

Rational operator*(const Rational& a, const Rational& b) {
  if (a.den_ == 1 && b.den_ == 1) {
    std::int64_t p = 0;
    if (!__builtin_mul_overflow(a.num_, b.num_, &p)) return Rational(p);
  }
  return Rational::from_wide(static_cast<Int128>(a.num_) * b.num_, static_cast<Int128>(a.den_) * b.den_);
}

Rational operator/(const Rational& a, const Rational& b) {
  return Rational::from_wide(static_cast<Int128>(a.num_) * b.den_, static_cast<Int128>(a.den_) * b.num_);
}

Rational Rational::operator-() const {
  Rational r = *this;
  r.num_ = -num_;
  return r;
}

Rational Rational::pow(int exponent) const {
  // The magnitude is taken as unsigned: -exponent would overflow for INT_MIN.
  unsigned e = exponent < 0 ? 0U - static_cast<unsigned>(exponent) : static_cast<unsigned>(exponent);
  Rational result(1);
  Rational base = *this;
  while (e != 0) {
    if ((e & 1U) != 0) result = result * base;
    e >>= 1U;
    if (e != 0) base = base * base;
  }
  return exponent < 0 ? Rational(1) / result : result;
}

std::strong_ordering operator<=>(const Rational& a, const Rational& b) {
  const Int128 l = static_cast<Int128>(a.num_) * b.den_;
  const Int128 r = static_cast<Int128>(b.num_) * a.den_;
  if (l < r) return std::strong_ordering::less;
  if (l > r) return std::strong_ordering::greater;
  return std::strong_ordering::equal;
}

std::size_t Rational::hash() const {
  const auto h1 = static_cast<std::uint64_t>(num_) * 0x9E3779B97F4A7C15ULL;
  const auto h2 = static_cast<std::uint64_t>(den_) * 0xC2B2AE3D27D4EB4FULL;
  return static_cast<std::size_t>(h1 ^ (h2 + 0x165667B19E3779F9ULL + (h1 << 6U) + (h1 >> 2U)));
}

bool Rational::parse_decimal(std::string_view text, Rational& out) {
  // digits [ '.' digits ] [ (e|E) [+-] digits ]
  std::size_t i = 0;
  Int128 mantissa = 0;
  int scale = 0;  // value = mantissa * 10^scale
  bool any_digit = false;
  const Int128 limit = static_cast<Int128>(1) << 100;
  while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
    mantissa = mantissa * 10 + (text[i] - '0');
    if (mantissa > limit) return false;
    any_digit = true;
    ++i;
  }
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
      mantissa = mantissa * 10 + (text[i] - '0');
      if (mantissa > limit) return false;
      --scale;
      any_digit = true;
      ++i;
    }
  }
  if (!any_digit) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    int sign = 1;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
      sign = text[i] == '-' ? -1 : 1;
      ++i;
    }
    int exponent = 0;
    bool exp_digit = false;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') {
      exponent = exponent * 10 + (text[i] - '0');
      if (exponent > 40) return false;
      exp_digit = true;
      ++i;
    }
    if (!exp_digit) return false;
    scale += sign * exponent;
  }
  if (i != text.size()) return false;
  if (scale < -38 || scale > 38) return false;
  Int128 den = 1;
  for (int k = 0; k < -scale; ++k) den *= 10;
  for (int k = 0; k < scale; ++k) {
    mantissa *= 10;
    if (mantissa > limit) return false;
  }
  try {
    out = from_wide(mantissa, den);
  } catch (const RationalOverflow&) {
    return false;
  }
  return true;
}

std::string Rational::to_string() const {
  if (den_ == 1) return std::to_string(num_);
  // Terminating decimal if den = 2^a 5^b.
  std::int64_t d = den_;
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
  const int digits = twos > fives ? twos : fives;
  if (d == 1 && digits <= 18) {
    // value = num/den = num * (10^digits/den) / 10^digits
    Int128 factor = 1;
    for (int k = 0; k < digits; ++k) factor *= 10;
    Int128 n = static_cast<Int128>(num_) * (factor / den_);
    const bool negative = n < 0;
    if (negative) n = -n;
    std::string s;
    for (int k = 0; k < digits || n > 0; ++k) {
      s.insert(s.begin(), static_cast<char>('0' + static_cast<int>(n % 10)));
      n /= 10;
      if (k + 1 == digits) s.insert(s.begin(), '.');
    }
    if (s.front() == '.') s.insert(s.begin(), '0');
    return negative ? "-" + s : s;
  }
  return std::to_string(num_) + "/" + std::to_string(den_);
}

}  // namespace dyncc::sym
