// Plain-text descriptions of an export model's joint map, for the comments both formats carry
// and for warnings: which joint is which coordinate, and how coupled joints follow.
#pragma once

#include <string>

#include "export/export_model.hpp"

namespace dyncc::exporting {

/// "forearm_joint = crank_joint - upper_arm_joint"
std::string coupling_text(const ExportModel& model, const Coupling& coupling);

/// "q1 = yaw_joint, q2 = upper_arm_joint, q3 = crank_joint" (scaled joints as "q4 = wrist_joint / 2",
/// coordinates without a joint of their own as "q5: a combination of joints").
std::string coordinates_text(const ExportModel& model);

}  // namespace dyncc::exporting
