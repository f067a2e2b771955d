// The description's loops as MJCF can state them: two points, each fixed in a body, that must
// coincide. Before writing a closure the export proves it (gen/kinematics' loop check), because
// MuJoCo would otherwise pull a mechanism that does not exist into shape.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "export/body_tree.hpp"
#include "export/nominal_values.hpp"
#include "robot/description.hpp"

namespace dyncc::exporting {

struct LoopClosure {
  std::string name;
  int body1 = -1, body2 = -1;                         // -1 = base
  Eigen::Vector3d anchor1 = Eigen::Vector3d::Zero();  // in body1's frame
  Eigen::Vector3d anchor2 = Eigen::Vector3d::Zero();  // in body2's frame
  bool fixed_points = true;  // false: a point moves in its link (depends on a coordinate); no MJCF form
  robot::SourceLocation location;
};

/// Throws ExportError when a loop does not close.
std::vector<LoopClosure> loop_closures(const robot::RobotDescription& robot, const std::vector<Body>& bodies,
                                       const SymbolValues& values);

}  // namespace dyncc::exporting
