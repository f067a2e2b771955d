#include "export/export_model.hpp"

#include <fmt/core.h>

#include <stdexcept>

#include "export/export_error.hpp"
#include "export/nominal_values.hpp"

namespace dyncc::exporting {
namespace {

/// A coordinate whose rotor, friction or limits have no joint of their own to sit on.
void warn_unattached_properties(const robot::RobotDescription& robot, ExportModel& model) {
  for (std::size_t i = 0; i < model.coordinates.size(); ++i) {
    const CoordinateProperties& c = model.coordinates[i];
    const bool has_any = c.rotor_inertia != 0.0 || c.coulomb != 0.0 || c.viscous != 0.0 || c.limits.has_value();
    if (!has_any || model.coupling.coordinate_joints[i].body >= 0) continue;
    model.warnings.push_back(warning_at(robot.source_path.string(), c.location, "coordinates." + c.name,
                                        "no joint follows this coordinate alone, so its rotor inertia, friction "
                                        "and limits are not exported"));
  }
}

}  // namespace

std::string joint_name(const Body& body) { return body.name + "_joint"; }

ExportModel build_export_model(const robot::RobotDescription& robot) {
  const SymbolValues values = nominal_symbol_values(robot);
  ExportModel model;
  model.name = robot.name;
  model.source = robot.source_path.string();
  model.description = robot.description;
  const std::array<double, 3> g = robot.gravity_values();
  model.gravity = Eigen::Vector3d(g[0], g[1], g[2]);
  model.joints = joint_coordinates(robot, values);
  model.bodies = build_bodies(robot, model.joints, values);
  model.coupling = couple_joints(robot, model.joints);
  model.coordinates = coordinate_properties(robot, values);
  try {
    model.loops = loop_closures(robot, model.bodies, values);
  } catch (const std::invalid_argument& e) {  // the kinematics refuse a D-H row
    throw ExportError{fmt::format("{}: error: {}", robot.source_path.string(), e.what())};
  }
  warn_unattached_properties(robot, model);
  return model;
}

}  // namespace dyncc::exporting
