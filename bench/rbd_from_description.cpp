#include "rbd_from_description.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "sym/evaluate.hpp"

namespace dyncc::bench {
namespace {

using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Vector3d;

struct Pose {
  Matrix3d rotation = Matrix3d::Identity();
  Vector3d position = Vector3d::Zero();
  [[nodiscard]] Pose then(const Pose& next) const {
    return {rotation * next.rotation, rotation * next.position + position};
  }
};

Pose rot_x(double angle) { return {AngleAxisd(angle, Vector3d::UnitX()).toRotationMatrix(), Vector3d::Zero()}; }
Pose rot_z(double angle) { return {AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix(), Vector3d::Zero()}; }
Pose trans_x(double length) { return {Matrix3d::Identity(), length * Vector3d::UnitX()}; }
Pose trans_z(double length) { return {Matrix3d::Identity(), length * Vector3d::UnitZ()}; }

class Values {
 public:
  explicit Values(const robot::RobotDescription& robot) : robot_(robot) {
    for (const auto& [name, value] : robot.constant_doubles()) values_[name] = value;
    for (const auto& [name, value] : robot.nominal_values()) values_[name] = value;
    set_coordinates(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.coordinates.size())));
  }
  void set_coordinates(const Eigen::VectorXd& q) {
    for (std::size_t k = 0; k < robot_.coordinates.size(); ++k) {
      values_[robot_.coordinates[k].name()] = q[static_cast<Eigen::Index>(k)];
    }
  }
  double operator()(sym::Expr e) const { return sym::evaluate(e, values_); }

 private:
  const robot::RobotDescription& robot_;
  std::unordered_map<std::string, double> values_;
};

}  // namespace

RigidBodyTree tree_from_description(const robot::RobotDescription& robot) {
  const auto n = static_cast<Eigen::Index>(robot.coordinates.size());
  Values v(robot);
  RigidBodyTree tree;
  const std::array<double, 3> g = robot.gravity_values();
  tree.gravity = Vector3d(g[0], g[1], g[2]);

  // Joint variables as offset + coupling row * q, read off by evaluating at q = 0 and at unit
  // vectors, then checked at one more point (an affine map is fixed by those values).
  std::vector<double> offsets;
  std::vector<Eigen::RowVectorXd> rows;
  for (const robot::Link& link : robot.links) {
    const sym::Expr variable = link.joint_expression();
    v.set_coordinates(Eigen::VectorXd::Zero(n));
    const double offset = v(variable);
    Eigen::RowVectorXd row(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      v.set_coordinates(Eigen::VectorXd::Unit(n, k));
      row[k] = v(variable) - offset;
    }
    const Eigen::VectorXd probe = Eigen::VectorXd::LinSpaced(n, 0.3, 0.9);
    v.set_coordinates(probe);
    if (std::abs(v(variable) - offset - row.dot(probe)) > 1e-12 * (1 + std::abs(offset))) {
      throw std::invalid_argument("link " + link.name + ": joint variable is not affine in the coordinates");
    }
    offsets.push_back(offset);
    rows.push_back(row);
  }
  v.set_coordinates(Eigen::VectorXd::Zero(n));

  std::vector<Pose> link_in_body;  // the D-H link frame inside each body
  std::vector<Eigen::RowVectorXd> joint_rows;
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    const robot::Link& link = robot.links[l];
    const bool revolute = link.joint == robot::JointType::Revolute;
    const double a = v(link.a), alpha = v(link.alpha);
    const double theta0 = revolute ? offsets[l] : v(link.theta);
    const double d0 = revolute ? v(link.d) : offsets[l];
    const Pose parent_link = link.parent < 0 ? Pose{} : link_in_body[static_cast<std::size_t>(link.parent)];
    RigidBody body;
    body.parent = link.parent;
    const bool moves = !rows[l].isZero(0.0);
    body.joint = !moves ? JointKind::Fixed : (revolute ? JointKind::Revolute : JointKind::Prismatic);
    Pose placement, in_body;
    if (robot.convention == robot::Convention::Modified) {
      // Craig: RotX(alpha) TransX(a) RotZ(theta) TransZ(d); the joint is the last factor.
      placement = parent_link.then(rot_x(alpha)).then(trans_x(a)).then(rot_z(theta0)).then(trans_z(d0));
    } else {
      // Standard: RotZ(theta) TransZ(d) TransX(a) RotX(alpha); the joint is the first factor.
      placement = parent_link;
      in_body = rot_z(theta0).then(trans_z(d0)).then(trans_x(a)).then(rot_x(alpha));
    }
    body.rotation = placement.rotation;
    body.position = placement.position;
    body.mass = v(link.mass);
    const Vector3d com(v(link.com[0]), v(link.com[1]), v(link.com[2]));
    body.com = in_body.rotation * com + in_body.position;
    const robot::InertiaTensor& t = link.inertia;
    Matrix3d inertia;
    inertia << v(t.xx), v(t.xy), v(t.xz), v(t.xy), v(t.yy), v(t.yz), v(t.xz), v(t.yz), v(t.zz);
    body.inertia = in_body.rotation * inertia * in_body.rotation.transpose();
    tree.bodies.push_back(body);
    link_in_body.push_back(in_body);
    if (moves) joint_rows.push_back(rows[l]);
  }
  tree.coupling.resize(static_cast<Eigen::Index>(joint_rows.size()), n);
  for (std::size_t j = 0; j < joint_rows.size(); ++j) tree.coupling.row(static_cast<Eigen::Index>(j)) = joint_rows[j];
  tree.armature = Eigen::VectorXd::Zero(n);
  for (const robot::Rotor& r : robot.rotors) tree.armature[r.coordinate] = v(r.reflected_inertia());
  return tree;
}

}  // namespace dyncc::bench
