#include "export/loop_closures.hpp"

#include <fmt/core.h>

#include <cmath>

#include "export/export_error.hpp"
#include "kinematics/kinematics.hpp"
#include "kinematics/loops.hpp"

namespace dyncc::exporting {
namespace {

bool depends_on_coordinates(const robot::RobotDescription& robot, const robot::LoopPoint& point) {
  for (const sym::Expr& e : point.at) {
    for (const sym::Expr q : robot.coordinates) {
      if (sym::depends_on(e, q)) return true;
    }
  }
  return false;
}

Eigen::Vector3d in_body_frame(const std::vector<Body>& bodies, const robot::LoopPoint& point,
                              const SymbolValues& values) {
  Eigen::Vector3d local;
  for (int i = 0; i < 3; ++i) local[i] = value_of(point.at[static_cast<std::size_t>(i)], values);
  if (point.link < 0) return local;
  return bodies[static_cast<std::size_t>(point.link)].from_link_frame(local);
}

}  // namespace

std::vector<LoopClosure> loop_closures(const robot::RobotDescription& robot, const std::vector<Body>& bodies,
                                       const SymbolValues& values) {
  std::vector<LoopClosure> out;
  if (robot.loops.empty()) return out;
  const kin::Kinematics kinematics = kin::compute_kinematics(robot);
  const std::vector<kin::LoopCheck> checks = kin::check_loops(robot, kinematics);
  for (std::size_t i = 0; i < robot.loops.size(); ++i) {
    const robot::Loop& loop = robot.loops[i];
    if (!checks[i].closed) {
      const auto& r = checks[i].residual;
      throw error_at(robot.source_path.string(), loop.location, "loops." + loop.name,
                     fmt::format("the loop does not close (the two points are {:.6g} m apart at a sample "
                                 "configuration), so there is no mechanism to export",
                                 std::hypot(r[0], r[1], r[2])));
    }
    LoopClosure c;
    c.name = loop.name;
    c.location = loop.location;
    c.body1 = loop.points[0].link;
    c.body2 = loop.points[1].link;
    c.fixed_points = !depends_on_coordinates(robot, loop.points[0]) && !depends_on_coordinates(robot, loop.points[1]);
    if (c.fixed_points) {
      c.anchor1 = in_body_frame(bodies, loop.points[0], values);
      c.anchor2 = in_body_frame(bodies, loop.points[1], values);
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace dyncc::exporting
