#include "export/body_tree.hpp"

#include "kinematics/kinematics.hpp"

namespace dyncc::exporting {
namespace {

struct Pose {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d position;
};

/// A D-H row with its joint variable at the q = 0 value, as numbers. The symbolic frame
/// (kin::dh_frame) evaluates cos(-pi/2) to an exact 0, so axes come out exactly.
Pose dh_pose_at_zero(const robot::RobotDescription& robot, const robot::Link& link, const JointCoordinate& joint,
                     const SymbolValues& values) {
  const bool revolute = link.joint == robot::JointType::Revolute;
  const sym::Expr theta = revolute ? joint.offset_expression : link.theta;
  const sym::Expr d = revolute ? link.d : joint.offset_expression;
  const kin::RelativeFrame frame = kin::dh_frame(robot.convention, link.a, link.alpha, d, theta);
  Pose pose;
  for (int r = 0; r < 3; ++r) {
    pose.position[r] = value_of(frame.origin[static_cast<std::size_t>(r)], values);
    for (int c = 0; c < 3; ++c) {
      pose.rotation(r, c) = value_of(frame.rotation[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)], values);
    }
  }
  return pose;
}

Inertial nominal_inertial(const robot::Link& link, const SymbolValues& values) {
  Inertial in;
  in.mass = value_of(link.mass, values);
  for (int i = 0; i < 3; ++i) in.com[i] = value_of(link.com[static_cast<std::size_t>(i)], values);
  const robot::InertiaTensor& t = link.inertia;
  const double xx = value_of(t.xx, values), yy = value_of(t.yy, values), zz = value_of(t.zz, values);
  const double xy = value_of(t.xy, values), xz = value_of(t.xz, values), yz = value_of(t.yz, values);
  in.inertia << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  return in;
}

}  // namespace

std::vector<Body> build_bodies(const robot::RobotDescription& robot, const std::vector<JointCoordinate>& joints,
                               const SymbolValues& values) {
  std::vector<Body> bodies;
  bodies.reserve(robot.links.size());
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    const robot::Link& link = robot.links[l];
    const Pose dh = dh_pose_at_zero(robot, link, joints[l], values);
    Body body;
    body.name = link.name;
    body.location = link.location;
    body.parent = link.parent;
    body.joint = link.joint;
    body.moves = joints[l].moves();
    // The parent's D-H link frame in the parent's body frame (the base frame is both).
    Pose parent_link{Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
    if (link.parent >= 0) {
      const Body& parent = bodies[static_cast<std::size_t>(link.parent)];
      parent_link = {parent.link_rotation, parent.link_position};
    }
    if (robot.convention == robot::Convention::Modified) {
      // RotX(alpha) TransX(a) RotZ(theta0 + qj) TransZ(d0 + dj): the joint acts last, about/along
      // the link frame's own z axis, so the body frame IS the link frame.
      body.rotation = parent_link.rotation * dh.rotation;
      body.position = parent_link.rotation * dh.position + parent_link.position;
    } else {
      // RotZ(theta0 + qj) TransZ(d0 + dj) TransX(a) RotX(alpha): the joint acts first, about/along
      // the parent link frame's z axis; the rest of the row is fixed inside the body.
      body.rotation = parent_link.rotation;
      body.position = parent_link.position;
      body.link_rotation = dh.rotation;
      body.link_position = dh.position;
    }
    const Inertial in_link = nominal_inertial(link, values);
    body.inertial.mass = in_link.mass;
    body.inertial.com = body.from_link_frame(in_link.com);
    body.inertial.inertia = body.link_rotation * in_link.inertia * body.link_rotation.transpose();
    bodies.push_back(std::move(body));
  }
  return bodies;
}

}  // namespace dyncc::exporting
