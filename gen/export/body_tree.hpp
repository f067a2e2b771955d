// The description's links as rigid bodies the way MJCF and URDF see them: each body's frame sits
// on its own joint (the joint turns about, or slides along, the body's z axis through its
// origin), placed at a fixed pose in its parent body's frame.
//
// Why a body frame can differ from the D-H link frame: with modified D-H (Craig) the link frame
// already sits on the link's own joint axis, so the two coincide. With standard D-H the link
// frame sits at the link's far end, on the NEXT joint's axis, while the link turns about its
// parent frame's z axis; the body frame is then the parent's link frame turned by the joint,
// and the D-H link frame is a fixed transform inside the body (link_rotation, link_position).
// Centres of mass, inertias and loop points, given in link frames, are moved into body frames.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "export/joint_coordinates.hpp"
#include "export/nominal_values.hpp"
#include "robot/description.hpp"

namespace dyncc::exporting {

/// Mass properties in the body frame; the inertia tensor is about the centre of mass (tensor
/// entries, as in the description, URDF and MJCF's fullinertia).
struct Inertial {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

struct Body {
  std::string name;                // the link's name
  robot::SourceLocation location;  // of the link's entry in the description
  int parent = -1;                 // index into the bodies (parallel to RobotDescription::links); -1 = base
  robot::JointType joint = robot::JointType::Revolute;
  bool moves = true;  // false: the joint variable is constant and the body is welded to its parent
  // Pose of the body frame in the parent body's frame when the joint reads 0 (q = 0).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  // The description's link frame in the body frame (identity for modified D-H).
  Eigen::Matrix3d link_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d link_position = Eigen::Vector3d::Zero();
  Inertial inertial;

  /// A point given in the description's link frame, in body coordinates.
  [[nodiscard]] Eigen::Vector3d from_link_frame(const Eigen::Vector3d& point) const {
    return link_rotation * point + link_position;
  }
};

/// Bodies parallel to robot.links (parents before children), with nominal inertial values.
std::vector<Body> build_bodies(const robot::RobotDescription& robot, const std::vector<JointCoordinate>& joints,
                               const SymbolValues& values);

}  // namespace dyncc::exporting
