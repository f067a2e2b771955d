// Internal to the loader: what the section readers build up and validate() checks.
//
// The readers handle one section each and everything local to it (node types, numbers, names,
// expressions against the coordinates and constants read before). validate() then checks what
// spans sections: the link tree, coordinate use, parameters against their nominal values, loops,
// physical consistency.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "robot/description.hpp"
#include "robot/expression_reader.hpp"
#include "robot/yaml_reader.hpp"

namespace dyncc::robot::detail {

/// One place an unknown parameter is used (an inertial, friction or rotor entry).
struct ParameterUse {
  std::string name;
  ParameterRole role = ParameterRole::Mass;
  int link = -1;
  int coordinate = -1;
  std::string field;
  SourceLocation location;
};

/// One entry of the `parameters` map.
struct NominalValue {
  std::string name;
  double value = 0.0;
  std::string field;
  SourceLocation location;
};

struct LoadState {
  RobotDescription robot;
  std::vector<ParameterUse> parameter_uses;                          // in file order
  std::unordered_map<std::string, std::size_t> parameter_use_index;  // name -> index in parameter_uses
  std::unordered_map<std::string, int> coordinate_index;             // name -> index in robot.coordinates
  std::unordered_map<std::string, std::size_t> constant_index;       // name -> index in robot.constants
  std::vector<NominalValue> nominal_values;                          // in file order
  std::vector<std::string> nominal_names;     // keys of `parameters`, read up front for better messages
  std::vector<std::string> unreadable_names;  // constants and parameters whose value was bad (already reported)
  bool links_readable = false;                // `links` was a non-empty list (tree checks make sense)

  /// Names allowed in geometry: coordinates, constants (and pi, handled by the parser).
  [[nodiscard]] SymbolScope geometry_scope() const;
  /// Names allowed in base_parameters: parameter names and constants.
  [[nodiscard]] SymbolScope base_parameter_scope() const;
  [[nodiscard]] bool is_coordinate(const std::string& name) const;
  [[nodiscard]] bool is_constant(const std::string& name) const;
  [[nodiscard]] bool is_parameter(const std::string& name) const { return parameter_use_index.contains(name); }
};

/// Turns a NumberOrName entry into an Expr: a number, or a parameter symbol whose use is
/// recorded (after checking it is not a coordinate, a constant or a name used before).
std::optional<sym::Expr> record_entry(YamlReader& reader, LoadState& state, const Located& value, ParameterRole role,
                                      int link, int coordinate);

/// Reads a coordinate name used as a key (friction, rotor, joint_limits); reports non-coordinates.
std::optional<int> coordinate_key(YamlReader& reader, const LoadState& state, const Located& key,
                                  std::string_view section);

// Section readers, in the order load_robot() calls them.
void read_header(YamlReader& reader, LoadState& state, const std::map<std::string, Located>& top);
void read_coordinates(YamlReader& reader, LoadState& state, const Located& value);
void read_constants(YamlReader& reader, LoadState& state, const Located& value);
void read_links(YamlReader& reader, LoadState& state, const Located& value);
void read_friction(YamlReader& reader, LoadState& state, const Located& value);
void read_rotors(YamlReader& reader, LoadState& state, const Located& value);
void read_joint_limits(YamlReader& reader, LoadState& state, const Located& value);
void read_parameters(YamlReader& reader, LoadState& state, const Located& value);
void read_loops(YamlReader& reader, LoadState& state, const Located& value);
void read_base_parameters(YamlReader& reader, LoadState& state, const Located& value);
void read_initial_estimate(YamlReader& reader, LoadState& state, const Located& value);

/// Cross-section checks; fills Link::parent, LoopPoint::link and RobotDescription::parameters.
void validate(LoadState& state, DiagnosticSink& sink);
/// Nominal values against physics (mass >= 0, inertia PSD and triangle inequality, friction and
/// rotor inertia >= 0); errors or warnings per RobotDescription::physical_consistency.
void check_physical_consistency(const RobotDescription& robot, DiagnosticSink& sink);

}  // namespace dyncc::robot::detail
