// Checks that span sections: the link tree, which coordinates the links use, parameters against
// their nominal values, and the links loops refer to.
#include <fmt/core.h>

#include <algorithm>
#include <optional>
#include <set>
#include <unordered_map>

#include "robot/load_state.hpp"
#include "robot/spelling.hpp"

namespace dyncc::robot::detail {

namespace {

std::vector<std::string> link_names_and_base(const RobotDescription& robot) {
  std::vector<std::string> names{"base"};
  for (const Link& link : robot.links) {
    if (!link.name.empty()) names.push_back(link.name);
  }
  return names;
}

using LinkIndex = std::unordered_map<std::string, int>;

// Follows parent names from `start`; returns the chain if it comes back to `start`.
std::vector<std::string> parent_cycle(const RobotDescription& robot, const LinkIndex& index, int start) {
  std::vector<std::string> chain{robot.links[static_cast<std::size_t>(start)].name};
  int current = start;
  for (std::size_t steps = 0; steps <= robot.links.size(); ++steps) {
    const auto parent = index.find(robot.links[static_cast<std::size_t>(current)].parent_name);
    if (parent == index.end()) return {};
    chain.push_back(robot.links[static_cast<std::size_t>(parent->second)].name);
    if (parent->second == start) return chain;
    current = parent->second;
  }
  return {};
}

void resolve_parents(RobotDescription& robot, DiagnosticSink& sink) {
  const std::vector<std::string> candidates = link_names_and_base(robot);
  LinkIndex index;
  for (std::size_t i = 0; i < robot.links.size(); ++i) index.emplace(robot.links[i].name, static_cast<int>(i));
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    Link& link = robot.links[i];
    link.parent = -1;
    if (link.parent_name.empty() || link.parent_name == "base") continue;
    const std::string field = fmt::format("links[{}].parent", i);
    const SourceLocation at = link.location_of("parent");
    const auto found = index.find(link.parent_name);
    const std::optional<int> parent = found == index.end() ? std::nullopt : std::optional<int>(found->second);
    if (!parent) {
      const std::string suggestion = sink.saturated() ? std::string() : closest_match(link.parent_name, candidates);
      sink.error(at, field,
                 unknown_name_message("parent link", link.parent_name, "expected 'base' or an earlier link",
                                      suggestion),
                 suggestion);
      continue;
    }
    if (static_cast<std::size_t>(*parent) == i) {
      sink.error(at, field, fmt::format("link '{}' cannot be its own parent", link.name));
      continue;
    }
    if (static_cast<std::size_t>(*parent) > i) {
      const std::vector<std::string> cycle =
          sink.saturated() ? std::vector<std::string>() : parent_cycle(robot, index, static_cast<int>(i));
      if (!cycle.empty()) {
        // Long cycles are shortened: the first few links and the way back are enough to find it.
        constexpr std::size_t kShown = 6;
        std::string chain;
        for (std::size_t k = 0; k < cycle.size(); ++k) {
          if (k == kShown && cycle.size() > kShown + 1) {
            chain += fmt::format(" -> ... ({} links)", cycle.size() - 1);
            k = cycle.size() - 1;
          }
          chain += (chain.empty() ? "" : " -> ") + cycle[k];
        }
        sink.error(at, field, fmt::format("parent cycle: {}; links must form a tree rooted at 'base'", chain));
      } else {
        sink.error(at, field,
                   fmt::format("parent '{}' is declared later (links[{}]); list parents before their children",
                               link.parent_name, *parent));
      }
      continue;
    }
    link.parent = *parent;
  }
}

// Coordinates (by name) that an expression depends on.
std::set<std::string> coordinates_in(sym::Expr expr, const std::set<std::string>& coordinate_names) {
  std::set<std::string> found;
  for (const sym::Expr& symbol : sym::free_symbols(expr)) {
    if (coordinate_names.contains(symbol.name())) found.insert(symbol.name());
  }
  return found;
}

std::set<std::string> coordinate_names(const RobotDescription& robot) {
  std::set<std::string> names;
  for (const sym::Expr& coordinate : robot.coordinates) names.insert(coordinate.name());
  return names;
}

void check_coordinate_use(const RobotDescription& robot, DiagnosticSink& sink) {
  const std::set<std::string> all = coordinate_names(robot);
  std::set<std::string> used;
  for (const Link& link : robot.links) {
    for (const sym::Expr expr : {link.a, link.alpha, link.d, link.theta}) used.merge(coordinates_in(expr, all));
  }
  for (std::size_t c = 0; c < robot.coordinates.size(); ++c) {
    const std::string& name = robot.coordinates[c].name();
    if (used.contains(name)) continue;
    sink.error(robot.coordinate_locations[c], fmt::format("coordinates[{}]", c),
               fmt::format("coordinate '{}' is used by no link (write it in a link's theta or d)", name));
  }
}

// Only the joint variable moves: coordinates elsewhere would contradict the joint type.
void check_joint_variables(const RobotDescription& robot, DiagnosticSink& sink, bool expressions_complete) {
  const std::set<std::string> all = coordinate_names(robot);
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    const Link& link = robot.links[i];
    const bool revolute = link.joint == JointType::Revolute;
    const std::string variable = revolute ? "theta" : "d";
    const std::pair<const char*, sym::Expr> fixed_fields[] = {
        {"a", link.a}, {"alpha", link.alpha}, {revolute ? "d" : "theta", revolute ? link.d : link.theta}};
    for (const auto& [field, expr] : fixed_fields) {
      const std::set<std::string> moving = coordinates_in(expr, all);
      if (moving.empty()) continue;
      sink.error(link.location_of(field), fmt::format("links[{}].{}", i, field),
                 fmt::format("depends on coordinate '{}', but only {} varies at a {} joint", *moving.begin(), variable,
                             to_string(link.joint)));
    }
    const bool moves = !coordinates_in(link.joint_expression(), all).empty();
    if (expressions_complete && !moves && link.field_locations.contains(variable)) {
      sink.warning(link.location_of(variable), fmt::format("links[{}].{}", i, variable),
                   fmt::format("the joint variable depends on no coordinate: link '{}' is rigidly attached to its "
                               "parent",
                               link.name));
    }
  }
}

void assemble_parameters(LoadState& state, DiagnosticSink& sink) {
  std::vector<std::string> used_names;
  for (const ParameterUse& use : state.parameter_uses) used_names.push_back(use.name);
  std::unordered_map<std::string, const NominalValue*> nominal_by_name;
  std::vector<std::string> unused_nominal_names;
  for (const NominalValue& nominal : state.nominal_values) {
    nominal_by_name.emplace(nominal.name, &nominal);
    if (!state.is_parameter(nominal.name)) unused_nominal_names.push_back(nominal.name);
  }
  const std::set<std::string> unreadable(state.unreadable_names.begin(), state.unreadable_names.end());
  for (const ParameterUse& use : state.parameter_uses) {
    const auto found = nominal_by_name.find(use.name);
    if (found == nominal_by_name.end() && unreadable.contains(use.name)) continue;  // its bad value was reported
    if (found == nominal_by_name.end()) {
      sink.error(use.location, use.field,
                 fmt::format("parameter '{}' has no nominal value (add '{}: VALUE' under parameters)", use.name,
                             use.name),
                 sink.saturated() ? std::string() : closest_match(use.name, unused_nominal_names));
      continue;
    }
    const NominalValue& nominal = *found->second;
    state.robot.parameters.push_back(Parameter{use.name, sym::symbol(use.name), nominal.value, use.role, use.link,
                                               use.coordinate, use.field, use.location, nominal.location});
  }
  for (const NominalValue& nominal : state.nominal_values) {
    if (state.is_parameter(nominal.name)) continue;
    sink.warning(nominal.location, nominal.field,
                 fmt::format("nominal value for '{}', which no link, friction or rotor entry uses", nominal.name),
                 sink.saturated() ? std::string() : closest_match(nominal.name, used_names));
  }
}

void resolve_loop_links(RobotDescription& robot, DiagnosticSink& sink) {
  const std::vector<std::string> candidates = link_names_and_base(robot);
  for (std::size_t l = 0; l < robot.loops.size(); ++l) {
    for (std::size_t p = 0; p < 2; ++p) {
      LoopPoint& point = robot.loops[l].points[p];
      point.link = -1;
      if (point.link_name == "base") continue;
      if (const auto link = robot.find_link(point.link_name)) {
        point.link = *link;
        continue;
      }
      const std::string suggestion = sink.saturated() ? std::string() : closest_match(point.link_name, candidates);
      sink.error(point.location, fmt::format("loops[{}].points[{}].link", l, p),
                 unknown_name_message("link", point.link_name, "expected a link name or 'base'", suggestion),
                 suggestion);
    }
  }
}

}  // namespace

void validate(LoadState& state, DiagnosticSink& sink) {
  RobotDescription& robot = state.robot;
  if (state.links_readable) {
    // An expression that failed to read is left 0, so "coordinate unused" would only be noise then.
    const bool expressions_complete = !sink.has_errors();
    resolve_parents(robot, sink);
    if (expressions_complete) check_coordinate_use(robot, sink);
    check_joint_variables(robot, sink, expressions_complete);
  }
  assemble_parameters(state, sink);
  resolve_loop_links(robot, sink);
  // Entries that failed to read are left 0, so physics checks would only add noise after an error.
  if (!sink.has_errors()) check_physical_consistency(robot, sink);
}

}  // namespace dyncc::robot::detail
