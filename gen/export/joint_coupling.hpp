// Which exported joints are independent and how the others follow them.
//
// A tree of n_j joints driven by n coordinates has n_j - n joints too many. The export picks n
// independent joints (preferring, for each coordinate, a joint driven by that coordinate alone,
// so its rotor, friction and limits can sit on that joint) and writes every other moving joint
// as a linear combination of them: MJCF states it as an equality constraint, URDF as a mimic
// joint when one joint is involved and cannot state it otherwise.
#pragma once

#include <vector>

#include "export/joint_coordinates.hpp"
#include "robot/description.hpp"

namespace dyncc::exporting {

struct CouplingTerm {
  int body = -1;  // an independent joint's body
  double factor = 0.0;
};

/// joint(body) = sum over terms of factor * joint(term.body)
struct Coupling {
  int body = -1;
  std::vector<CouplingTerm> terms;
};

/// The joint that carries coordinate i alone: joint(body) = scale * q_i. body = -1 when every
/// joint driven by q_i mixes in other coordinates.
struct CoordinateJoint {
  int body = -1;
  double scale = 0.0;
};

struct JointCoupling {
  std::vector<int> independent;                    // bodies whose joints parametrise the mechanism
  std::vector<CoordinateJoint> coordinate_joints;  // one per coordinate
  std::vector<Coupling> couplings;                 // one per other moving body, in body order
};

/// Throws ExportError when the joint variables do not determine every coordinate.
JointCoupling couple_joints(const robot::RobotDescription& robot, const std::vector<JointCoordinate>& joints);

}  // namespace dyncc::exporting
