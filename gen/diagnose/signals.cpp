#include "diagnose/signals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dyncc::diagnose {
namespace {

struct Biquad {
  double b0, b1, b2, a1, a2;
};

// Bilinear-transform Butterworth low-pass of order 2 (prewarped cutoff).
Biquad butterworth(double cutoff, double rate) {
  const double k = std::tan(std::numbers::pi * std::min(cutoff, 0.45 * rate) / rate);
  const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * k + k * k);
  return {k * k * norm, 2 * k * k * norm, k * k * norm, 2 * (k * k - 1) * norm,
          (1 - std::numbers::sqrt2 * k + k * k) * norm};
}

// One pass, started in the steady state of the first sample (no start-up transient for a constant).
void run(const Biquad& f, std::vector<double>& x) {
  if (x.empty()) return;
  const double x0 = x.front();
  double x1 = x0, x2 = x0, y1 = x0, y2 = x0;
  for (double& v : x) {
    const double y = f.b0 * v + f.b1 * x1 + f.b2 * x2 - f.a1 * y1 - f.a2 * y2;
    x2 = x1;
    x1 = v;
    y2 = y1;
    y1 = y;
    v = y;
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Noise std from second differences: for a smooth signal plus white noise of std s, the second
// difference is dominated by the noise, with variance 6 s^2.
double second_difference_noise(const Eigen::VectorXd& x) {
  if (x.size() < 3) return 0.0;
  std::vector<double> d;
  d.reserve(static_cast<std::size_t>(x.size()));
  for (Eigen::Index i = 1; i + 1 < x.size(); ++i) d.push_back(std::abs(x[i + 1] - 2 * x[i] + x[i - 1]));
  // The median absolute value is robust to the few large second differences of real motion;
  // for a Gaussian it is 0.6745 sigma.
  return median(d) / 0.6745 / std::sqrt(6.0);
}

// The step of a quantised signal: the smallest nonzero change, accepted when most changes are
// whole multiples of it.
double quantum(const Eigen::VectorXd& x) {
  std::vector<double> steps;
  for (Eigen::Index i = 1; i < x.size(); ++i) {
    const double d = std::abs(x[i] - x[i - 1]);
    if (d > 1e-12 * (1.0 + std::abs(x[i]))) steps.push_back(d);
  }
  if (steps.size() < 10) return 0.0;
  const double smallest = *std::min_element(steps.begin(), steps.end());
  int whole = 0;
  for (const double d : steps) {
    const double ratio = d / smallest;
    if (std::abs(ratio - std::round(ratio)) < 0.02) ++whole;
  }
  return whole >= static_cast<int>(0.9 * static_cast<double>(steps.size())) ? smallest : 0.0;
}

}  // namespace

Eigen::VectorXd zero_phase_lowpass(const Eigen::VectorXd& x, double cutoff, double rate) {
  const Eigen::Index n = x.size();
  if (n < 3) return x;
  const Biquad f = butterworth(cutoff, rate);
  const Eigen::Index pad = std::min<Eigen::Index>(n - 1, static_cast<Eigen::Index>(3.0 * rate / cutoff) + 1);
  std::vector<double> y;
  y.reserve(static_cast<std::size_t>(n + 2 * pad));
  for (Eigen::Index i = pad; i >= 1; --i) y.push_back(2 * x[0] - x[i]);
  for (Eigen::Index i = 0; i < n; ++i) y.push_back(x[i]);
  for (Eigen::Index i = 1; i <= pad; ++i) y.push_back(2 * x[n - 1] - x[n - 1 - i]);
  run(f, y);
  std::reverse(y.begin(), y.end());
  run(f, y);
  std::reverse(y.begin(), y.end());
  Eigen::VectorXd out(n);
  for (Eigen::Index i = 0; i < n; ++i) out[i] = y[static_cast<std::size_t>(i + pad)];
  return out;
}

Eigen::VectorXd derivative(const Eigen::VectorXd& x, double dt) {
  const Eigen::Index n = x.size();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  if (n < 2) return d;
  d[0] = (x[1] - x[0]) / dt;
  d[n - 1] = (x[n - 1] - x[n - 2]) / dt;
  for (Eigen::Index i = 1; i + 1 < n; ++i) d[i] = (x[i + 1] - x[i - 1]) / (2 * dt);
  return d;
}

Eigen::MatrixXd interpolate(const Eigen::VectorXd& t, const Eigen::MatrixXd& values, const Eigen::VectorXd& grid) {
  Eigen::MatrixXd out(grid.size(), values.cols());
  Eigen::Index k = 0;
  for (Eigen::Index i = 0; i < grid.size(); ++i) {
    while (k + 2 < t.size() && t[k + 1] < grid[i]) ++k;
    const double u = std::clamp((grid[i] - t[k]) / (t[k + 1] - t[k]), 0.0, 1.0);
    out.row(i) = (1 - u) * values.row(k) + u * values.row(k + 1);
  }
  return out;
}

Audit audit_log(const JointLog& log) {
  Audit a;
  a.samples = log.samples();
  a.duration = log.t[log.samples() - 1] - log.t[0];
  std::vector<double> dt;
  for (Eigen::Index i = 1; i < log.samples(); ++i) dt.push_back(log.t[i] - log.t[i - 1]);
  const double typical = median(dt);
  a.rate = 1.0 / typical;
  double sum = 0, sum2 = 0, largest = 0;
  for (const double d : dt) {
    sum += d;
    sum2 += d * d;
    largest = std::max(largest, d);
  }
  const double mean = sum / static_cast<double>(dt.size());
  a.jitter = std::sqrt(std::max(0.0, sum2 / static_cast<double>(dt.size()) - mean * mean)) / typical;
  a.largest_gap = largest / typical;
  for (Eigen::Index k = 0; k < log.joints(); ++k) {
    const Eigen::VectorXd q = log.q.col(k), tau = log.tau.col(k);
    JointAudit j;
    j.quantum = quantum(q);
    // A quantised, otherwise clean position has noise quantum / sqrt(12) at most.
    j.position_noise = std::max(second_difference_noise(q), j.quantum / std::sqrt(12.0));
    j.torque_noise = second_difference_noise(tau);
    a.joints.push_back(j);
  }
  return a;
}

Eigen::VectorXd minority_sign_share(const Eigen::MatrixXd& values) {
  Eigen::VectorXd out(values.cols());
  for (Eigen::Index j = 0; j < values.cols(); ++j) {
    const double positive = static_cast<double>((values.col(j).array() > 0).count());
    out[j] = std::min(positive, static_cast<double>(values.rows()) - positive) / static_cast<double>(values.rows());
  }
  return out;
}

}  // namespace dyncc::diagnose
