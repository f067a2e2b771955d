// Baseline for the speed comparison: textbook rigid-body algorithms in plain Eigen, the way a
// hand-written dynamics library computes them numerically at run time.
//   mass_matrix:       composite rigid body algorithm (CRBA)
//   inverse_dynamics:  recursive Newton-Euler (RNEA), gravity included
//   gravity_torque:    RNEA at zero velocity and acceleration
// Everything is in body frames with 3-vectors (no spatial 6-vectors), fixed-size Eigen types and
// workspaces allocated once, so a call allocates nothing.
//
// The tree may have more joints than the robot has coordinates (a closed chain such as the
// Kraft arm's parallelogram, cut into a tree): joint positions, velocities and accelerations are
// `coupling` times the coordinate ones (constant: joint variables are affine in the
// coordinates), and results are projected back, H = G^T M G and tau = G^T tau_joints, which is
// exact because the loop constraints are then satisfied identically. For an open chain G is the
// identity and the projection is skipped.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace dyncc::bench {

enum class JointKind { Revolute, Prismatic, Fixed };

/// One body of the tree. Its joint turns about, or slides along, the body's own z axis through
/// its origin; the body frame's pose in the parent frame at joint value 0 is fixed.
struct RigidBody {
  int parent = -1;  // index of an earlier body; -1 = fixed base
  JointKind joint = JointKind::Revolute;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // body frame in the parent frame, joint at 0
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      // body frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centre of mass, body axes
};

struct RigidBodyTree {
  std::vector<RigidBody> bodies;                      // parents before children
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // base frame
  Eigen::MatrixXd coupling;  // (joints x coordinates): joint values = coupling * q; joints in body order
  Eigen::VectorXd armature;  // per coordinate: reflected rotor inertia, added to H's diagonal
};

class EigenRbd {
 public:
  explicit EigenRbd(RigidBodyTree tree);

  [[nodiscard]] int dof() const { return static_cast<int>(tree_.coupling.cols()); }
  [[nodiscard]] const RigidBodyTree& tree() const { return tree_; }

  /// H (dof x dof, row-major; symmetric) at q.
  void mass_matrix(const double* q, double* H);
  /// tau = H(q) qdd + C(q, qd) qd + g(q).
  void inverse_dynamics(const double* q, const double* qd, const double* qdd, double* tau);
  /// g(q) = tau at qd = qdd = 0.
  void gravity_torque(const double* q, double* g);

 private:
  void place_bodies(const Eigen::VectorXd& joint_q);  // rotation_[i], offset_[i] from joint values
  void joint_mass_matrix();                           // CRBA into m_joint_
  void joint_inverse_dynamics(const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd);  // RNEA into tau_joint_

  RigidBodyTree tree_;
  bool identity_coupling_ = false;
  std::vector<int> joint_of_;                       // per body: index of its joint, -1 when fixed
  std::vector<Eigen::Vector3d> first_moment_;       // per body: mass * centre of mass
  std::vector<Eigen::Matrix3d> inertia_at_origin_;  // per body: about the body origin
  // Workspaces, per body: pose in the parent frame at the current q, velocities, composite
  // inertias (mass, first moment and inertia about the body origin), and forces.
  std::vector<Eigen::Matrix3d> rotation_;
  std::vector<Eigen::Vector3d> offset_;
  std::vector<Eigen::Vector3d> omega_, omega_dot_, accel_, force_, moment_;
  std::vector<double> composite_mass_;
  std::vector<Eigen::Vector3d> composite_first_moment_;
  std::vector<Eigen::Matrix3d> composite_inertia_;
  Eigen::VectorXd q_joint_, qd_joint_, qdd_joint_, tau_joint_, zeros_;
  Eigen::MatrixXd m_joint_, m_times_coupling_;
};

}  // namespace dyncc::bench
