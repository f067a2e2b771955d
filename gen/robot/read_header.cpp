// Readers for the top of the file: name, convention, gravity, coordinates, constants.
#include <fmt/core.h>

#include "robot/load_state.hpp"
#include "robot/spelling.hpp"

namespace dyncc::robot::detail {

namespace {

// A scalar that must be one of a few words ("modified" | "standard").
std::optional<std::string> read_choice(YamlReader& reader, const Located& value,
                                       const std::vector<std::string>& choices) {
  auto word = reader.text(value, "one of a fixed set of words");
  if (!word) return std::nullopt;
  for (const std::string& choice : choices) {
    if (*word == choice) return word;
  }
  std::string listed;
  for (const std::string& choice : choices) listed += (listed.empty() ? "'" : " or '") + choice + "'";
  reader.sink().error(value.location, value.path, fmt::format("expected {}, got '{}'", listed, word->substr(0, 40)),
                      closest_match(*word, choices));
  return std::nullopt;
}

}  // namespace

void read_header(YamlReader& reader, LoadState& state, const std::map<std::string, Located>& top) {
  RobotDescription& robot = state.robot;
  if (const auto name = top.find("name"); name != top.end()) {
    if (auto text = reader.identifier(name->second, "the robot name, which names generated code")) robot.name = *text;
  }
  if (const auto description = top.find("description"); description != top.end()) {
    if (auto text = reader.text(description->second, "free text")) robot.description = *text;
  }
  if (const auto convention = top.find("convention"); convention != top.end()) {
    if (auto word = read_choice(reader, convention->second, {"modified", "standard"})) {
      robot.convention = *word == "modified" ? Convention::Modified : Convention::Standard;
    }
  }
  if (const auto gravity = top.find("gravity"); gravity != top.end()) {
    if (auto items = reader.fixed_sequence(gravity->second, 3, "x, y, z of gravity in m/s^2")) {
      for (std::size_t i = 0; i < 3; ++i) {
        if (auto value = reader.exact_number((*items)[i])) robot.gravity[i] = sym::number(*value);
      }
    }
  }
  if (const auto mode = top.find("physical_consistency"); mode != top.end()) {
    if (auto word = read_choice(reader, mode->second, {"error", "warn"})) {
      robot.physical_consistency = *word == "error" ? ConsistencyMode::Error : ConsistencyMode::Warn;
    }
  }
}

void read_coordinates(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_sequence(value, "the names of the independent coordinates, e.g. [q1, q2]")) return;
  const std::vector<Located> items = reader.elements(value);
  if (items.empty()) {
    reader.sink().error(value.location, value.path, "expected at least one coordinate");
    return;
  }
  for (const Located& item : items) {
    const auto name = reader.identifier(item, "a coordinate name");
    if (!name) continue;
    if (const auto earlier = state.coordinate_index.find(*name); earlier != state.coordinate_index.end()) {
      const SourceLocation first = state.robot.coordinate_locations[static_cast<std::size_t>(earlier->second)];
      reader.sink().error(item.location, item.path,
                          fmt::format("duplicate coordinate '{}' (first given at line {}, column {})", *name,
                                      first.line, first.column));
      continue;
    }
    state.coordinate_index.emplace(*name, static_cast<int>(state.robot.coordinates.size()));
    state.robot.coordinates.push_back(sym::symbol(*name));
    state.robot.coordinate_locations.push_back(item.location);
  }
}

void read_constants(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_map(value, "constant names with their values, e.g. {l2: 0.180}")) return;
  for (const auto& [key, item] : reader.entries(value)) {
    const auto name = reader.identifier(key, "a constant name");
    if (!name) continue;
    if (state.is_coordinate(*name)) {
      reader.sink().error(key.location, key.path,
                          fmt::format("'{}' is already a coordinate; a name can be a coordinate, a constant or a "
                                      "parameter, not several",
                                      *name));
      continue;
    }
    if (const auto number = reader.exact_number(item)) {
      state.constant_index.emplace(*name, state.robot.constants.size());
      state.robot.constants.push_back(Constant{*name, sym::symbol(*name), *number, key.location});
    } else {
      state.unreadable_names.push_back(*name);
    }
  }
}

}  // namespace dyncc::robot::detail
