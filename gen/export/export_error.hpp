// Why a description cannot be exported, and what the export could not represent, in the
// description front end's diagnostic format ("file:line:column: error: field: what").
#pragma once

#include <string>

#include "robot/description.hpp"
#include "robot/diagnostics.hpp"

namespace dyncc::exporting {

/// Thrown by the export stage for a description that loads but has no MJCF/URDF counterpart
/// (a joint variable that is not affine in the coordinates, a loop that does not close).
struct ExportError {
  std::string message;  // formatted, with the file and position
};

ExportError error_at(const std::string& file, robot::SourceLocation at, std::string field, std::string message);

robot::Diagnostic warning_at(const std::string& file, robot::SourceLocation at, std::string field, std::string message);

}  // namespace dyncc::exporting
