#include "export/coordinate_properties.hpp"

namespace dyncc::exporting {

std::vector<CoordinateProperties> coordinate_properties(const robot::RobotDescription& robot,
                                                        const SymbolValues& values) {
  std::vector<CoordinateProperties> out(robot.coordinates.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].name = robot.coordinates[i].name();
    if (i < robot.coordinate_locations.size()) out[i].location = robot.coordinate_locations[i];
  }
  for (const robot::Rotor& r : robot.rotors) {
    out[static_cast<std::size_t>(r.coordinate)].rotor_inertia = value_of(r.reflected_inertia(), values);
    out[static_cast<std::size_t>(r.coordinate)].rotor_location = r.location;
  }
  for (const robot::Friction& f : robot.friction) {
    out[static_cast<std::size_t>(f.coordinate)].coulomb = value_of(f.coulomb, values);
    out[static_cast<std::size_t>(f.coordinate)].viscous = value_of(f.viscous, values);
  }
  for (const robot::JointLimit& l : robot.joint_limits) {
    out[static_cast<std::size_t>(l.coordinate)].limits = std::make_pair(l.lower, l.upper);
  }
  return out;
}

}  // namespace dyncc::exporting
