#include "kinematics/loops.hpp"

#include <random>

#include "sym/evaluate.hpp"
#include "sym/substitute.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::kin {

std::vector<LoopCheck> check_loops(const robot::RobotDescription& robot, const Kinematics& kin) {
  std::vector<LoopCheck> out;
  const sym::Substitution constants = robot.constant_values();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (const robot::Loop& loop : robot.loops) {
    LoopCheck check;
    check.name = loop.name;
    const Vec3 p1 = point_in_base(kin, loop.points[0].link, loop.points[0].at);
    const Vec3 p2 = point_in_base(kin, loop.points[1].link, loop.points[1].at);
    const Vec3 gap = p2 - p1;
    // Exact proof with the constants' exact values (a gap that closes only for the given
    // dimensions is still a closed loop for this robot).
    check.closed = true;
    check.proved = true;
    for (const sym::Expr component : gap) {
      const sym::ZeroTestResult r = sym::test_zero(sym::substitute(component, constants));
      if (r.verdict != sym::ZeroVerdict::Zero) check.closed = false;
      if (!r.proved) {
        check.proved = false;
        check.detail = r.note;
      }
    }
    std::vector<double> q(robot.coordinates.size());
    for (std::size_t i = 0; i < q.size(); ++i) {
      q[i] = std::round(angle(rng) * 1000.0) / 1000.0;
      check.sample.emplace_back(robot.coordinates[i].name(), q[i]);
    }
    std::vector<sym::Expr> outputs;
    for (const sym::Expr component : gap) outputs.push_back(sym::substitute(component, constants));
    const sym::CompiledFunction f(outputs, robot.coordinates);
    const std::vector<double> r = f(q);
    check.residual = {r[0], r[1], r[2]};
    out.push_back(std::move(check));
  }
  return out;
}

}  // namespace dyncc::kin
