// Readers for the sections after `links`: friction, rotor, joint_limits, parameters, loops,
// base_parameters.
#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "robot/load_state.hpp"
#include "robot/spelling.hpp"

namespace dyncc::robot::detail {

void read_friction(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_map(value, "friction per coordinate, e.g. {q1: {coulomb: fc1, viscous: fv1}}")) return;
  for (const auto& [key, item] : reader.entries(value)) {
    const auto coordinate = coordinate_key(reader, state, key, "friction");
    if (!coordinate) continue;
    if (!reader.expect_map(item, "coulomb and viscous coefficients")) continue;
    const auto fields = reader.fields(item, {"coulomb", "viscous"});
    Friction friction{*coordinate, sym::Expr(), sym::Expr(), key.location};
    if (const auto coulomb = fields.find("coulomb"); coulomb != fields.end()) {
      if (auto entry = record_entry(reader, state, coulomb->second, ParameterRole::CoulombFriction, -1, *coordinate)) {
        friction.coulomb = *entry;
      }
    }
    if (const auto viscous = fields.find("viscous"); viscous != fields.end()) {
      if (auto entry = record_entry(reader, state, viscous->second, ParameterRole::ViscousFriction, -1, *coordinate)) {
        friction.viscous = *entry;
      }
    }
    state.robot.friction.push_back(friction);
  }
}

void read_rotors(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_map(value, "rotor per coordinate, e.g. {q1: {inertia: 0.0002, gear_ratio: 62.6}}")) return;
  for (const auto& [key, item] : reader.entries(value)) {
    const auto coordinate = coordinate_key(reader, state, key, "rotor");
    if (!coordinate) continue;
    if (!reader.expect_map(item, "the rotor's inertia and gear_ratio")) continue;
    const auto fields = reader.fields(item, {"inertia", "gear_ratio"});
    Rotor rotor{*coordinate, sym::Expr(), sym::Rational(1), key.location};
    if (reader.require(fields, item, "inertia", "the motor rotor's inertia about its axis, kg m^2")) {
      if (auto entry =
              record_entry(reader, state, fields.at("inertia"), ParameterRole::RotorInertia, -1, *coordinate)) {
        rotor.inertia = *entry;
      }
    }
    if (const auto ratio = fields.find("gear_ratio"); ratio != fields.end()) {
      // A number, never an unknown: ratio^2 * inertia must stay linear in the unknowns.
      if (auto number = reader.exact_number(ratio->second)) {
        if (number->is_zero()) {
          reader.sink().error(ratio->second.location, ratio->second.path, "gear_ratio must not be 0");
        } else {
          rotor.gear_ratio = *number;
        }
      }
    }
    state.robot.rotors.push_back(rotor);
  }
}

void read_joint_limits(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_map(value, "limits per coordinate, e.g. {q1: [-2.5, 2.5]}")) return;
  for (const auto& [key, item] : reader.entries(value)) {
    const auto coordinate = coordinate_key(reader, state, key, "joint_limits");
    if (!coordinate) continue;
    const auto bounds = reader.fixed_sequence(item, 2, "lower and upper limit, rad or m");
    if (!bounds) continue;
    const auto lower = reader.finite_number((*bounds)[0]);
    const auto upper = reader.finite_number((*bounds)[1]);
    if (!lower || !upper) continue;
    if (!(*lower < *upper)) {
      reader.sink().error(item.location, item.path,
                          fmt::format("lower limit {} must be below upper limit {}", *lower, *upper));
      continue;
    }
    state.robot.joint_limits.push_back(JointLimit{*coordinate, *lower, *upper, key.location});
  }
}

void read_parameters(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_map(value, "nominal values of the parameter names, e.g. {m3: 0.40}")) return;
  for (const auto& [key, item] : reader.entries(value)) {
    const auto name = reader.identifier(key, "a parameter name");
    if (!name) continue;
    if (state.is_constant(*name) || state.is_coordinate(*name)) {
      reader.sink().error(key.location, key.path,
                          fmt::format("'{}' is a {} and cannot also be a parameter", *name,
                                      state.is_constant(*name) ? "constant" : "coordinate"));
      continue;
    }
    if (const auto number = reader.finite_number(item)) {
      state.nominal_values.push_back(NominalValue{*name, *number, key.path, key.location});
    } else {
      state.unreadable_names.push_back(*name);
    }
  }
}

namespace {

std::optional<LoopPoint> read_loop_point(YamlReader& reader, const SymbolScope& scope, const Located& value) {
  if (!reader.expect_map(value, "a point {link: NAME, at: [x, y, z]} in that link's frame")) return std::nullopt;
  const auto fields = reader.fields(value, {"link", "at"});
  LoopPoint point;
  point.location = value.location;
  bool ok = reader.require(fields, value, "link", "a link name or 'base'");
  ok = reader.require(fields, value, "at", "x, y, z in the link's frame") && ok;
  if (!ok) return std::nullopt;
  const auto link = reader.identifier(fields.at("link"), "a link name or 'base'");
  const auto at = reader.fixed_sequence(fields.at("at"), 3, "x, y, z in the link's frame");
  if (!link || !at) return std::nullopt;
  point.link_name = *link;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto coordinate = read_expression(reader, (*at)[i], scope);
    if (!coordinate)
      ok = false;
    else
      point.at[i] = *coordinate;
  }
  if (!ok) return std::nullopt;
  return point;
}

}  // namespace

void read_loops(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_sequence(value, "a list of loop closures")) return;
  const SymbolScope scope = state.geometry_scope();
  for (const Located& entry : reader.elements(value)) {
    if (!reader.expect_map(entry, "a loop {name: NAME, points: [POINT, POINT]}")) continue;
    const auto fields = reader.fields(entry, {"name", "points"});
    bool ok = reader.require(fields, entry, "name");
    ok = reader.require(fields, entry, "points", "two points, one on each side of the loop") && ok;
    if (!ok) continue;
    Loop loop;
    loop.location = entry.location;
    const auto name = reader.identifier(fields.at("name"), "a loop name");
    if (name) {
      const bool duplicate = std::any_of(state.robot.loops.begin(), state.robot.loops.end(),
                                         [&](const Loop& other) { return other.name == *name; });
      if (duplicate) {
        reader.sink().error(fields.at("name").location, fields.at("name").path,
                            fmt::format("duplicate loop name '{}'", *name));
      }
      loop.name = *name;
    }
    const auto points = reader.fixed_sequence(fields.at("points"), 2, "the two points that must coincide");
    if (!points) continue;
    auto first = read_loop_point(reader, scope, (*points)[0]);
    auto second = read_loop_point(reader, scope, (*points)[1]);
    if (!first || !second || !name) continue;
    loop.points = {*first, *second};
    state.robot.loops.push_back(std::move(loop));
  }
}

void read_base_parameters(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_map(value, "named groupings of parameters, e.g. {p13: m2*x2 + m3*l2}")) return;
  const SymbolScope scope = state.base_parameter_scope();
  for (const auto& [key, item] : reader.entries(value)) {
    const auto name = reader.identifier(key, "a base parameter name");
    if (!name) continue;
    const bool clashes = state.is_constant(*name) || state.is_coordinate(*name) || state.is_parameter(*name);
    if (clashes) {
      reader.sink().error(key.location, key.path,
                          fmt::format("'{}' is already a coordinate, constant or parameter; give the grouping its "
                                      "own name",
                                      *name));
      continue;
    }
    if (auto expr = read_expression(reader, item, scope)) {
      state.robot.base_parameters.push_back(BaseParameter{*name, *expr, key.location});
    }
  }
}

// Names: every grouping of base_parameters must get a value (a partial estimate cannot be mapped
// onto the base set); parameters outside the groupings (friction, say) may be given too.
void read_initial_estimate(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_map(value, "starting values of the base_parameters groupings, e.g. {p0: 0.0489}")) return;
  if (state.robot.base_parameters.empty()) {
    reader.sink().error(value.location, value.path,
                        "initial_estimate gives values of base_parameters groupings, but the description has no "
                        "base_parameters");
    return;
  }
  std::vector<std::string> allowed;  // the grouping names
  std::set<std::string> inside;      // parameter names the groupings contain
  for (const auto& b : state.robot.base_parameters) {
    allowed.push_back(b.name);
    for (const sym::Expr e : sym::free_symbols(b.value)) inside.insert(e.name());
  }
  bool all_read = true;
  for (const auto& [key, item] : reader.entries(value)) {
    const auto name = reader.identifier(key, "a base_parameters grouping or parameter name");
    if (!name) {
      all_read = false;
      continue;
    }
    const bool grouping = std::find(allowed.begin(), allowed.end(), *name) != allowed.end();
    if (!grouping && !state.is_parameter(*name)) {
      const std::string near = closest_match(*name, allowed);
      reader.sink().error(key.location, key.path,
                          fmt::format("'{}' is neither a base_parameters grouping nor a parameter{}", *name,
                                      near.empty() ? std::string() : fmt::format("; did you mean '{}'?", near)));
      all_read = false;
      continue;
    }
    if (!grouping && inside.contains(*name)) {
      reader.sink().error(key.location, key.path,
                          fmt::format("'{}' enters the base_parameters groupings; give the groupings' values, "
                                      "not its own",
                                      *name));
      all_read = false;
      continue;
    }
    const auto number = reader.finite_number(item);
    if (!number) {
      all_read = false;
      continue;
    }
    state.robot.initial_estimate.push_back(EstimateEntry{*name, *number, key.location});
  }
  if (!all_read) return;
  std::vector<std::string> missing;
  for (const auto& b : state.robot.base_parameters) {
    const bool given = std::any_of(state.robot.initial_estimate.begin(), state.robot.initial_estimate.end(),
                                   [&](const EstimateEntry& e) { return e.name == b.name; });
    if (!given) missing.push_back(b.name);
  }
  if (!missing.empty()) {
    reader.sink().error(value.location, value.path,
                        fmt::format("initial_estimate has no value for {} (every base_parameters grouping needs "
                                    "one)",
                                    fmt::join(missing, ", ")));
  }
}

}  // namespace dyncc::robot::detail
