// URDF: a tree of links and joints. URDF cannot close a loop, couple a joint to several others
// (mimic follows exactly one), hold a rotor inertia or name a gravity vector, so the export
// keeps what it can (single-joint couplings as <mimic>, gravity by turning the base under a
// `world` link) and lists every dropped item in a comment and as a warning.
#pragma once

#include <string>
#include <vector>

#include "export/export_model.hpp"
#include "robot/diagnostics.hpp"

namespace dyncc::exporting {

std::string write_urdf(const ExportModel& model, std::vector<robot::Diagnostic>& warnings);

}  // namespace dyncc::exporting
