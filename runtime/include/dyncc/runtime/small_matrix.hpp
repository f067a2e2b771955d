// Fixed-size dense helpers for the controller path: row-major n x n matrices in std::array,
// no allocation, no exceptions. Only what the runtime needs (products, a Cholesky test).
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

/// Whether a symmetric matrix is positive definite (a Cholesky factorisation succeeds with
/// pivots above `margin`). Used to reject parameter estimates whose mass matrix is not.
template <typename S, int N>
bool is_positive_definite(const Matrix<S, N>& m, S margin = S(0)) {
  Matrix<S, N> l{};
  for (std::size_t j = 0; j < static_cast<std::size_t>(N); ++j) {
    S diagonal = m[j * N + j];
    for (std::size_t k = 0; k < j; ++k) diagonal -= l[j * N + k] * l[j * N + k];
    if (!(diagonal > margin)) return false;  // also false for NaN
    const S pivot = std::sqrt(diagonal);
    l[j * N + j] = pivot;
    for (std::size_t i = j + 1; i < static_cast<std::size_t>(N); ++i) {
      S sum = m[i * N + j];
      for (std::size_t k = 0; k < j; ++k) sum -= l[i * N + k] * l[j * N + k];
      l[i * N + j] = sum / pivot;
    }
  }
  return true;
}

}  // namespace dyncc::runtime
