#include "eigen_rbd.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace dyncc::bench {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using RowMajorMap = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;

/// |r|^2 1 - r r^T = -[r]x [r]x: a unit point mass at r, about the origin.
Matrix3d point_inertia(const Vector3d& r) { return r.squaredNorm() * Matrix3d::Identity() - r * r.transpose(); }

/// -([a]x [b]x + [b]x [a]x) = 2 (a.b) 1 - a b^T - b a^T
Matrix3d cross_pair(const Vector3d& a, const Vector3d& b) {
  return 2.0 * a.dot(b) * Matrix3d::Identity() - a * b.transpose() - b * a.transpose();
}

/// R * RotZ(angle), with the rotation about z applied to R's first two columns only.
Matrix3d times_rot_z(const Matrix3d& r, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Matrix3d out;
  out.col(0) = c * r.col(0) + s * r.col(1);
  out.col(1) = -s * r.col(0) + c * r.col(1);
  out.col(2) = r.col(2);
  return out;
}

}  // namespace

EigenRbd::EigenRbd(RigidBodyTree tree) : tree_(std::move(tree)) {
  const std::size_t nb = tree_.bodies.size();
  int joints = 0;
  for (const RigidBody& b : tree_.bodies) joint_of_.push_back(b.joint == JointKind::Fixed ? -1 : joints++);
  if (tree_.coupling.rows() != joints) throw std::invalid_argument("EigenRbd: coupling needs one row per joint");
  if (tree_.armature.size() != tree_.coupling.cols()) tree_.armature = Eigen::VectorXd::Zero(tree_.coupling.cols());
  identity_coupling_ = tree_.coupling.rows() == tree_.coupling.cols() && tree_.coupling.isIdentity(0.0);
  // A body's own first moment and inertia about its origin are constant: computed once.
  for (const RigidBody& b : tree_.bodies) {
    first_moment_.emplace_back(b.mass * b.com);
    inertia_at_origin_.emplace_back(b.inertia + b.mass * point_inertia(b.com));
  }
  rotation_.resize(nb);
  offset_.resize(nb);
  omega_.resize(nb);
  omega_dot_.resize(nb);
  accel_.resize(nb);
  force_.resize(nb);
  moment_.resize(nb);
  composite_mass_.resize(nb);
  composite_first_moment_.resize(nb);
  composite_inertia_.resize(nb);
  q_joint_.resize(joints);
  qd_joint_.resize(joints);
  qdd_joint_.resize(joints);
  tau_joint_.resize(joints);
  m_joint_.resize(joints, joints);
  m_times_coupling_.resize(joints, tree_.coupling.cols());
  zeros_.resize(tree_.coupling.cols());
}

void EigenRbd::place_bodies(const Eigen::VectorXd& joint_q) {
  for (std::size_t i = 0; i < tree_.bodies.size(); ++i) {
    const RigidBody& b = tree_.bodies[i];
    const int j = joint_of_[i];
    rotation_[i] = b.joint == JointKind::Revolute ? times_rot_z(b.rotation, joint_q[j]) : b.rotation;
    offset_[i] = b.joint == JointKind::Prismatic ? Vector3d(b.position + joint_q[j] * b.rotation.col(2)) : b.position;
  }
}

// CRBA: composite inertias from the leaves down, then each joint's unit motion is carried to its
// ancestors as a force, whose components along their axes fill one column of M.
void EigenRbd::joint_mass_matrix() {
  const std::size_t nb = tree_.bodies.size();
  for (std::size_t i = 0; i < nb; ++i) {
    composite_mass_[i] = tree_.bodies[i].mass;
    composite_first_moment_[i] = first_moment_[i];
    composite_inertia_[i] = inertia_at_origin_[i];
  }
  for (std::size_t i = nb; i-- > 0;) {
    const int p = tree_.bodies[i].parent;
    if (p < 0) continue;
    const Matrix3d& e = rotation_[i];
    const Vector3d& r = offset_[i];
    const double m = composite_mass_[i];
    const Vector3d h = e * composite_first_moment_[i];  // about body i's origin, parent axes
    const auto pu = static_cast<std::size_t>(p);
    composite_mass_[pu] += m;
    composite_first_moment_[pu] += h + m * r;
    composite_inertia_[pu] += e * composite_inertia_[i] * e.transpose() + m * point_inertia(r) + cross_pair(r, h);
  }
  // Joints on different branches of a tree do not couple: their entries stay 0.
  if (!identity_coupling_) m_joint_.setZero();
  for (std::size_t i = 0; i < nb; ++i) {
    const int j = joint_of_[i];
    if (j < 0) continue;
    const Vector3d z = Vector3d::UnitZ();
    Vector3d f, n;  // force and moment about the body origin for a unit joint rate
    if (tree_.bodies[i].joint == JointKind::Revolute) {
      f = z.cross(composite_first_moment_[i]);
      n = composite_inertia_[i] * z;
    } else {
      f = composite_mass_[i] * z;
      n = composite_first_moment_[i].cross(z);
    }
    m_joint_(j, j) = tree_.bodies[i].joint == JointKind::Revolute ? n.z() : f.z();
    for (std::size_t k = i; tree_.bodies[k].parent >= 0;) {
      f = rotation_[k] * f;
      n = rotation_[k] * n + offset_[k].cross(f);
      k = static_cast<std::size_t>(tree_.bodies[k].parent);
      const int jk = joint_of_[k];
      if (jk < 0) continue;
      m_joint_(jk, j) = m_joint_(j, jk) = tree_.bodies[k].joint == JointKind::Revolute ? n.z() : f.z();
    }
  }
}

// RNEA: velocities and accelerations from the base out (gravity as an upward base acceleration),
// forces and moments back in; a joint's torque is the moment (force) along its axis.
void EigenRbd::joint_inverse_dynamics(const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) {
  const std::size_t nb = tree_.bodies.size();
  const Vector3d z = Vector3d::UnitZ();
  for (std::size_t i = 0; i < nb; ++i) {
    const RigidBody& b = tree_.bodies[i];
    const int p = b.parent;
    const Matrix3d& e = rotation_[i];
    const Vector3d& r = offset_[i];
    Vector3d w_p = Vector3d::Zero(), wd_p = Vector3d::Zero(), a_p = -tree_.gravity;
    if (p >= 0) {
      const auto pu = static_cast<std::size_t>(p);
      w_p = omega_[pu];
      wd_p = omega_dot_[pu];
      a_p = accel_[pu];
    }
    const Vector3d w_in = e.transpose() * w_p;
    Vector3d a = e.transpose() * (a_p + wd_p.cross(r) + w_p.cross(w_p.cross(r)));
    Vector3d w = w_in, wd = e.transpose() * wd_p;
    const int j = joint_of_[i];
    if (b.joint == JointKind::Revolute) {
      w += qd[j] * z;
      wd += qdd[j] * z + w_in.cross(qd[j] * z);
    } else if (b.joint == JointKind::Prismatic) {
      a += qdd[j] * z + 2.0 * w.cross(qd[j] * z);
    }
    omega_[i] = w;
    omega_dot_[i] = wd;
    accel_[i] = a;
    const Vector3d a_com = a + wd.cross(b.com) + w.cross(w.cross(b.com));
    force_[i] = b.mass * a_com;
    moment_[i] = b.inertia * wd + w.cross(b.inertia * w) + b.com.cross(force_[i]);
  }
  for (std::size_t i = nb; i-- > 0;) {
    const RigidBody& b = tree_.bodies[i];
    const int j = joint_of_[i];
    if (j >= 0) tau_joint_[j] = b.joint == JointKind::Revolute ? moment_[i].z() : force_[i].z();
    if (b.parent < 0) continue;
    const auto pu = static_cast<std::size_t>(b.parent);
    const Vector3d f = rotation_[i] * force_[i];
    force_[pu] += f;
    moment_[pu] += rotation_[i] * moment_[i] + offset_[i].cross(f);
  }
}

void EigenRbd::mass_matrix(const double* q, double* H) {
  const auto n = tree_.coupling.cols();
  const Eigen::Map<const Eigen::VectorXd> q_map(q, n);
  if (identity_coupling_) {
    q_joint_ = q_map;
  } else {
    q_joint_.noalias() = tree_.coupling * q_map;
  }
  place_bodies(q_joint_);
  joint_mass_matrix();
  RowMajorMap h(H, n, n);
  if (identity_coupling_) {
    h = m_joint_;
  } else {
    m_times_coupling_.noalias() = m_joint_ * tree_.coupling;
    h.noalias() = tree_.coupling.transpose() * m_times_coupling_;
  }
  h.diagonal() += tree_.armature;
}

void EigenRbd::inverse_dynamics(const double* q, const double* qd, const double* qdd, double* tau) {
  const auto n = tree_.coupling.cols();
  const Eigen::Map<const Eigen::VectorXd> q_map(q, n), qd_map(qd, n), qdd_map(qdd, n);
  if (identity_coupling_) {
    q_joint_ = q_map;
    qd_joint_ = qd_map;
    qdd_joint_ = qdd_map;
  } else {
    q_joint_.noalias() = tree_.coupling * q_map;
    qd_joint_.noalias() = tree_.coupling * qd_map;
    qdd_joint_.noalias() = tree_.coupling * qdd_map;
  }
  place_bodies(q_joint_);
  joint_inverse_dynamics(qd_joint_, qdd_joint_);
  Eigen::Map<Eigen::VectorXd> out(tau, n);
  if (identity_coupling_) {
    out = tau_joint_;
  } else {
    out.noalias() = tree_.coupling.transpose() * tau_joint_;
  }
  out += tree_.armature.cwiseProduct(qdd_map);
}

void EigenRbd::gravity_torque(const double* q, double* g) {
  zeros_.setZero();
  inverse_dynamics(q, zeros_.data(), zeros_.data(), g);
}

}  // namespace dyncc::bench
