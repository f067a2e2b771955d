#include "robot/load_state.hpp"

#include <fmt/core.h>

#include <algorithm>

#include "robot/spelling.hpp"

namespace dyncc::robot::detail {

bool LoadState::is_coordinate(const std::string& name) const { return coordinate_index.contains(name); }

bool LoadState::is_constant(const std::string& name) const { return constant_index.contains(name); }

SymbolScope LoadState::geometry_scope() const {
  SymbolScope scope;
  scope.description = "coordinates, constants, pi and numbers";
  for (const sym::Expr& coordinate : robot.coordinates) scope.names.insert(coordinate.name());
  for (const Constant& constant : robot.constants) scope.names.insert(constant.name);
  // A constant whose value was bad is still declared: its uses are not "unknown symbols" too.
  for (const std::string& name : unreadable_names) scope.names.insert(name);
  for (const ParameterUse& use : parameter_uses) scope.forbidden.emplace(use.name, "an unknown parameter");
  for (const std::string& name : nominal_names) scope.forbidden.emplace(name, "an unknown parameter");
  return scope;
}

SymbolScope LoadState::base_parameter_scope() const {
  SymbolScope scope;
  scope.description = "parameter names, constants, pi and numbers";
  for (const ParameterUse& use : parameter_uses) scope.names.insert(use.name);
  for (const Constant& constant : robot.constants) scope.names.insert(constant.name);
  for (const sym::Expr& coordinate : robot.coordinates) {
    scope.forbidden.emplace(coordinate.name(), "a coordinate (base parameters do not depend on the motion)");
  }
  for (const std::string& name : nominal_names) {
    if (!scope.names.contains(name)) {
      scope.forbidden.emplace(name, "given a nominal value but used in no link, friction or rotor entry");
    }
  }
  return scope;
}

std::optional<sym::Expr> record_entry(YamlReader& reader, LoadState& state, const Located& value, ParameterRole role,
                                      int link, int coordinate) {
  const auto entry = read_number_or_name(reader, value);
  if (!entry) return std::nullopt;
  if (entry->number) return sym::number(*entry->number);
  const std::string& name = entry->name;
  const std::string expected = "expected a number or the name of an unknown parameter";
  if (state.is_coordinate(name)) {
    reader.sink().error(value.location, value.path, fmt::format("'{}' is a coordinate; {}", name, expected));
    return std::nullopt;
  }
  if (state.is_constant(name)) {
    reader.sink().error(value.location, value.path,
                        fmt::format("'{}' is a constant and cannot also be a parameter; {} (write the value, or "
                                    "give the parameter its own name)",
                                    name, expected));
    return std::nullopt;
  }
  if (const auto found = state.parameter_use_index.find(name); found != state.parameter_use_index.end()) {
    // One entry per unknown keeps each parameter's role (and the regressor column) unambiguous.
    const ParameterUse& earlier = state.parameter_uses[found->second];
    reader.sink().error(value.location, value.path,
                        fmt::format("parameter '{}' is already used by {} (line {}); each unknown parameter may "
                                    "appear in one entry only",
                                    name, earlier.field, earlier.location.line));
    return std::nullopt;
  }
  state.parameter_use_index.emplace(name, state.parameter_uses.size());
  state.parameter_uses.push_back(ParameterUse{name, role, link, coordinate, value.path, value.location});
  return sym::symbol(name);
}

std::optional<int> coordinate_key(YamlReader& reader, const LoadState& state, const Located& key,
                                  std::string_view section) {
  const std::string& name = key.node.Scalar();
  if (const auto found = state.coordinate_index.find(name); found != state.coordinate_index.end()) return found->second;
  std::vector<std::string> names;
  for (const sym::Expr& coordinate : state.robot.coordinates) names.push_back(coordinate.name());
  // Not unknown_name_message: the name may well exist, as a link or a constant, just not as a coordinate.
  reader.sink().error(key.location, key.path,
                      fmt::format("'{}' is not a coordinate ({} entries are keyed by coordinate)", name, section),
                      closest_match(name, names));
  return std::nullopt;
}

}  // namespace dyncc::robot::detail
