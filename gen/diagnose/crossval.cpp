#include "diagnose/crossval.hpp"

#include <cmath>

namespace dyncc::diagnose {
namespace {

constexpr double kRidge = 1e-9;  // relative to the scaled normal matrix's unit diagonal

// Columns scaled by their norms over all rows (`scale`), not over the training rows: a column that
// is nearly zero where a fold trains (a load carried only in the held-out stretch) is then held
// near zero by the ridge instead of being blown up to unit size and predicting nonsense.
Eigen::VectorXd column_scale(const Eigen::MatrixXd& a) {
  Eigen::VectorXd scale(a.cols());
  for (Eigen::Index c = 0; c < a.cols(); ++c) {
    const double norm = a.col(c).norm();
    scale[c] = norm > 0 ? 1.0 / norm : 0.0;
  }
  return scale;
}

Eigen::VectorXd solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& scale) {
  const Eigen::MatrixXd as = a * scale.asDiagonal();
  Eigen::MatrixXd normal = as.transpose() * as;
  normal.diagonal().array() += kRidge;
  const Eigen::VectorXd x = normal.ldlt().solve(as.transpose() * b);
  return scale.asDiagonal() * x;
}

}  // namespace

Eigen::VectorXd joint_rms(const Eigen::VectorXd& stacked, Eigen::Index joints, Eigen::Index begin, Eigen::Index end) {
  const Eigen::Index samples = stacked.size() / joints;
  if (end < 0) end = samples;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(joints);
  for (Eigen::Index s = begin; s < end; ++s) {
    for (Eigen::Index j = 0; j < joints; ++j) sum[j] += stacked[s * joints + j] * stacked[s * joints + j];
  }
  return (sum / static_cast<double>(std::max<Eigen::Index>(1, end - begin))).cwiseSqrt();
}

CrossValidation cross_validate(const Eigen::VectorXd& r, const Eigen::MatrixXd& E, Eigen::Index joints,
                               const Eigen::VectorXd& weight, const Eigen::MatrixXd* fitted_on) {
  const Eigen::Index samples = r.size() / joints, k = E.cols();
  CrossValidation cv;
  cv.heldout = r;
  cv.theta_folds.resize(k, kFolds);
  Eigen::VectorXd w(r.size());
  for (Eigen::Index s = 0; s < samples; ++s) w.segment(s * joints, joints) = weight;
  const Eigen::MatrixXd we = w.asDiagonal() * (fitted_on != nullptr ? *fitted_on : E);
  const Eigen::VectorXd wr = w.asDiagonal() * r;
  const Eigen::VectorXd scale = column_scale(we);
  for (int f = 0; f < kFolds; ++f) {
    const Eigen::Index begin = fold_begin(samples, f), end = fold_begin(samples, f + 1);
    cv.fold_end.push_back(end);
    const Eigen::Index train = samples - (end - begin);
    Eigen::MatrixXd a(train * joints, k);
    Eigen::VectorXd b(train * joints);
    a.topRows(begin * joints) = we.topRows(begin * joints);
    b.head(begin * joints) = wr.head(begin * joints);
    a.bottomRows((samples - end) * joints) = we.bottomRows((samples - end) * joints);
    b.tail((samples - end) * joints) = wr.tail((samples - end) * joints);
    const Eigen::VectorXd theta = solve(a, b, scale);
    cv.theta_folds.col(f) = theta;
    cv.heldout.segment(begin * joints, (end - begin) * joints) -=
        E.middleRows(begin * joints, (end - begin) * joints) * theta;
  }
  cv.theta = solve(we, wr, scale);
  const Eigen::VectorXd mean = cv.theta_folds.rowwise().mean();
  cv.theta_error =
      ((cv.theta_folds.colwise() - mean).array().square().rowwise().sum() * (static_cast<double>(kFolds - 1) / kFolds))
          .sqrt();
  return cv;
}

}  // namespace dyncc::diagnose
