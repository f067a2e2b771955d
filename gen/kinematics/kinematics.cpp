#include "kinematics/kinematics.hpp"

#include <stdexcept>

#include "sym/diff.hpp"

namespace dyncc::kin {

RelativeFrame dh_frame(robot::Convention convention, sym::Expr a, sym::Expr alpha, sym::Expr d, sym::Expr theta) {
  using sym::Expr;
  const Expr ca = sym::cos(alpha);
  const Expr sa = sym::sin(alpha);
  const Expr ct = sym::cos(theta);
  const Expr st = sym::sin(theta);
  RelativeFrame f;
  if (convention == robot::Convention::Modified) {
    // T = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i) TransZ(d_i)
    f.rotation = {Vec3{ct, -st, Expr(0)}, Vec3{st * ca, ct * ca, -sa}, Vec3{st * sa, ct * sa, ca}};
    f.origin = {a, -sa * d, ca * d};
    f.joint_axis = {Expr(0), -sa, ca};
    f.axis_through_child_origin = true;
  } else {
    // T = RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i)
    f.rotation = {Vec3{ct, -st * ca, st * sa}, Vec3{st, ct * ca, -ct * sa}, Vec3{Expr(0), sa, ca}};
    f.origin = {a * ct, a * st, d};
    f.joint_axis = {Expr(0), Expr(0), Expr(1)};
    f.axis_through_child_origin = false;
  }
  return f;
}

Kinematics compute_kinematics(const robot::RobotDescription& robot) {
  Kinematics kin;
  kin.coordinates = robot.coordinates;
  const std::size_t n = robot.coordinates.size();
  std::vector<sym::Differentiator> by_coordinate;
  by_coordinate.reserve(n);
  for (const sym::Expr q : robot.coordinates) by_coordinate.emplace_back(q);

  for (const robot::Link& link : robot.links) {
    for (const sym::Expr q : robot.coordinates) {
      if (sym::depends_on(link.a, q) || sym::depends_on(link.alpha, q)) {
        throw std::invalid_argument("link '" + link.name + "': a and alpha must not depend on the coordinates");
      }
    }
    const RelativeFrame rel = dh_frame(robot.convention, link.a, link.alpha, link.d, link.theta);
    const bool has_parent = link.parent >= 0;
    const LinkKinematics* parent = has_parent ? &kin.links[static_cast<std::size_t>(link.parent)] : nullptr;

    LinkKinematics lk;
    lk.rotation = has_parent ? parent->rotation * rel.rotation : rel.rotation;
    lk.origin = has_parent ? parent->origin + parent->rotation * rel.origin : rel.origin;
    lk.angular.resize(n);
    lk.linear.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      // Rates of the joint variables per unit qd_k (the constraint Jacobian entries).
      const sym::Expr theta_rate = by_coordinate[k](link.theta);
      const sym::Expr d_rate = by_coordinate[k](link.d);
      const Vec3 w_parent = has_parent ? parent->angular[k] : zero_vec();
      const Vec3 v_parent = has_parent ? parent->linear[k] : zero_vec();
      // In parent coordinates: omega_child = omega_parent + theta_rate * axis.
      const Vec3 w_child_p = w_parent + theta_rate * rel.joint_axis;
      // Origin velocity: the rotation's pivot is the child origin (modified) or the parent
      // origin (standard), so the lever arm r turns with omega_parent or omega_child.
      const Vec3& w_pivot = rel.axis_through_child_origin ? w_parent : w_child_p;
      const Vec3 v_child_p = v_parent + cross(w_pivot, rel.origin) + d_rate * rel.joint_axis;
      lk.angular[k] = transpose_times(rel.rotation, w_child_p);
      lk.linear[k] = transpose_times(rel.rotation, v_child_p);
    }
    kin.links.push_back(std::move(lk));
  }
  return kin;
}

Vec3 point_in_base(const Kinematics& kin, int link, const Vec3& local) {
  if (link < 0) return local;
  const LinkKinematics& lk = kin.links[static_cast<std::size_t>(link)];
  return lk.origin + lk.rotation * local;
}

}  // namespace dyncc::kin
