// Mass properties MuJoCo accepts, with the same dynamics.
//
// MuJoCo 2.2 refuses a body with a joint whose mass or any principal moment of inertia is not
// positive, and any body whose principal moments break the triangle inequality A + B >= C
// (unless told to "balance" them, which changes the dynamics). Published parameter sets do that: the PUMA 560's
// link 1 has mass 0 and a single moment about its joint axis, its link 3 breaks the triangle
// inequality, and a thin rod has a zero moment about its own axis.
//
// Only the dynamics have to be kept, and two changes provably keep them:
//  - A revolute joint changes only the angular velocity component along its axis a, so the
//    tensor delta*(1 - a a^T) sees the same kinetic energy on the body as on its parent (the
//    component of omega perpendicular to a is the same for both). Moving it from the parent to
//    the body changes no term of H, C or g. (Prismatic joint: body and parent turn together,
//    so any tensor moves; an isotropic one is used.) On a body whose parent is the fixed base it
//    is simply added. A body without a joint turns with its parent, so any tensor moves too.
//  - A mass at a point that never moves changes nothing: on a body turning about a fixed axis
//    (a revolute joint on the base), a point of that axis.
// Bodies are treated children first, so a parent pays for its children before it is checked; a
// child takes nothing from a parent that could not then repair itself. Where no exact move
// exists (a thin rod whose parent is a thin rod along another axis), the last resort adds the
// smallest mass and isotropic inertia MuJoCo takes, 1e-9 of the robot's largest, and says so.
// Anything still inadmissible is reported; MuJoCo will then reject the model.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "export/body_tree.hpp"

namespace dyncc::exporting {

struct RepairNote {
  int body = -1;
  bool exact = true;  // false: the last resort, which changes the dynamics slightly
  std::string text;   // what changed, naming the bodies involved
};

struct InertiaRepair {
  std::vector<Body> bodies;  // with admissible moving bodies where possible
  std::vector<RepairNote> notes;
  std::vector<int> unrepaired;  // bodies MuJoCo will still reject
};

/// An inertia tensor the way MuJoCo stores it: principal moments and the orientation of the
/// principal axes in the body frame (MJCF's <inertial quat diaginertia>).
struct PrincipalInertia {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();
};

/// Why not let MuJoCo diagonalise a fullinertia itself: its iterative 3x3 eigensolver stops at a
/// tolerance that moves the mass matrix by ~1e-8 relative; Eigen's is accurate to rounding. A
/// diagonal tensor keeps its exact entries and the identity orientation. The moments are shaved
/// by a few ulps where needed so that A + B >= C holds in floating point whenever it holds
/// mathematically (a thin rod meets it with equality; MuJoCo checks the printed numbers).
PrincipalInertia principal_inertia(const Eigen::Matrix3d& inertia);

/// True when MuJoCo accepts the body's mass properties: the triangle inequality for every body;
/// positive mass and principal moments for a body with a joint.
bool admissible_for_mujoco(const Body& body);

InertiaRepair repair_for_mujoco(std::vector<Body> bodies);

}  // namespace dyncc::exporting
