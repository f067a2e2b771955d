#include "diagnose/signals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "diagnose/column_filter.hpp"

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

// The rows of a signal padded by odd reflection at both ends, the padding held apart: the
// signal's own rows are filtered where they are (a log's contact candidates are a few hundred
// columns of 10^4-10^5 rows: a padded copy of them cost more than the filter).
class PaddedRows {
 public:
  PaddedRows(RowMatrix& x, Eigen::Index pad) : x_(x), pad_(pad), head_(pad, x.cols()), tail_(pad, x.cols()) {
    const Eigen::Index n = x.rows();
    for (Eigen::Index i = pad; i >= 1; --i) head_.row(pad - i) = 2 * x.row(0) - x.row(i);
    for (Eigen::Index i = 1; i <= pad; ++i) tail_.row(i - 1) = 2 * x.row(n - 1) - x.row(n - 1 - i);
  }
  [[nodiscard]] Eigen::Index rows() const { return x_.rows() + 2 * pad_; }
  [[nodiscard]] Eigen::Index cols() const { return x_.cols(); }
  [[nodiscard]] double* row(Eigen::Index t) {
    if (t < pad_) return head_.row(t).data();
    if (t < pad_ + x_.rows()) return x_.row(t - pad_).data();
    return tail_.row(t - pad_ - x_.rows()).data();
  }

 private:
  RowMatrix& x_;
  Eigen::Index pad_;
  RowMatrix head_, tail_;
};

// One pass over the rows (forward, or backward from the last row), each column a signal, started
// in the steady state of its first sample (no start-up transient for a constant). The columns'
// recurrences run side by side: one alone waits on its previous output at every sample.
void run(const Biquad& f, PaddedRows& x, bool backward) {
  const Eigen::Index rows = x.rows();
  const Eigen::Index first = backward ? rows - 1 : 0, step = backward ? -1 : 1;
  const auto m = static_cast<std::size_t>(x.cols());
  std::vector<double> x1(x.row(first), x.row(first) + m);
  std::vector<double> x2 = x1, y1 = x1, y2 = x1;
  for (Eigen::Index k = 0; k < rows; ++k) {
    double* v = x.row(first + step * k);
    for (std::size_t c = 0; c < m; ++c) {
      const double y = f.b0 * v[c] + f.b1 * x1[c] + f.b2 * x2[c] - f.a1 * y1[c] - f.a2 * y2[c];
      x2[c] = x1[c];
      x1[c] = v[c];
      y2[c] = y1[c];
      y1[c] = y;
      v[c] = y;
    }
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

void zero_phase_lowpass_rows(RowMatrix& x, double cutoff, double rate) {
  const Eigen::Index n = x.rows();
  if (n < 3 || x.cols() == 0) return;
  const Biquad f = butterworth(cutoff, rate);
  const Eigen::Index pad = std::min<Eigen::Index>(n - 1, static_cast<Eigen::Index>(3.0 * rate / cutoff) + 1);
  PaddedRows padded(x, pad);
  run(f, padded, false);
  run(f, padded, true);
}

Eigen::VectorXd zero_phase_lowpass(const Eigen::VectorXd& x, double cutoff, double rate) {
  RowMatrix y = x;
  zero_phase_lowpass_rows(y, cutoff, rate);
  return y.col(0);
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
