// What the description attaches to a coordinate rather than to a link: the reflected rotor
// inertia, friction and joint limits. MJCF and URDF attach them to a joint, so they go on the
// joint that carries the coordinate alone (see joint_coupling.hpp), scaled by its ratio.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "export/nominal_values.hpp"
#include "robot/description.hpp"

namespace dyncc::exporting {

struct CoordinateProperties {
  std::string name;
  double rotor_inertia = 0.0;  // gear_ratio^2 * inertia: adds to H_ii
  double coulomb = 0.0;        // friction torque coulomb*sign(qd) + viscous*qd
  double viscous = 0.0;
  std::optional<std::pair<double, double>> limits;  // lower, upper
  robot::SourceLocation location;                   // of the coordinate in `coordinates`
  robot::SourceLocation rotor_location;             // of its `rotor` entry, if any
};

/// One entry per coordinate, nominal values.
std::vector<CoordinateProperties> coordinate_properties(const robot::RobotDescription& robot,
                                                        const SymbolValues& values);

}  // namespace dyncc::exporting
