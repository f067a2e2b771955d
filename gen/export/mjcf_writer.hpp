// MuJoCo MJCF: the bodies nested as a tree, hinge/slide joints on each body's z axis, rotor
// inertia as joint armature, friction as damping and frictionloss, couplings between joints as
// equality constraints, loops as <connect>, and a motor per coordinate.
#pragma once

#include <string>
#include <vector>

#include "export/export_model.hpp"
#include "robot/diagnostics.hpp"

namespace dyncc::exporting {

/// The MJCF document. Appends to `warnings` what MuJoCo cannot take as described (mass
/// properties moved to equivalent admissible ones, loops whose points move in their links).
std::string write_mjcf(const ExportModel& model, std::vector<robot::Diagnostic>& warnings);

}  // namespace dyncc::exporting
