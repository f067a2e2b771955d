// Recovering exact rationals from floating-point coefficients found numerically.
#pragma once

#include <optional>

#include "sym/rational.hpp"

namespace dyncc::base {

/// The simplest rational within |x| * rel_tol (+ abs_tol) of x (continued fractions), or nothing
/// when no rational with a denominator up to max_den is that close.
std::optional<sym::Rational> rational_near(double x, double rel_tol = 1e-9, double abs_tol = 1e-12,
                                           std::int64_t max_den = 100000000);

}  // namespace dyncc::base
