// Loading the shipped robots and load_robot's diagnostics, called directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "robot/load.hpp"
#include "robot/spelling.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"
#include "sym/substitute.hpp"

namespace dyncc::robot {
namespace {

const std::string kRobots = std::string(DYNCC_SOURCE_DIR) + "/robots/";

std::vector<std::string> parameter_names(const RobotDescription& robot) {
  std::vector<std::string> names;
  for (const Parameter& parameter : robot.parameters) names.push_back(parameter.name);
  return names;
}

std::string all_messages(const LoadResult& result) {
  std::string text;
  for (const Diagnostic& diagnostic : result.diagnostics) text += diagnostic.format() + "\n";
  return text;
}

// A small valid description; tests replace one piece of it to break it.
const std::string kValid = R"(name: tiny
convention: modified
gravity: [0, 0, -9.81]
coordinates: [q1, q2]
constants: {l1: 0.5}
links:
  - name: first
    parent: base
    joint: revolute
    theta: q1
    mass: m1
    com: [x1, 0, 0]
    inertia: {xx: 0.001, yy: 0.002, zz: 0.002}
  - name: second
    parent: first
    joint: revolute
    a: l1
    alpha: -pi/2
    theta: q2
    mass: 0.5
parameters: {m1: 1.0, x1: 0.2}
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(RobotLoad, KraftStructure) {
  const LoadResult result = load_robot(kRobots + "kraft.yaml");
  ASSERT_TRUE(result.ok()) << all_messages(result);
  EXPECT_EQ(result.warning_count(), 0u) << all_messages(result);
  const RobotDescription& robot = *result.robot;
  EXPECT_EQ(robot.name, "kraft_right");
  EXPECT_EQ(robot.convention, Convention::Modified);
  ASSERT_EQ(robot.coordinates.size(), 3u);
  EXPECT_EQ(robot.coordinates[0], sym::symbol("q1"));
  EXPECT_EQ(robot.coordinates[2], sym::symbol("q3"));
  ASSERT_EQ(robot.links.size(), 5u);
  const std::vector<std::string> names = {"yaw", "upper_arm", "forearm", "crank", "coupler"};
  const std::vector<int> parents = {-1, 0, 1, 0, 3};
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(robot.links[i].name, names[i]);
    EXPECT_EQ(robot.links[i].parent, parents[i]) << names[i];
    EXPECT_EQ(robot.links[i].joint, JointType::Revolute);
  }
  // The parallel-link constraints are in the joint expressions, in terms of named constants.
  EXPECT_EQ(robot.links[2].theta, sym::parse_or_throw("q3 - q2"));
  EXPECT_EQ(robot.links[2].d, sym::parse_or_throw("b2 - b1"));
  EXPECT_EQ(robot.links[4].theta, sym::parse_or_throw("q2 - q3"));
  EXPECT_EQ(robot.links[1].alpha, sym::parse_or_throw("-pi/2"));
  EXPECT_EQ(robot.gravity[2], sym::parse_or_throw("-9.81"));
  // 32 inertial unknowns (paper's appendix) + 6 friction + 3 actuator inertias.
  EXPECT_EQ(robot.parameters.size(), 41u);
  const std::vector<std::string> expected_start = {"m1", "y1", "z1", "i1xx", "i1yy", "i1zz", "i1yz", "m2", "x2"};
  const std::vector<std::string> actual = parameter_names(robot);
  EXPECT_TRUE(std::equal(expected_start.begin(), expected_start.end(), actual.begin()));
  EXPECT_EQ(actual.back(), "jm3");
  const Parameter* fc1 = robot.find_parameter("fc1");
  ASSERT_NE(fc1, nullptr);
  EXPECT_EQ(fc1->role, ParameterRole::CoulombFriction);
  EXPECT_EQ(fc1->coordinate, 0);
  EXPECT_DOUBLE_EQ(fc1->nominal, 0.0228);
  const Parameter* i3xy = robot.find_parameter("i3xy");
  ASSERT_NE(i3xy, nullptr);
  EXPECT_EQ(i3xy->link, 2);
  EXPECT_EQ(i3xy->field, "links[2].inertia.xy");
  EXPECT_EQ(robot.links[2].inertia.xy, sym::symbol("i3xy"));
  EXPECT_TRUE(robot.links[1].inertia.xy.is_zero());  // entries left out are 0
  ASSERT_EQ(robot.loops.size(), 1u);
  EXPECT_EQ(robot.loops[0].points[0].link, 4);
  EXPECT_EQ(robot.loops[0].points[1].link, 2);
  ASSERT_EQ(robot.base_parameters.size(), 15u);
  EXPECT_EQ(robot.base_parameters[13].name, "p13");
  EXPECT_EQ(robot.base_parameters[13].value, sym::parse_or_throw("m2*x2 + m3*l2 + m4*x4"));
  EXPECT_EQ(robot.friction.size(), 3u);
  EXPECT_EQ(robot.joint_limits.size(), 3u);
  EXPECT_EQ(robot.physical_consistency, ConsistencyMode::Error);
}

TEST(RobotLoad, KraftConstantsStaySymbolic) {
  const LoadResult result = load_robot(kRobots + "kraft.yaml");
  ASSERT_TRUE(result.ok());
  const RobotDescription& robot = *result.robot;
  const sym::Expr d3 = robot.links[2].d;
  EXPECT_FALSE(d3.is_number());
  // Table 1: d3 = b2 - b1 = 0.055.
  EXPECT_EQ(sym::substitute(d3, robot.constant_values()), sym::parse_or_throw("0.055"));
  const Constant* l2 = robot.find_constant("l2");
  ASSERT_NE(l2, nullptr);
  EXPECT_EQ(l2->value, sym::Rational(9, 50));
  EXPECT_DOUBLE_EQ(robot.constant_doubles().at("b1"), 0.075);
  EXPECT_EQ(robot.links[2].location_of("theta").line, robot.links[2].field_locations.at("theta").line);
  EXPECT_GT(robot.links[2].location.line, 0);
}

TEST(RobotLoad, PlanarTwoLink) {
  const LoadResult result = load_robot(kRobots + "planar_2link.yaml");
  ASSERT_TRUE(result.ok()) << all_messages(result);
  const RobotDescription& robot = *result.robot;
  EXPECT_EQ(robot.convention, Convention::Standard);
  ASSERT_EQ(robot.links.size(), 2u);
  EXPECT_EQ(robot.links[1].parent, 0);
  EXPECT_EQ(robot.children(-1), std::vector<int>{0});
  EXPECT_EQ(robot.children(0), std::vector<int>{1});
  EXPECT_EQ(parameter_names(robot), (std::vector<std::string>{"m1", "c1", "i1zz", "m2", "c2", "i2zz", "fv1", "fv2"}));
  ASSERT_EQ(robot.rotors.size(), 1u);
  EXPECT_EQ(robot.rotors[0].reflected_inertia(), sym::parse_or_throw("0.05"));
  const auto gravity = robot.gravity_values();
  EXPECT_DOUBLE_EQ(gravity[1], -9.81);
  EXPECT_TRUE(robot.loops.empty());
}

TEST(RobotLoad, ValidTextLoads) {
  const LoadResult result = load_robot_from_string(kValid, "tiny.yaml");
  ASSERT_TRUE(result.ok()) << all_messages(result);
  EXPECT_TRUE(result.diagnostics.empty()) << all_messages(result);
}

TEST(RobotLoad, UnknownSymbolPointsInsideTheExpression) {
  const LoadResult result = load_robot_from_string(replaced(kValid, "theta: q2", "theta: q1 + q3"), "x.yaml");
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.error_count(), 1u) << all_messages(result);
  const Diagnostic& error = result.diagnostics.front();
  EXPECT_EQ(error.location.line, 19);
  EXPECT_EQ(error.location.column, 17);  // "    theta: q1 + q3": q3 starts in column 17
  EXPECT_EQ(error.field, "links[1].theta");
  EXPECT_EQ(error.suggestion, "q1");
  EXPECT_EQ(error.format(), "x.yaml:19:17: error: links[1].theta: unknown symbol 'q3'; did you mean 'q1'?");
}

TEST(RobotLoad, QuotedScalarColumnsSkipTheQuote) {
  const LoadResult result = load_robot_from_string(replaced(kValid, "a: l1", "a: 'l1 + zz'"), "x.yaml");
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.diagnostics.front().location.line, 17);
  EXPECT_EQ(result.diagnostics.front().location.column, 14);  // "    a: 'l1 + zz'": zz in column 14
}

TEST(RobotLoad, YamlSyntaxErrorIsADiagnosticWithOneBasedPosition) {
  const LoadResult result = load_robot_from_string("name: [a, b\n", "x.yaml");
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.diagnostics.size(), 1u);
  EXPECT_NE(result.diagnostics[0].message.find("invalid YAML"), std::string::npos);
  EXPECT_GE(result.diagnostics[0].location.line, 1);
  EXPECT_GE(result.diagnostics[0].location.column, 1);
}

TEST(RobotLoad, MissingFileIsADiagnostic) {
  const LoadResult result = load_robot(kRobots + "does_not_exist.yaml");
  ASSERT_FALSE(result.ok());
  EXPECT_NE(all_messages(result).find("no such file"), std::string::npos);
}

TEST(RobotLoad, MisspeltKeyGetsASuggestion) {
  const LoadResult result = load_robot_from_string(replaced(kValid, "    joint: revolute\n    theta: q1",
                                                            "    joint: revolute\n    thetaa: q1"),
                                                   "x.yaml");
  ASSERT_FALSE(result.ok());
  const auto found = std::find_if(result.diagnostics.begin(), result.diagnostics.end(),
                                  [](const Diagnostic& d) { return d.field == "links[0].thetaa"; });
  ASSERT_NE(found, result.diagnostics.end()) << all_messages(result);
  EXPECT_EQ(found->suggestion, "theta");
}

TEST(RobotLoad, PhysicalConsistencyWarnMode) {
  const std::string broken = replaced(kValid, "mass: 0.5", "mass: -0.5");
  const LoadResult strict = load_robot_from_string(broken, "x.yaml");
  EXPECT_FALSE(strict.ok());
  const LoadResult lenient = load_robot_from_string(broken + "physical_consistency: warn\n", "x.yaml");
  ASSERT_TRUE(lenient.ok()) << all_messages(lenient);
  EXPECT_EQ(lenient.warning_count(), 1u);
  EXPECT_EQ(lenient.robot->physical_consistency, ConsistencyMode::Warn);
}

TEST(RobotLoad, UnusedNominalValueIsAWarning) {
  const LoadResult result =
      load_robot_from_string(replaced(kValid, "{m1: 1.0, x1: 0.2}", "{m1: 1.0, x1: 0.2, m9: 3}"), "x.yaml");
  ASSERT_TRUE(result.ok()) << all_messages(result);
  ASSERT_EQ(result.warning_count(), 1u);
  EXPECT_EQ(result.diagnostics[0].field, "parameters.m9");
}

TEST(RobotLoad, HostileInputsAreDiagnosticsNotCrashes) {
  const std::vector<std::string> inputs = {
      "",
      "---\n...\n",
      "[1, 2, 3]\n",
      "name: &a [*a]\n",
      "links: !!binary aGVsbG8=\n",
      std::string(5000, '[') + std::string(5000, ']'),
      replaced(kValid, "theta: q2", "theta: " + std::string(400, '(') + "q2" + std::string(400, ')')),
      replaced(kValid, "theta: q2", "theta: 2^64^64"),
      replaced(kValid, "theta: q2", "theta: q2/0"),
      replaced(kValid, "a: l1", "a: 99999999999999999999999"),
      replaced(kValid, "mass: 0.5", "mass: {a: 1}"),
      replaced(kValid, "links:", "links: ~\nx:"),
  };
  for (const std::string& input : inputs) {
    const LoadResult result = load_robot_from_string(input, "hostile.yaml");
    EXPECT_FALSE(result.ok()) << input.substr(0, 80);
    EXPECT_GT(result.error_count(), 0u) << input.substr(0, 80);
  }
}

TEST(RobotSpelling, EditDistanceCountsSwapsOnce) {
  EXPECT_EQ(edit_distance("theta", "theta"), 0u);
  EXPECT_EQ(edit_distance("thetta", "theta"), 1u);
  EXPECT_EQ(edit_distance("yx", "xy"), 1u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(closest_match("gravty", {"name", "gravity", "links"}), "gravity");
  EXPECT_EQ(closest_match("yx", {"xx", "yy", "zz", "xy"}), "xy");
  EXPECT_EQ(closest_match("banana", {"q1", "q2"}), "");
}

}  // namespace
}  // namespace dyncc::robot
