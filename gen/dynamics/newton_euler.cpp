#include "dynamics/newton_euler.hpp"

#include "kinematics/kinematics.hpp"
#include "sym/diff.hpp"
#include "sym/substitute.hpp"

namespace dyncc::dyn {
namespace {

using kin::Mat3;
using kin::Vec3;
using sym::Expr;

Vec3 add3(const Vec3& a, const Vec3& b) { return kin::operator+(a, b); }
Vec3 scale(Expr s, const Vec3& v) { return kin::operator*(s, v); }
Vec3 times(const Mat3& m, const Vec3& v) { return kin::operator*(m, v); }

// Link i's motion in its own coordinates.
struct LinkMotion {
  Mat3 rotation;  // this link's frame -> parent's frame
  Vec3 origin;    // this link's origin in the parent's frame
  Vec3 axis;      // joint axis in this link's coordinates
  Vec3 w, wd, a;  // angular velocity, angular acceleration, acceleration of the origin
  bool prismatic = false;
  bool axis_through_origin = true;  // modified D-H; standard D-H turns about the parent's origin
  std::vector<Expr> coefficient;    // d(joint variable)/d(q_k), numbers
};

}  // namespace

std::optional<std::vector<Expr>> newton_euler_torque(const robot::RobotDescription& robot, const DynamicModel& model,
                                                     const NewtonEulerInputs& in) {
  const std::size_t n = model.q.size();
  const std::size_t count = robot.links.size();
  const sym::Substitution constants = robot.constant_values();
  std::vector<LinkMotion> links(count);

  const Vec3 zero = kin::zero_vec();
  Vec3 base_acceleration = zero;
  if (in.gravity) {
    for (std::size_t c = 0; c < 3; ++c) base_acceleration[c] = -robot.gravity[c];
  }

  // ---- outward: velocities and accelerations, parent before child
  for (std::size_t i = 0; i < count; ++i) {
    const robot::Link& link = robot.links[i];
    LinkMotion& L = links[i];
    L.prismatic = link.joint == robot::JointType::Prismatic;
    const Expr variable = sym::substitute(L.prismatic ? link.d : link.theta, constants);
    Expr rate(0), acceleration(0);
    for (std::size_t k = 0; k < n; ++k) {
      const Expr c = sym::diff(variable, model.q[k]);
      if (!c.is_number()) return std::nullopt;  // not affine: no Newton-Euler form
      L.coefficient.push_back(c);
      rate += c * in.qd[k];
      acceleration += c * in.qdd[k];
    }
    const kin::RelativeFrame rel =
        kin::dh_frame(robot.convention, sym::substitute(link.a, constants), sym::substitute(link.alpha, constants),
                      sym::substitute(link.d, constants), sym::substitute(link.theta, constants));
    L.rotation = rel.rotation;
    L.origin = rel.origin;
    L.axis_through_origin = rel.axis_through_child_origin;
    L.axis = kin::transpose_times(rel.rotation, rel.joint_axis);

    const bool root = link.parent < 0;
    const LinkMotion* parent = root ? nullptr : &links[static_cast<std::size_t>(link.parent)];
    const Vec3& wp = root ? zero : parent->w;
    const Vec3& wdp = root ? zero : parent->wd;
    const Vec3& ap = root ? base_acceleration : parent->a;
    const Vec3 w_in = kin::transpose_times(L.rotation, wp);    // parent's rotation, in this frame
    const Vec3 wd_in = kin::transpose_times(L.rotation, wdp);  // parent's angular acceleration, here
    if (L.prismatic) {
      // a = R^T (a_p + wd_p x p + w_p x (w_p x p) + 2 w_p x (rate z_p) + acc z_p)
      const Vec3 p = L.origin;
      Vec3 ao = add3(add3(ap, kin::cross(wdp, p)), kin::cross(wp, kin::cross(wp, p)));
      ao = add3(ao,
                add3(scale(Expr(2), kin::cross(wp, scale(rate, rel.joint_axis))), scale(acceleration, rel.joint_axis)));
      L.w = w_in;
      L.wd = wd_in;
      L.a = kin::transpose_times(L.rotation, ao);
      continue;
    }
    L.w = add3(w_in, scale(rate, L.axis));
    L.wd = add3(add3(wd_in, scale(acceleration, L.axis)), kin::cross(w_in, scale(rate, L.axis)));
    if (L.axis_through_origin) {
      // The origin is on the axis: its acceleration as a point of the parent.
      const Vec3 p = L.origin;
      L.a = kin::transpose_times(L.rotation, add3(add3(ap, kin::cross(wdp, p)), kin::cross(wp, kin::cross(wp, p))));
    } else {
      // The axis passes through the parent's origin (a point of both bodies); the origin is
      // carried round it by this link's own motion.
      const Vec3 r = kin::transpose_times(L.rotation, L.origin);
      L.a = add3(add3(kin::transpose_times(L.rotation, ap), kin::cross(L.wd, r)), kin::cross(L.w, kin::cross(L.w, r)));
    }
  }

  // ---- inward: force f and moment n (about the link origin) the parent exerts on each link
  std::vector<Vec3> f(count, zero), moment(count, zero);
  std::vector<Expr> tau(n, Expr(0));
  for (std::size_t i = count; i-- > 0;) {
    const LinkMotion& L = links[i];
    const auto& of = model.params.of_link[i];
    auto P = [&](StandardKind kind) { return model.params.symbol_or_zero(of[static_cast<std::size_t>(kind)]); };
    const Expr mass = P(StandardKind::M);
    const Vec3 h = {P(StandardKind::MX), P(StandardKind::MY), P(StandardKind::MZ)};
    const Mat3 inertia = {Vec3{P(StandardKind::XX), P(StandardKind::XY), P(StandardKind::XZ)},
                          Vec3{P(StandardKind::XY), P(StandardKind::YY), P(StandardKind::YZ)},
                          Vec3{P(StandardKind::XZ), P(StandardKind::YZ), P(StandardKind::ZZ)}};
    // F = m a + wd x h + w x (w x h);  N = I wd + w x (I w) + h x a
    const Vec3 F = add3(add3(scale(mass, L.a), kin::cross(L.wd, h)), kin::cross(L.w, kin::cross(L.w, h)));
    const Vec3 N = add3(add3(times(inertia, L.wd), kin::cross(L.w, times(inertia, L.w))), kin::cross(h, L.a));
    f[i] = add3(f[i], F);
    moment[i] = add3(moment[i], N);
    Expr joint;
    if (L.prismatic) {
      joint = kin::dot(L.axis, f[i]);
    } else if (L.axis_through_origin) {
      joint = kin::dot(L.axis, moment[i]);
    } else {
      const Vec3 r = kin::transpose_times(L.rotation, L.origin);  // from the pivot to this origin
      joint = kin::dot(L.axis, add3(moment[i], kin::cross(r, f[i])));
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (!L.coefficient[k].is_zero()) tau[k] += L.coefficient[k] * joint;
    }
    const int parent = robot.links[i].parent;
    if (parent >= 0) {
      const auto p = static_cast<std::size_t>(parent);
      const Vec3 f_parent = times(L.rotation, f[i]);
      f[p] = add3(f[p], f_parent);
      moment[p] = add3(moment[p], add3(times(L.rotation, moment[i]), kin::cross(L.origin, f_parent)));
    }
  }
  for (std::size_t k = 0; k < n; ++k) tau[k] += model.params.symbol_or_zero(model.params.rotor_of[k]) * in.qdd[k];
  return tau;
}

}  // namespace dyncc::dyn
