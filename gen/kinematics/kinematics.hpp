// Forward kinematics and velocity Jacobians of every link, in the independent coordinates.
//
// Every link's joint variable is an expression in the coordinates (the parallel-link
// constraints), so closed chains are handled as a tree whose joints are driven by those
// expressions; the loops are then checked to close (loops.hpp). Velocities are propagated from
// parent to child in link frames (the Newton-Euler way), one Jacobian column per coordinate:
// compact expressions that share the parent's subexpressions.
#pragma once

#include <vector>

#include "kinematics/vec3.hpp"
#include "robot/description.hpp"

namespace dyncc::kin {

struct LinkKinematics {
  Mat3 rotation;              // link frame -> base frame
  Vec3 origin;                // link frame origin in base coordinates
  std::vector<Vec3> angular;  // per coordinate k: d(omega)/d(qd_k), in link-frame coordinates
  std::vector<Vec3> linear;   // per coordinate k: d(v_origin)/d(qd_k), in link-frame coordinates
};

struct Kinematics {
  std::vector<sym::Expr> coordinates;
  std::vector<LinkKinematics> links;  // parallel to RobotDescription::links
};

/// Rotation and origin of a link frame relative to its parent for one D-H row.
struct RelativeFrame {
  Mat3 rotation;
  Vec3 origin;
  Vec3 joint_axis;                         // axis of the joint's rotation/translation, in parent coordinates
  bool axis_through_child_origin = false;  // modified D-H: rotation about the child's own z axis
};
RelativeFrame dh_frame(robot::Convention convention, sym::Expr a, sym::Expr alpha, sym::Expr d, sym::Expr theta);

/// Throws std::invalid_argument when a or alpha depends on a coordinate (not a D-H joint).
Kinematics compute_kinematics(const robot::RobotDescription& robot);

/// A point given in a link's frame (link -1 = base), in base coordinates.
Vec3 point_in_base(const Kinematics& kin, int link, const Vec3& local);

}  // namespace dyncc::kin
