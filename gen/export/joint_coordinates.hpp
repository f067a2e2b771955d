// How each link's joint variable depends on the independent coordinates.
//
// MJCF and URDF joints are plain tree joints, one variable each, measured from a reference
// configuration. A description drives every joint by an expression in the coordinates (the way
// it states parallel-link constraints, e.g. theta: q3 - q2), so the export needs that expression
// as  joint variable = offset + sum_k coefficient_k * q_k.  The offset goes into the body's fixed
// placement (the exported joint reads 0 at q = 0) and the coefficients become couplings between
// the exported joints. An expression that is not affine in the coordinates (sin(q1), q1*q2) has
// no MJCF/URDF counterpart and is rejected.
#pragma once

#include <vector>

#include "export/nominal_values.hpp"
#include "robot/description.hpp"
#include "sym/expr.hpp"

namespace dyncc::exporting {

struct JointCoordinate {
  sym::Expr offset_expression;       // the joint expression at q = 0, in constants (exact)
  double offset = 0.0;               // its value
  std::vector<double> coefficients;  // d(joint variable)/d(q_k), one per coordinate
  /// False for a joint variable without coordinates: the link is rigidly attached to its parent.
  [[nodiscard]] bool moves() const;
};

/// One entry per link, parallel to robot.links. Throws ExportError for a joint expression whose
/// derivative still depends on a coordinate.
std::vector<JointCoordinate> joint_coordinates(const robot::RobotDescription& robot, const SymbolValues& values);

}  // namespace dyncc::exporting
