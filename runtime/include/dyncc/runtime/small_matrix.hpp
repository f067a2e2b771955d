// Fixed-size dense helpers for the controller path: row-major n x n matrices in std::array,
// no allocation, no exceptions. Only what the runtime and its plants need (products, Cholesky).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace dyncc::runtime {

template <typename S, int N>
using Vector = std::array<S, static_cast<std::size_t>(N)>;

template <typename S, int N>
using Matrix = std::array<S, static_cast<std::size_t>(N) * static_cast<std::size_t>(N)>;  // row-major

/// y = M x
template <typename S, int N>
constexpr Vector<S, N> multiply(const Matrix<S, N>& m, const Vector<S, N>& x) {
  Vector<S, N> y{};
  for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
    S sum = S(0);
    for (std::size_t j = 0; j < static_cast<std::size_t>(N); ++j) sum += m[i * N + j] * x[j];
    y[i] = sum;
  }
  return y;
}

template <typename S, int N>
constexpr S dot(const Vector<S, N>& a, const Vector<S, N>& b) {
  S sum = S(0);
  for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) sum += a[i] * b[i];
  return sum;
}

/// Cholesky factor L (lower, row-major; M = L L^T) of a symmetric matrix. False when M is not
/// positive definite with pivots above `margin` (also for NaN); L is then incomplete.
template <typename S, int N>
bool cholesky(const Matrix<S, N>& m, Matrix<S, N>& l, S margin = S(0)) {
  l = Matrix<S, N>{};
  for (std::size_t j = 0; j < static_cast<std::size_t>(N); ++j) {
    S diagonal = m[j * N + j];
    for (std::size_t k = 0; k < j; ++k) diagonal -= l[j * N + k] * l[j * N + k];
    if (!(diagonal > margin)) return false;
    const S pivot = std::sqrt(diagonal);
    l[j * N + j] = pivot;
    for (std::size_t i = j + 1; i < static_cast<std::size_t>(N); ++i) {
      S sum = m[i * N + j];
      // (k runs over the whole row and skips k >= j: a loop bound of j here made GCC 12 at -O1
      // warn, aggressive-loop-optimizations, of an out-of-range iteration that cannot happen.)
      for (std::size_t k = 0; k < static_cast<std::size_t>(N); ++k) sum -= k < j ? l[i * N + k] * l[j * N + k] : S(0);
      l[i * N + j] = sum / pivot;
    }
  }
  return true;
}

/// Whether a symmetric matrix is positive definite (a Cholesky factorisation succeeds with
/// pivots above `margin`). Used to reject parameter estimates whose mass matrix is not.
template <typename S, int N>
bool is_positive_definite(const Matrix<S, N>& m, S margin = S(0)) {
  Matrix<S, N> l{};
  return cholesky<S, N>(m, l, margin);
}

/// x = M^-1 b for a symmetric positive definite M (forward dynamics: H qdd = tau - bias).
/// False, x untouched, when M is not positive definite.
template <typename S, int N>
bool solve_positive_definite(const Matrix<S, N>& m, const Vector<S, N>& b, Vector<S, N>& x) {
  Matrix<S, N> l{};
  if (!cholesky<S, N>(m, l)) return false;
  Vector<S, N> y = b;
  for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) {
    for (std::size_t k = 0; k < i; ++k) y[i] -= l[i * N + k] * y[k];
    y[i] /= l[i * N + i];
  }
  for (auto i = static_cast<std::size_t>(N); i-- > 0;) {
    for (std::size_t k = i + 1; k < static_cast<std::size_t>(N); ++k) y[i] -= l[k * N + i] * y[k];
    y[i] /= l[i * N + i];
  }
  x = y;
  return true;
}

}  // namespace dyncc::runtime
