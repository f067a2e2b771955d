// Everything both export formats need, as numbers: the description reduced to one concrete
// mechanism (nominal parameter values) in the form tree-of-joints formats describe.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "export/body_tree.hpp"
#include "export/coordinate_properties.hpp"
#include "export/joint_coordinates.hpp"
#include "export/joint_coupling.hpp"
#include "export/loop_closures.hpp"
#include "robot/description.hpp"
#include "robot/diagnostics.hpp"

namespace dyncc::exporting {

struct ExportModel {
  std::string name;    // the description's name: the model's name
  std::string source;  // the description's path, as given
  std::string description;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // base frame
  std::vector<Body> bodies;                           // parallel to the description's links
  std::vector<JointCoordinate> joints;                // parallel to bodies
  JointCoupling coupling;
  std::vector<CoordinateProperties> coordinates;
  std::vector<LoopClosure> loops;
  /// Things the export could not represent in either format ("warning" diagnostics).
  std::vector<robot::Diagnostic> warnings;
};

/// Throws ExportError (formatted, with the description's file and position) when the
/// description has no tree-of-joints form.
ExportModel build_export_model(const robot::RobotDescription& robot);

/// The exported name of a body's joint.
std::string joint_name(const Body& body);

}  // namespace dyncc::exporting
