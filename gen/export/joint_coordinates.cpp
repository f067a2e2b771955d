#include "export/joint_coordinates.hpp"

#include <fmt/core.h>

#include <algorithm>

#include "export/export_error.hpp"
#include "sym/diff.hpp"
#include "sym/print.hpp"
#include "sym/substitute.hpp"

namespace dyncc::exporting {

bool JointCoordinate::moves() const {
  return std::any_of(coefficients.begin(), coefficients.end(), [](double c) { return c != 0.0; });
}

std::vector<JointCoordinate> joint_coordinates(const robot::RobotDescription& robot, const SymbolValues& values) {
  sym::Substitution at_zero;
  for (const sym::Expr q : robot.coordinates) at_zero.emplace(q, sym::Expr(0));

  std::vector<JointCoordinate> out;
  out.reserve(robot.links.size());
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    const robot::Link& link = robot.links[l];
    const sym::Expr variable = link.joint_expression();
    const char* field = link.joint == robot::JointType::Revolute ? "theta" : "d";
    JointCoordinate jc;
    jc.offset_expression = sym::substitute(variable, at_zero);
    jc.offset = value_of(jc.offset_expression, values);
    for (const sym::Expr q : robot.coordinates) {
      const sym::Expr rate = sym::diff(variable, q);
      for (const sym::Expr other : robot.coordinates) {
        if (!sym::depends_on(rate, other)) continue;
        throw error_at(robot.source_path.string(), link.location_of(field), fmt::format("links[{}].{}", l, field),
                       fmt::format("'{}' is not affine in the coordinates (its derivative by {} is {}); MJCF and "
                                   "URDF joints can only be coupled linearly",
                                   sym::to_string(variable), q.name(), sym::to_string(rate)));
      }
      jc.coefficients.push_back(value_of(rate, values));
    }
    out.push_back(std::move(jc));
  }
  return out;
}

}  // namespace dyncc::exporting
