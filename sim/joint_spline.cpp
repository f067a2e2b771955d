#include "joint_spline.hpp"

#include <algorithm>
#include <stdexcept>

namespace dyncc::sim {

JointSpline::JointSpline(std::vector<double> t, std::vector<Joints> q) : t_(std::move(t)), q_(std::move(q)) {
  const std::size_t n = t_.size();
  if (n < 2 || q_.size() != n) throw std::invalid_argument("a joint spline needs at least two samples");
  for (std::size_t i = 1; i < n; ++i) {
    if (!(t_[i] > t_[i - 1])) throw std::invalid_argument("a joint spline needs increasing sample times");
  }
  // Natural spline (zero curvature at both ends): the tridiagonal system of the continuity of the
  // slope at the inner samples, solved by the Thomas algorithm (diagonally dominant: no pivoting).
  curvature_.assign(n, Joints{});
  std::vector<double> diagonal(n, 1.0), upper(n, 0.0);
  std::vector<Joints> rhs(n, Joints{});
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
    const double lower = h0 / 6;
    diagonal[i] = (h0 + h1) / 3 - lower * upper[i - 1];
    upper[i] = h1 / 6 / diagonal[i];
    for (int k = 0; k < kDof; ++k) {
      const double slope_jump = (q_[i + 1][k] - q_[i][k]) / h1 - (q_[i][k] - q_[i - 1][k]) / h0;
      rhs[i][k] = (slope_jump - lower * rhs[i - 1][k]) / diagonal[i];
    }
  }
  for (std::size_t i = n - 1; i-- > 1;) {
    for (int k = 0; k < kDof; ++k) curvature_[i][k] = rhs[i][k] - upper[i] * curvature_[i + 1][k];
  }
}

TrajectoryPoint JointSpline::at(double t) const {
  TrajectoryPoint out;
  if (t <= t_.front() || t >= t_.back()) {
    out.q = t <= t_.front() ? q_.front() : q_.back();
    return out;
  }
  const auto i = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  const double h = t_[i + 1] - t_[i], a = (t_[i + 1] - t) / h, b = (t - t_[i]) / h;
  for (int k = 0; k < kDof; ++k) {
    const double m0 = curvature_[i][k], m1 = curvature_[i + 1][k];
    const double y0 = q_[i][k], y1 = q_[i + 1][k];
    out.q[k] = a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6;
    out.qd[k] = (y1 - y0) / h + ((1 - 3 * a * a) * m0 + (3 * b * b - 1) * m1) * h / 6;
    out.qdd[k] = a * m0 + b * m1;
  }
  return out;
}

}  // namespace dyncc::sim
