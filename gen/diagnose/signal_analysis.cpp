#include "diagnose/signal_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <unsupported/Eigen/FFT>
#include <vector>

namespace dyncc::diagnose {
namespace {

// Zero-padding to at least this many times the record interpolates the spectrum between its
// natural bins, so a sinusoid between two of them loses at most about 1 % to the window's
// scalloping instead of 15 %.
constexpr Eigen::Index kPadding = 4;

}  // namespace

Spectrum amplitude_spectrum(const Eigen::VectorXd& x, double rate) {
  Spectrum out;
  const Eigen::Index n = x.size();
  if (n < 2 || !(rate > 0)) return out;
  Eigen::Index size = 1;
  while (size < kPadding * n) size *= 2;  // kissfft is fastest on powers of two
  std::vector<double> padded(static_cast<std::size_t>(size), 0.0);
  const double mean = x.mean();
  double window_sum = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    // Hann: the record's ends do not leak a step into every bin.
    const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n - 1));
    padded[static_cast<std::size_t>(i)] = w * (x[i] - mean);
    window_sum += w;
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> bins;
  fft.fwd(bins, padded);
  const Eigen::Index half = size / 2;
  out.frequency.resize(half + 1);
  out.amplitude.resize(half + 1);
  for (Eigen::Index k = 0; k <= half; ++k) {
    // Single-sided: the negative frequencies carry the other half of a sinusoid's amplitude.
    const double sides = k == 0 || k == half ? 1.0 : 2.0;
    out.frequency[k] = static_cast<double>(k) * rate / static_cast<double>(size);
    out.amplitude[k] = sides * std::abs(bins[static_cast<std::size_t>(k)]) / window_sum;
  }
  return out;
}

Correlation cross_correlation(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double rate, double max_lag) {
  Correlation out;
  const Eigen::Index n = std::min(a.size(), b.size());
  if (n < 4 || !(rate > 0) || !(max_lag >= 0)) return out;
  // A quarter of the record at most: at longer lags too little overlaps to say anything.
  const Eigen::Index reach =
      std::min<Eigen::Index>(static_cast<Eigen::Index>(std::floor(max_lag * rate + 1e-9)), n / 4);
  out.lag.resize(2 * reach + 1);
  out.value.resize(2 * reach + 1);
  for (Eigen::Index k = -reach; k <= reach; ++k) {
    const Eigen::Index begin = std::max<Eigen::Index>(0, -k), end = std::min(n, n - k), m = end - begin;
    const auto ai = a.segment(begin, m), bi = b.segment(begin + k, m);
    const double mean_a = ai.mean(), mean_b = bi.mean();
    const double cov = ((ai.array() - mean_a) * (bi.array() - mean_b)).sum();
    const double var_a = (ai.array() - mean_a).square().sum(), var_b = (bi.array() - mean_b).square().sum();
    const double scale = std::sqrt(var_a * var_b);
    out.lag[k + reach] = static_cast<double>(k) / rate;
    out.value[k + reach] = scale > 0 ? cov / scale : 0.0;
  }
  return out;
}

double peak_lag(const Correlation& c) {
  const Eigen::Index size = c.value.size();
  if (size == 0) return 0;
  Eigen::Index m = 0;
  c.value.maxCoeff(&m);
  if (m == 0 || m == size - 1) return c.lag[m];
  const double left = c.value[m - 1], centre = c.value[m], right = c.value[m + 1];
  const double curvature = left - 2 * centre + right;
  if (!(curvature < 0)) return c.lag[m];
  // The vertex of the parabola through the three samples; within half a step of the sample.
  const double offset = std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5);
  return c.lag[m] + offset * (c.lag[m + 1] - c.lag[m]);
}

}  // namespace dyncc::diagnose
