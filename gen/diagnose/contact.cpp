#include "diagnose/contact.hpp"

#include <cmath>

#include "diagnose/effects.hpp"
#include "sym/substitute.hpp"

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
  down_ = Eigen::Vector3d(gravity[0], gravity[1], gravity[2]) / g_;
  // The link's rotation and its Jacobians (link-frame components, rotated to the base below).
  const kin::LinkKinematics& lk = derivation.kinematics.links[static_cast<std::size_t>(link)];
  const sym::Substitution constants = derivation.robot.constant_values();
  std::vector<sym::Expr> outputs;
  for (const auto& row : lk.rotation) {
    for (const sym::Expr& e : row) outputs.push_back(sym::substitute(e, constants));
  }
  for (const sym::Expr& e : lk.origin) outputs.push_back(sym::substitute(e, constants));
  for (const auto* columns : {&lk.linear, &lk.angular}) {
    for (const kin::Vec3& v : *columns) {
      for (const sym::Expr& e : v) outputs.push_back(sym::substitute(e, constants));
    }
  }
  kinematics_ = std::make_shared<const sym::CompiledFunction>(outputs, derivation.kinematics.coordinates);
}

Eigen::MatrixXd ContactGeometry::Frame::point_jacobian(const Eigen::Vector3d& c) const {
  Eigen::MatrixXd j(3, linear.cols());
  for (Eigen::Index k = 0; k < linear.cols(); ++k) {
    const Eigen::Vector3d w = angular.col(k);
    j.col(k) = linear.col(k) + w.cross(c);
  }
  return rotation * j;
}

ContactGeometry::Frame ContactGeometry::frame(const Eigen::VectorXd& q) const { return frames(q.transpose()).front(); }

std::vector<ContactGeometry::Frame> ContactGeometry::frames(const Eigen::MatrixXd& q) const {
  const Eigen::Index n = q.cols(), rows = q.rows();
  const Eigen::MatrixXd values = dyn::evaluate_rows(*kinematics_, q);
  // The outputs in their order: rotation (row-major), origin, then per coordinate linear and angular.
  std::vector<Frame> out;
  out.reserve(static_cast<std::size_t>(rows));
  for (Eigen::Index r = 0; r < rows; ++r) {
    const Eigen::VectorXd v = values.row(r).transpose();
    Frame f;
    f.rotation = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v.data());
    f.origin = v.segment<3>(9);
    f.linear = Eigen::Map<const Eigen::MatrixXd>(v.data() + 12, 3, n);
    f.angular = Eigen::Map<const Eigen::MatrixXd>(v.data() + 12 + 3 * n, 3, n);
    out.push_back(std::move(f));
  }
  return out;
}

ContactGeometry::Basis ContactGeometry::at(const Eigen::VectorXd& q) const { return at_rows(q.transpose()).front(); }

std::vector<ContactGeometry::Basis> ContactGeometry::at_rows(const Eigen::MatrixXd& q) const {
  const dyn::NumericModel& model = *derivation_->numeric;
  const Eigen::Index n = q.cols();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  std::vector<dyn::State> states;
  states.reserve(static_cast<std::size_t>(q.rows()));
  for (Eigen::Index r = 0; r < q.rows(); ++r) states.push_back({q.row(r).transpose(), zero, zero, zero});
  const std::vector<Eigen::MatrixXd> ys = model.regressor(states);
  std::vector<Basis> out(states.size(), Basis{Eigen::Vector4d::Zero(), Eigen::MatrixXd::Zero(n, 4)});
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model.parameter_count()));
  for (int k = 0; k < 4; ++k) {
    unit.setZero();
    unit[columns_[k]] = 1.0;
    const std::vector<double> energies = model.energy(states, unit);
    for (std::size_t r = 0; r < states.size(); ++r) {
      out[r].height[k] = energies[r] / g_;
      out[r].lever.col(k) = -ys[r].col(columns_[k]) / g_;
    }
  }
  return out;
}

}  // namespace dyncc::diagnose
