#include "robot/description.hpp"

#include <stdexcept>

namespace dyncc::robot {

std::string_view to_string(Convention convention) {
  return convention == Convention::Modified ? "modified" : "standard";
}

std::string_view to_string(JointType joint) { return joint == JointType::Revolute ? "revolute" : "prismatic"; }

std::string_view to_string(ParameterRole role) {
  switch (role) {
    case ParameterRole::Mass: return "mass";
    case ParameterRole::CenterOfMass: return "centre of mass";
    case ParameterRole::Inertia: return "inertia";
    case ParameterRole::CoulombFriction: return "coulomb friction";
    case ParameterRole::ViscousFriction: return "viscous friction";
    case ParameterRole::RotorInertia: return "rotor inertia";
  }
  return "?";
}

SourceLocation Link::location_of(std::string_view field) const {
  const auto found = field_locations.find(std::string(field));
  return found != field_locations.end() ? found->second : location;
}

sym::Expr Rotor::reflected_inertia() const { return sym::number(gear_ratio * gear_ratio) * inertia; }

sym::Substitution RobotDescription::constant_values() const {
  sym::Substitution values;
  for (const Constant& constant : constants) values.emplace(constant.symbol, sym::number(constant.value));
  return values;
}

std::map<std::string, double> RobotDescription::constant_doubles() const {
  std::map<std::string, double> values;
  for (const Constant& constant : constants) values.emplace(constant.name, constant.value.to_double());
  return values;
}

std::map<std::string, double> RobotDescription::nominal_values() const {
  std::map<std::string, double> values;
  for (const Parameter& parameter : parameters) values.emplace(parameter.name, parameter.nominal);
  return values;
}

std::array<double, 3> RobotDescription::gravity_values() const {
  return {gravity[0].value().to_double(), gravity[1].value().to_double(), gravity[2].value().to_double()};
}

std::optional<int> RobotDescription::find_link(std::string_view link_name) const {
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].name == link_name) return static_cast<int>(i);
  }
  return std::nullopt;
}

std::optional<int> RobotDescription::find_coordinate(std::string_view coordinate_name) const {
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    if (coordinates[i].name() == coordinate_name) return static_cast<int>(i);
  }
  return std::nullopt;
}

const Constant* RobotDescription::find_constant(std::string_view constant_name) const {
  for (const Constant& constant : constants) {
    if (constant.name == constant_name) return &constant;
  }
  return nullptr;
}

const Parameter* RobotDescription::find_parameter(std::string_view parameter_name) const {
  for (const Parameter& parameter : parameters) {
    if (parameter.name == parameter_name) return &parameter;
  }
  return nullptr;
}

const std::string& RobotDescription::coordinate_name(int index) const {
  if (index < 0 || static_cast<std::size_t>(index) >= coordinates.size()) {
    throw std::out_of_range("coordinate index out of range");
  }
  return coordinates[static_cast<std::size_t>(index)].name();
}

std::vector<int> RobotDescription::children(int link) const {
  std::vector<int> result;
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].parent == link) result.push_back(static_cast<int>(i));
  }
  return result;
}

}  // namespace dyncc::robot
