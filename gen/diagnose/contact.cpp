#include "diagnose/contact.hpp"

#include <cmath>

#include "diagnose/effects.hpp"

namespace dyncc::diagnose {

ContactGeometry::ContactGeometry(const pipeline::Derivation& derivation) : derivation_(&derivation) {
  const auto gravity = derivation.robot.gravity_values();
  g_ = std::sqrt(gravity[0] * gravity[0] + gravity[1] * gravity[1] + gravity[2] * gravity[2]);
  const int link = payload_link(derivation);
  if (link < 0 || g_ <= 0) return;
  const auto& of = derivation.model.params.of_link[static_cast<std::size_t>(link)];
  for (std::size_t k = 0; k < 4; ++k) {
    if (of[k] < 0) return;
    columns_[k] = of[k];
  }
  link_ = link;
}

ContactGeometry::Basis ContactGeometry::at(const Eigen::VectorXd& q) const {
  const dyn::NumericModel& model = *derivation_->numeric;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(q.size());
  const Eigen::MatrixXd y = model.regressor({q, zero, zero, zero});
  Basis b{Eigen::Vector4d::Zero(), Eigen::MatrixXd::Zero(q.size(), 4)};
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model.parameter_count()));
  for (int k = 0; k < 4; ++k) {
    unit.setZero();
    unit[columns_[k]] = 1.0;
    b.height[k] = model.energy(q, zero, unit) / g_;
    b.lever.col(k) = -y.col(columns_[k]) / g_;
  }
  return b;
}

}  // namespace dyncc::diagnose
