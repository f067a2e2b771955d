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

// A link's frame relative to its parent and its joint, shared by both recursions.
struct LinkJoint {
  Mat3 rotation;     // link -> parent
  Vec3 origin;       // link origin in parent coordinates
  Vec3 axis;         // joint axis, link coordinates
  Vec3 parent_axis;  // joint axis, parent coordinates
  Vec3 lever;        // from the point the joint turns about to the link origin, link coordinates
  bool prismatic = false;
  bool axis_through_origin = true;  // modified D-H; standard D-H turns about the parent's origin
  std::vector<Expr> coefficient;    // d(joint variable)/d(q_k), numbers
};

// Every link's joint, or nullopt when a joint variable is not affine in the coordinates.
std::optional<std::vector<LinkJoint>> link_joints(const robot::RobotDescription& robot, const DynamicModel& model) {
  const sym::Substitution constants = robot.constant_values();
  std::vector<LinkJoint> joints(robot.links.size());
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    const robot::Link& link = robot.links[i];
    LinkJoint& J = joints[i];
    J.prismatic = link.joint == robot::JointType::Prismatic;
    const Expr variable = sym::substitute(J.prismatic ? link.d : link.theta, constants);
    for (const Expr q : model.q) {
      const Expr c = sym::diff(variable, q);
      if (!c.is_number()) return std::nullopt;
      J.coefficient.push_back(c);
    }
    const kin::RelativeFrame rel =
        kin::dh_frame(robot.convention, sym::substitute(link.a, constants), sym::substitute(link.alpha, constants),
                      sym::substitute(link.d, constants), sym::substitute(link.theta, constants));
    J.rotation = rel.rotation;
    J.origin = rel.origin;
    J.axis = kin::transpose_times(rel.rotation, rel.joint_axis);
    J.parent_axis = rel.joint_axis;
    J.axis_through_origin = rel.axis_through_child_origin;
    J.lever = rel.axis_through_child_origin ? kin::zero_vec() : kin::transpose_times(rel.rotation, rel.origin);
  }
  return joints;
}

// The value of a standard parameter: its symbol, or what the caller substitutes for it.
Expr parameter_value(const DynamicModel& model, std::span<const Expr> values, int index) {
  if (index < 0) return Expr(0);
  const auto i = static_cast<std::size_t>(index);
  return values.empty() ? model.params.list[i].symbol : values[i];
}

// A link's mass, first moment and inertia about its origin, in the given parameter values.
struct LinkInertia {
  Expr mass;
  Vec3 moment;
  Mat3 inertia;
};

LinkInertia link_inertia(const DynamicModel& model, std::span<const Expr> values, std::size_t link) {
  const auto& of = model.params.of_link[link];
  auto P = [&](StandardKind kind) { return parameter_value(model, values, of[static_cast<std::size_t>(kind)]); };
  return {P(StandardKind::M),
          {P(StandardKind::MX), P(StandardKind::MY), P(StandardKind::MZ)},
          {Vec3{P(StandardKind::XX), P(StandardKind::XY), P(StandardKind::XZ)},
           Vec3{P(StandardKind::XY), P(StandardKind::YY), P(StandardKind::YZ)},
           Vec3{P(StandardKind::XZ), P(StandardKind::YZ), P(StandardKind::ZZ)}}};
}

// The generalised force of a joint from the force F and moment N (about the link origin) on
// its link: the force along the axis, or the moment about the axis line.
Expr joint_force(const LinkJoint& J, const Vec3& F, const Vec3& N) {
  if (J.prismatic) return kin::dot(J.axis, F);
  return kin::dot(J.axis, add3(N, kin::cross(J.lever, F)));
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
  const auto joints = link_joints(robot, model);
  if (!joints) return std::nullopt;  // not affine: no Newton-Euler form
  struct Motion {
    Vec3 w, wd, a;  // angular velocity, angular acceleration, acceleration of the origin
  };
  std::vector<Motion> links(count);

  const Vec3 zero = kin::zero_vec();
  Vec3 base_acceleration = zero;
  if (in.gravity) {
    for (std::size_t c = 0; c < 3; ++c) base_acceleration[c] = -robot.gravity[c];
  }

  // ---- outward: velocities and accelerations, parent before child
  for (std::size_t i = 0; i < count; ++i) {
    const LinkJoint& J = (*joints)[i];
    Motion& L = links[i];
    Expr rate(0), acceleration(0);
    for (std::size_t k = 0; k < n; ++k) {
      rate += J.coefficient[k] * in.qd[k];
      acceleration += J.coefficient[k] * in.qdd[k];
    }
    const int parent_index = robot.links[i].parent;
    const Motion* parent = parent_index < 0 ? nullptr : &links[static_cast<std::size_t>(parent_index)];
    const Vec3& wp = parent == nullptr ? zero : parent->w;
    const Vec3& wdp = parent == nullptr ? zero : parent->wd;
    const Vec3& ap = parent == nullptr ? base_acceleration : parent->a;
    const Vec3 w_in = kin::transpose_times(J.rotation, wp);    // parent's rotation, in this frame
    const Vec3 wd_in = kin::transpose_times(J.rotation, wdp);  // parent's angular acceleration, here
    if (J.prismatic) {
      // a = R^T (a_p + wd_p x p + w_p x (w_p x p) + 2 w_p x (rate z_p) + acc z_p)
      const Vec3 p = J.origin;
      Vec3 ao = add3(add3(ap, kin::cross(wdp, p)), kin::cross(wp, kin::cross(wp, p)));
      ao = add3(ao,
                add3(scale(Expr(2), kin::cross(wp, scale(rate, J.parent_axis))), scale(acceleration, J.parent_axis)));
      L.w = bind3(in.bindings, w_in);
      L.wd = bind3(in.bindings, wd_in);
      L.a = bind3(in.bindings, kin::transpose_times(J.rotation, ao));
      continue;
    }
    L.w = bind3(in.bindings, add3(w_in, scale(rate, J.axis)));
    L.wd = bind3(in.bindings, add3(add3(wd_in, scale(acceleration, J.axis)), kin::cross(w_in, scale(rate, J.axis))));
    if (J.axis_through_origin) {
      // The origin is on the axis: its acceleration as a point of the parent.
      const Vec3 p = J.origin;
      L.a = kin::transpose_times(J.rotation, add3(add3(ap, kin::cross(wdp, p)), kin::cross(wp, kin::cross(wp, p))));
    } else {
      // The axis passes through the parent's origin (a point of both bodies); the origin is
      // carried round it by this link's own motion.
      const Vec3& r = J.lever;
      L.a = add3(add3(kin::transpose_times(J.rotation, ap), kin::cross(L.wd, r)), kin::cross(L.w, kin::cross(L.w, r)));
    }
    L.a = bind3(in.bindings, L.a);
  }

  // ---- inward: force f and moment n (about the link origin) the parent exerts on each link
  std::vector<Vec3> f(count, zero), moment(count, zero);
  std::vector<Expr> tau(n, Expr(0));
  for (std::size_t i = count; i-- > 0;) {
    const LinkJoint& J = (*joints)[i];
    const Motion& L = links[i];
    const auto [mass, h, inertia] = link_inertia(model, in.parameters, i);
    // F = m a + wd x h + w x (w x h);  N = I wd + w x (I w) + h x a
    const Vec3 F = add3(add3(scale(mass, L.a), kin::cross(L.wd, h)), kin::cross(L.w, kin::cross(L.w, h)));
    const Vec3 N = add3(add3(times(inertia, L.wd), kin::cross(L.w, times(inertia, L.w))), kin::cross(h, L.a));
    f[i] = bind3(in.bindings, add3(f[i], F));
    moment[i] = bind3(in.bindings, add3(moment[i], N));
    const Expr joint = joint_force(J, f[i], moment[i]);
    for (std::size_t k = 0; k < n; ++k) {
      if (!J.coefficient[k].is_zero()) tau[k] += J.coefficient[k] * joint;
    }
    const int parent = robot.links[i].parent;
    if (parent >= 0) {
      const auto p = static_cast<std::size_t>(parent);
      const Vec3 f_parent = times(J.rotation, f[i]);
      f[p] = add3(f[p], f_parent);
      moment[p] = add3(moment[p], add3(times(J.rotation, moment[i]), kin::cross(J.origin, f_parent)));
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    tau[k] += parameter_value(model, in.parameters, model.params.rotor_of[k]) * in.qdd[k];
  }
  return tau;
}

namespace {

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

}  // namespace

std::optional<Matrix> composite_rigid_body_mass_matrix(const robot::RobotDescription& robot, const DynamicModel& model,
                                                       std::span<const Expr> parameters, sym::Bindings* bindings) {
  const std::size_t n = model.q.size();
  const std::size_t count = robot.links.size();
  const auto found = link_joints(robot, model);
  if (!found) return std::nullopt;
  const std::vector<LinkJoint>& joints = *found;
  std::vector<Expr> mass(count);
  std::vector<Vec3> moment(count);
  std::vector<Mat3> inertia(count);
  for (std::size_t i = 0; i < count; ++i) {
    const LinkInertia own = link_inertia(model, parameters, i);
    mass[i] = own.mass;
    moment[i] = own.moment;
    inertia[i] = own.inertia;
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
