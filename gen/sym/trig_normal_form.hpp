// Trigonometric normal form: a decision procedure for identically-zero expressions.
//
// An expression polynomial in sin/cos of linear combinations of symbols (and polynomial in
// other symbols) is rewritten as a polynomial in s_j = sin(y_j), c_j = cos(y_j) of independent
// basis angles y_j, then reduced modulo s_j^2 + c_j^2 - 1 (s_j^2 -> 1 - c_j^2). Those relations
// form a Groebner basis, so the reduced polynomial is unique: the expression is identically
// zero exactly when it reduces to 0. Angle sums and multiples are expanded through
// (c + i s)^n. Rational multiples (q/2) get a common basis angle; rational constants in
// arguments share one basis angle too, which is exact by Lindemann-Weierstrass.
// Outside the class (sqrt, atan2, division by a non-number, sin of a non-linear argument,
// non-trivial multiples of pi) the atoms are treated as opaque: a 0 result is still a proof,
// a non-0 result is only reported as non-zero with a numeric witness.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::sym {

enum class ZeroVerdict { Zero, NonZero, Unknown };

struct ZeroTestResult {
  ZeroVerdict verdict = ZeroVerdict::Unknown;
  bool proved = false;  // true when the verdict follows from the normal form (not from sampling)
  std::vector<std::pair<std::string, double>> witness;  // a point where the value is not 0
  double witness_value = 0.0;
  std::string note;  // why the result is not a proof, when it is not
};

struct TrigNormalForm {
  Expr expr;           // the reduced polynomial, as an expression
  bool exact = false;  // expression lies in the decidable class
  std::size_t terms = 0;
};

/// Throws std::overflow_error when coefficients or degrees exceed the exact range.
/// Monomial operations a normal form may take before it gives up with std::overflow_error (the
/// zero test then falls back to sampling). The default is ~1.5 s of work at -O3; the largest
/// identity dyncc proves for a shipped arm, an entry of the Panda's Hdot-2C, takes 2.3e5
/// (measured 2026-11-22), a ~9x margin. The fuzzer passes a smaller budget, so that it looks
/// for bugs rather than big computations.
inline constexpr std::size_t kDefaultWorkBudget = 2'000'000;

TrigNormalForm trig_normal_form(Expr e, std::size_t work_budget = kDefaultWorkBudget);

ZeroTestResult test_zero(Expr e, std::size_t work_budget = kDefaultWorkBudget);
inline bool is_identically_zero(Expr e) { return test_zero(e).verdict == ZeroVerdict::Zero; }

}  // namespace dyncc::sym
