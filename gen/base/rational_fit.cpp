#include "base/rational_fit.hpp"

#include <cmath>

namespace dyncc::base {

std::optional<sym::Rational> rational_near(double x, double rel_tol, double abs_tol, std::int64_t max_den) {
  if (!std::isfinite(x) || std::abs(x) > 1e15) return std::nullopt;
  const double tol = std::abs(x) * rel_tol + abs_tol;
  // Convergents h/k of the continued fraction of x.
  double h_prev = 1.0;
  double h = std::floor(x);
  double k_prev = 0.0;
  double k = 1.0;
  double frac = x - std::floor(x);
  for (int i = 0; i < 64; ++i) {
    if (std::abs(x - h / k) <= tol) return sym::Rational(static_cast<std::int64_t>(h), static_cast<std::int64_t>(k));
    if (frac < 1e-300) break;
    const double inv = 1.0 / frac;
    const double a = std::floor(inv);
    frac = inv - a;
    const double h_next = a * h + h_prev;
    const double k_next = a * k + k_prev;
    if (k_next > static_cast<double>(max_den)) break;
    h_prev = h;
    h = h_next;
    k_prev = k;
    k = k_next;
  }
  return std::nullopt;
}

}  // namespace dyncc::base
