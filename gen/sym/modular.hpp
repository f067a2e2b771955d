// Exact evaluation of expressions over a prime field GF(p), for exact linear algebra on
// sampled values (base parameters) and randomised exact identity tests.
//
// sin and cos of a linear combination of symbols with integer coefficients are evaluated from
// a point (s_j, c_j) on the unit circle of GF(p) per symbol (s_j^2 + c_j^2 = 1 exactly), using
// the angle-sum formulas; symbols that also occur outside sin/cos take independent values.
// An identity that holds as a function of the coordinates then holds exactly at every such
// point, and a non-identity fails at a random point except with probability ~degree/p
// (Schwartz-Zippel), so sampling is an exact test in practice, not a floating-point one.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

__extension__ using UInt128 = unsigned __int128;

class PrimeField {
 public:
  static constexpr std::uint64_t kPrime1 = (1ULL << 61U) - 1U;   // 2^61 - 1
  static constexpr std::uint64_t kPrime2 = (1ULL << 60U) - 93U;  // 2^60 - 93

  explicit PrimeField(std::uint64_t prime) : p_(prime) {}
  [[nodiscard]] std::uint64_t prime() const { return p_; }
  [[nodiscard]] std::uint64_t add(std::uint64_t a, std::uint64_t b) const { return (a + b) % p_; }
  [[nodiscard]] std::uint64_t sub(std::uint64_t a, std::uint64_t b) const { return (a + p_ - b) % p_; }
  [[nodiscard]] std::uint64_t mul(std::uint64_t a, std::uint64_t b) const {
    return static_cast<std::uint64_t>(static_cast<UInt128>(a) * b % p_);
  }
  [[nodiscard]] std::uint64_t pow(std::uint64_t a, std::uint64_t e) const;
  /// Throws std::domain_error for 0.
  [[nodiscard]] std::uint64_t inv(std::uint64_t a) const;
  [[nodiscard]] std::uint64_t neg(std::uint64_t a) const { return a == 0 ? 0 : p_ - a; }
  [[nodiscard]] std::uint64_t from(const Rational& r) const;
  [[nodiscard]] std::uint64_t from_int(std::int64_t v) const;

 private:
  std::uint64_t p_;
};

/// Thrown when an expression is outside what can be evaluated exactly (sqrt, atan2,
/// non-integer multiples of a symbol or constant offsets inside sin/cos).
struct NotModular : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// A random point: a value per symbol and a point on the unit circle per symbol.
struct ModularPoint {
  std::vector<std::uint64_t> value, sin, cos;
};

class ModularFunction {
 public:
  ModularFunction(std::span<const Expr> outputs, std::span<const Expr> inputs);
  /// Throws std::domain_error when a division by zero occurs at this point (pick another).
  [[nodiscard]] std::vector<std::uint64_t> evaluate(const PrimeField& f, const ModularPoint& pt) const;
  [[nodiscard]] std::size_t input_count() const { return inputs_; }
  /// Points on the unit circle a ModularPoint needs: one per input and per constant angle.
  [[nodiscard]] std::size_t circle_count() const { return inputs_ + constant_angles_.size(); }

 private:
  struct Instruction {
    Kind kind{};
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    Rational value;
  };
  struct Operand {
    std::uint32_t slot = 0;  // input or instruction slot; for sin/cos: the symbol's input index
    Rational coefficient;    // Add coefficient | Mul exponent | sin/cos integer multiple
  };
  // Field images of the exact constants, per prime, converted on first use: a conversion
  // costs a modular inverse, far more than the evaluation itself.
  struct BoundConstants {
    std::vector<std::uint64_t> values;        // per instruction
    std::vector<std::uint64_t> coefficients;  // per operand (Add coefficients only)
  };
  const BoundConstants& bind(const PrimeField& field) const;

  std::vector<Instruction> instructions_;
  std::vector<Operand> operands_;
  mutable std::vector<std::pair<std::uint64_t, BoundConstants>> bound_;
  std::vector<std::uint32_t> output_slots_;
  std::unordered_map<Expr, std::uint32_t> constant_angles_;  // -> index into the point's circles
  std::size_t inputs_ = 0;
};

ModularPoint random_point(const PrimeField& field, std::size_t symbols, std::mt19937_64& rng);

/// Rational with |num|, den <= sqrt(m/2) congruent to a mod m (Wang's algorithm), if any.
std::optional<Rational> rational_reconstruct(UInt128 a, UInt128 m);

/// CRT of a1 mod p1 and a2 mod p2 (coprime).
UInt128 crt(std::uint64_t a1, std::uint64_t p1, std::uint64_t a2, std::uint64_t p2);

}  // namespace dyncc::sym
