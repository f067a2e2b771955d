// `dyncc check ROBOT.yaml`: load and validate a robot description, print what was understood.
//
// Diagnostics go to stderr in the compiler format (file:line:column: error: ...) so editors can
// jump to them; the summary goes to stdout. Exit code 2 on any error, 0 otherwise.
#include <fmt/core.h>

#include <array>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "robot/load.hpp"
#include "sym/print.hpp"

namespace dyncc::cli {

namespace {

using robot::Link;
using robot::RobotDescription;

std::string text(sym::Expr e) { return sym::to_string(e); }

std::string vector_text(const std::array<sym::Expr, 3>& v) {
  return fmt::format("[{}, {}, {}]", text(v[0]), text(v[1]), text(v[2]));
}

std::string joint_summary(const Link& link) {
  std::string line =
      fmt::format("{} [{}] {} = {}", link.name, robot::to_string(link.joint),
                  link.joint == robot::JointType::Revolute ? "theta" : "d", text(link.joint_expression()));
  // The fixed D-H entries, only the nonzero ones, so the tree stays readable.
  std::vector<std::string> fixed;
  const auto add = [&](const char* name, sym::Expr value) {
    if (!value.is_zero()) fixed.push_back(fmt::format("{} = {}", name, text(value)));
  };
  add("a", link.a);
  add("alpha", link.alpha);
  if (link.joint == robot::JointType::Revolute)
    add("d", link.d);
  else
    add("theta", link.theta);
  if (!fixed.empty()) {
    line += "   (";
    for (std::size_t i = 0; i < fixed.size(); ++i) line += (i ? ", " : "") + fixed[i];
    line += ")";
  }
  return line;
}

void print_tree(const RobotDescription& robot, int parent, int depth) {
  for (const int child : robot.children(parent)) {
    fmt::print("  {:{}}{}\n", "", 2 * depth, joint_summary(robot.links[static_cast<std::size_t>(child)]));
    print_tree(robot, child, depth + 1);
  }
}

std::string number(double value) { return fmt::format("{:g}", value); }

void print_parameters(const RobotDescription& robot) {
  fmt::print("unknown parameters ({}):\n", robot.parameters.size());
  // Grouped by owner: each link, then each coordinate's friction and rotor.
  std::map<std::pair<int, int>, std::vector<const robot::Parameter*>> groups;
  for (const robot::Parameter& parameter : robot.parameters) {
    const std::pair<int, int> owner =
        parameter.link >= 0 ? std::pair{0, parameter.link} : std::pair{1, parameter.coordinate};
    groups[owner].push_back(&parameter);
  }
  for (const auto& [owner, members] : groups) {
    const std::string title = owner.first == 0 ? robot.links[static_cast<std::size_t>(owner.second)].name
                                               : "joint " + robot.coordinate_name(owner.second);
    std::string line;
    for (const robot::Parameter* parameter : members) {
      line += fmt::format("{}{} = {}", line.empty() ? "" : ", ", parameter->name, number(parameter->nominal));
    }
    fmt::print("  {:<12} {}\n", title + ":", line);
  }
}

void print_summary(const RobotDescription& robot) {
  fmt::print("robot {} ({} D-H convention)\n", robot.name, robot::to_string(robot.convention));
  if (!robot.description.empty()) fmt::print("  {}\n", robot.description);
  fmt::print("gravity: {} m/s^2\n", vector_text(robot.gravity));
  std::string coordinates;
  for (const sym::Expr& coordinate : robot.coordinates)
    coordinates += (coordinates.empty() ? "" : ", ") + coordinate.name();
  fmt::print("coordinates ({}): {}\n", robot.coordinates.size(), coordinates);
  if (!robot.constants.empty()) {
    std::string constants;
    for (const robot::Constant& constant : robot.constants) {
      constants += fmt::format("{}{} = {}", constants.empty() ? "" : ", ", constant.name, constant.value.to_string());
    }
    fmt::print("constants ({}): {}\n", robot.constants.size(), constants);
  }
  fmt::print("links ({}):\n  base\n", robot.links.size());
  print_tree(robot, -1, 1);
  print_parameters(robot);
  if (!robot.friction.empty()) {
    fmt::print("friction:\n");
    for (const robot::Friction& friction : robot.friction) {
      fmt::print("  {}: coulomb {}, viscous {}\n", robot.coordinate_name(friction.coordinate), text(friction.coulomb),
                 text(friction.viscous));
    }
  }
  if (!robot.rotors.empty()) {
    fmt::print("rotor (reflected inertia = gear_ratio^2 * inertia):\n");
    for (const robot::Rotor& rotor : robot.rotors) {
      fmt::print("  {}: inertia {}, gear ratio {} -> {}\n", robot.coordinate_name(rotor.coordinate),
                 text(rotor.inertia), rotor.gear_ratio.to_string(), text(rotor.reflected_inertia()));
    }
  }
  if (!robot.joint_limits.empty()) {
    fmt::print("joint limits:\n");
    for (const robot::JointLimit& limit : robot.joint_limits) {
      fmt::print("  {}: [{}, {}]\n", robot.coordinate_name(limit.coordinate), number(limit.lower), number(limit.upper));
    }
  }
  if (!robot.loops.empty()) {
    fmt::print("loops ({}, to be proven closed by a later stage):\n", robot.loops.size());
    for (const robot::Loop& loop : robot.loops) {
      fmt::print("  {}: {} {} == {} {}\n", loop.name, loop.points[0].link_name, vector_text(loop.points[0].at),
                 loop.points[1].link_name, vector_text(loop.points[1].at));
    }
  }
  if (!robot.base_parameters.empty()) {
    fmt::print("base parameters ({}):\n", robot.base_parameters.size());
    for (const robot::BaseParameter& base : robot.base_parameters) {
      fmt::print("  {} = {}\n", base.name, text(base.value));
    }
  }
  fmt::print("physical consistency of nominal values: {}\n",
             robot.physical_consistency == robot::ConsistencyMode::Error ? "error" : "warn");
}

}  // namespace

int run_check(const CheckOptions& o) {
  const std::string& path = o.robot;
  const robot::LoadResult result = robot::load_robot(path);
  for (const robot::Diagnostic& diagnostic : result.diagnostics) fmt::print(stderr, "{}\n", diagnostic.format());
  const std::size_t errors = result.error_count();
  const std::size_t warnings = result.warning_count();
  if (!result.ok()) {
    fmt::print(stderr, "{}: {} error{}, {} warning{}\n", path, errors, errors == 1 ? "" : "s", warnings,
               warnings == 1 ? "" : "s");
    return kBadInput;
  }
  print_summary(*result.robot);
  fmt::print("ok: {} ({} warning{})\n", path, warnings, warnings == 1 ? "" : "s");
  return kSuccess;
}

}  // namespace dyncc::cli
