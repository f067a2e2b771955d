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

// The value of a standard parameter: its symbol, or what the caller substitutes for it.
Expr parameter_value(const DynamicModel& model, std::span<const Expr> values, int index) {
  if (index < 0) return Expr(0);
  const auto i = static_cast<std::size_t>(index);
  return values.empty() ? model.params.list[i].symbol : values[i];
}

Vec3 bind3(sym::Bindings* bindings, const Vec3& v) {
  if (bindings == nullptr) return v;
  return {bindings->bind(v[0]), bindings->bind(v[1]), bindings->bind(v[2])};
}

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
      L.w = bind3(in.bindings, w_in);
      L.wd = bind3(in.bindings, wd_in);
      L.a = bind3(in.bindings, kin::transpose_times(L.rotation, ao));
      continue;
    }
    L.w = bind3(in.bindings, add3(w_in, scale(rate, L.axis)));
    L.wd = bind3(in.bindings, add3(add3(wd_in, scale(acceleration, L.axis)), kin::cross(w_in, scale(rate, L.axis))));
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
    L.a = bind3(in.bindings, L.a);
  }

  // ---- inward: force f and moment n (about the link origin) the parent exerts on each link
  std::vector<Vec3> f(count, zero), moment(count, zero);
  std::vector<Expr> tau(n, Expr(0));
  for (std::size_t i = count; i-- > 0;) {
    const LinkMotion& L = links[i];
    const auto& of = model.params.of_link[i];
    auto P = [&](StandardKind kind) {
      return parameter_value(model, in.parameters, of[static_cast<std::size_t>(kind)]);
    };
    const Expr mass = P(StandardKind::M);
    const Vec3 h = {P(StandardKind::MX), P(StandardKind::MY), P(StandardKind::MZ)};
    const Mat3 inertia = {Vec3{P(StandardKind::XX), P(StandardKind::XY), P(StandardKind::XZ)},
                          Vec3{P(StandardKind::XY), P(StandardKind::YY), P(StandardKind::YZ)},
                          Vec3{P(StandardKind::XZ), P(StandardKind::YZ), P(StandardKind::ZZ)}};
    // F = m a + wd x h + w x (w x h);  N = I wd + w x (I w) + h x a
    const Vec3 F = add3(add3(scale(mass, L.a), kin::cross(L.wd, h)), kin::cross(L.w, kin::cross(L.w, h)));
    const Vec3 N = add3(add3(times(inertia, L.wd), kin::cross(L.w, times(inertia, L.w))), kin::cross(h, L.a));
    f[i] = bind3(in.bindings, add3(f[i], F));
    moment[i] = bind3(in.bindings, add3(moment[i], N));
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
  for (std::size_t k = 0; k < n; ++k) {
    tau[k] += parameter_value(model, in.parameters, model.params.rotor_of[k]) * in.qdd[k];
  }
  return tau;
}

namespace {

// A link's frame relative to its parent and its joint, for the composite-rigid-body algorithm.
struct LinkJoint {
  Mat3 rotation;  // link -> parent
  Vec3 origin;    // link origin in parent coordinates
  Vec3 axis;      // joint axis, link coordinates
  Vec3 lever;     // from the point the joint turns about to the link origin, link coordinates
  bool prismatic = false;
  std::vector<Expr> coefficient;
};

// [a]x [b]x applied to v, i.e. a x (b x v).
Vec3 cross_cross(const Vec3& a, const Vec3& b, const Vec3& v) { return kin::cross(a, kin::cross(b, v)); }

// Inertia about the parent's origin, in parent axes, of a body with mass m, first moment h
// and inertia I about its own origin (own axes), whose origin sits at p:  R I R^T - m [p]x^2
// - [p]x [h']x - [h']x [p]x with h' = R h. Built column by column from unit vectors.
Mat3 shifted_inertia(const Mat3& R, const Mat3& I, Expr m, const Vec3& h_parent, const Vec3& p) {
  Mat3 out;
  for (std::size_t col = 0; col < 3; ++col) {
    Vec3 e = kin::zero_vec();
    e[col] = Expr(1);
    const Vec3 rotated = times(R, times(I, kin::transpose_times(R, e)));
    const Vec3 column = kin::operator-(kin::operator-(kin::operator-(rotated, scale(m, cross_cross(p, p, e))),
                                                      cross_cross(p, h_parent, e)),
                                       cross_cross(h_parent, p, e));
    for (std::size_t row = 0; row < 3; ++row) out[row][col] = column[row];
  }
  return out;
}

Expr joint_force(const LinkJoint& J, const Vec3& F, const Vec3& N) {
  if (J.prismatic) return kin::dot(J.axis, F);
  return kin::dot(J.axis, add3(N, kin::cross(J.lever, F)));
}

}  // namespace

std::optional<Matrix> composite_rigid_body_mass_matrix(const robot::RobotDescription& robot, const DynamicModel& model,
                                                       std::span<const Expr> parameters, sym::Bindings* bindings) {
  const std::size_t n = model.q.size();
  const std::size_t count = robot.links.size();
  const sym::Substitution constants = robot.constant_values();
  std::vector<LinkJoint> joints(count);
  std::vector<Expr> mass(count);
  std::vector<Vec3> moment(count);
  std::vector<Mat3> inertia(count);
  for (std::size_t i = 0; i < count; ++i) {
    const robot::Link& link = robot.links[i];
    LinkJoint& J = joints[i];
    J.prismatic = link.joint == robot::JointType::Prismatic;
    const Expr variable = sym::substitute(J.prismatic ? link.d : link.theta, constants);
    for (std::size_t k = 0; k < n; ++k) {
      const Expr c = sym::diff(variable, model.q[k]);
      if (!c.is_number()) return std::nullopt;
      J.coefficient.push_back(c);
    }
    const kin::RelativeFrame rel =
        kin::dh_frame(robot.convention, sym::substitute(link.a, constants), sym::substitute(link.alpha, constants),
                      sym::substitute(link.d, constants), sym::substitute(link.theta, constants));
    J.rotation = rel.rotation;
    J.origin = rel.origin;
    J.axis = kin::transpose_times(rel.rotation, rel.joint_axis);
    J.lever = rel.axis_through_child_origin ? kin::zero_vec() : kin::transpose_times(rel.rotation, rel.origin);
    const auto& of = model.params.of_link[i];
    auto P = [&](StandardKind kind) { return parameter_value(model, parameters, of[static_cast<std::size_t>(kind)]); };
    mass[i] = P(StandardKind::M);
    moment[i] = {P(StandardKind::MX), P(StandardKind::MY), P(StandardKind::MZ)};
    inertia[i] = {Vec3{P(StandardKind::XX), P(StandardKind::XY), P(StandardKind::XZ)},
                  Vec3{P(StandardKind::XY), P(StandardKind::YY), P(StandardKind::YZ)},
                  Vec3{P(StandardKind::XZ), P(StandardKind::YZ), P(StandardKind::ZZ)}};
  }
  // ---- composite bodies, leaf to root (children come after their parents)
  for (std::size_t i = count; i-- > 0;) {
    const int parent = robot.links[i].parent;
    if (parent < 0) continue;
    const auto p = static_cast<std::size_t>(parent);
    const LinkJoint& J = joints[i];
    const Vec3 h_parent = times(J.rotation, moment[i]);
    const Mat3 shifted = shifted_inertia(J.rotation, inertia[i], mass[i], h_parent, J.origin);
    for (std::size_t r = 0; r < 3; ++r) {
      for (std::size_t c = 0; c < 3; ++c) inertia[p][r][c] += shifted[r][c];
    }
    moment[p] = add3(moment[p], add3(scale(mass[i], J.origin), h_parent));
    mass[p] += mass[i];
    // The parent's composite body is complete once its last child is added; binding every
    // accumulation is simpler and costs nothing extra.
    moment[p] = bind3(bindings, moment[p]);
    for (std::size_t r = 0; r < 3; ++r) inertia[p][r] = bind3(bindings, inertia[p][r]);
    if (bindings != nullptr) mass[p] = bindings->bind(mass[p]);
  }
  // ---- H_tree[k][j]: the force a unit acceleration of joint j needs, at every ancestor k
  std::vector<std::vector<Expr>> tree(count, std::vector<Expr>(count, Expr(0)));
  for (std::size_t j = 0; j < count; ++j) {
    const LinkJoint& J = joints[j];
    // Unit joint acceleration of the composite body j, at rest: angular z (revolute) and
    // linear acceleration of the origin z x lever, or linear z (prismatic).
    const Vec3 angular = J.prismatic ? kin::zero_vec() : J.axis;
    const Vec3 linear = J.prismatic ? J.axis : kin::cross(J.axis, J.lever);
    Vec3 F = add3(scale(mass[j], linear), kin::cross(angular, moment[j]));
    Vec3 N = add3(times(inertia[j], angular), kin::cross(moment[j], linear));
    F = bind3(bindings, F);
    N = bind3(bindings, N);
    tree[j][j] = joint_force(J, F, N);
    for (std::size_t k = j; robot.links[k].parent >= 0;) {
      const LinkJoint& child = joints[k];
      const Vec3 F_parent = bind3(bindings, times(child.rotation, F));
      N = bind3(bindings, add3(times(child.rotation, N), kin::cross(child.origin, F_parent)));
      F = F_parent;
      k = static_cast<std::size_t>(robot.links[k].parent);
      tree[k][j] = joint_force(joints[k], F, N);
      tree[j][k] = tree[k][j];
    }
  }
  // ---- onto the coordinates: H = G^T H_tree G + rotor inertias
  Matrix H(n, std::vector<Expr>(n, Expr(0)));
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a; b < n; ++b) {
      Expr sum(0);
      for (std::size_t k = 0; k < count; ++k) {
        if (joints[k].coefficient[a].is_zero()) continue;
        for (std::size_t j = 0; j < count; ++j) {
          if (joints[j].coefficient[b].is_zero() || tree[k][j].is_zero()) continue;
          sum += joints[k].coefficient[a] * joints[j].coefficient[b] * tree[k][j];
        }
      }
      if (a == b) sum += parameter_value(model, parameters, model.params.rotor_of[a]);
      H[a][b] = sum;
      H[b][a] = sum;
    }
  }
  return H;
}

}  // namespace dyncc::dyn
