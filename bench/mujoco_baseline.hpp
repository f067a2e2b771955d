// Baseline for the speed comparison: MuJoCo (2.2, the Debian package) on the MJCF that
// `dyncc export` writes, computing the same quantities as dyncc's generated code.
//
// What a call does (and so what the benchmarks time):
//   mass_matrix:       mj_kinematics, mj_comPos, mj_crb (composite rigid body, armature included),
//                      mj_fullM (MuJoCo's sparse factor storage to a dense matrix)
//   inverse_dynamics:  mj_kinematics, mj_comPos, mj_comVel, mj_rne with accelerations, plus
//                      armature * qacc (mj_rne leaves the armature out; mj_inverse adds it the same
//                      way)
// For a closed chain (the Kraft arm) MuJoCo's joints are more than the coordinates; the call sets
// qpos = G q, qvel = G qd, qacc = G qdd and returns G^T M G and G^T tau (G from the joint
// expressions; exact, since the loop constraints hold identically). The model's equality
// constraints are loaded but take no part in M or in RNE; mj_forward (forward dynamics with the
// constraint solve) is offered separately for reference.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>

#include "robot/description.hpp"

struct mjModel_;
struct mjData_;

namespace dyncc::bench {

class MujocoBaseline {
 public:
  /// Loads an MJCF file. `coupling` maps coordinates to MuJoCo's degrees of freedom (nv x n):
  /// qpos = coupling * q (the exported joints read 0 at q = 0). Throws std::runtime_error with
  /// MuJoCo's message when the model does not load.
  MujocoBaseline(const std::string& mjcf_path, Eigen::MatrixXd coupling);
  ~MujocoBaseline();
  MujocoBaseline(const MujocoBaseline&) = delete;
  MujocoBaseline& operator=(const MujocoBaseline&) = delete;
  MujocoBaseline(MujocoBaseline&&) = delete;
  MujocoBaseline& operator=(MujocoBaseline&&) = delete;

  [[nodiscard]] int dof() const { return static_cast<int>(coupling_.cols()); }
  [[nodiscard]] const mjModel_* model() const { return model_; }
  [[nodiscard]] mjData_* data() { return data_; }
  [[nodiscard]] const Eigen::MatrixXd& coupling() const { return coupling_; }

  /// H (dof x dof, row-major) at q.
  void mass_matrix(const double* q, double* H);
  /// tau = H qdd + C qd + g.
  void inverse_dynamics(const double* q, const double* qd, const double* qdd, double* tau);
  /// mj_forward at (q, qd) with zero control: forward dynamics including the equality constraints.
  void forward(const double* q, const double* qd);

 private:
  void set_positions(const double* q);

  mjModel_* model_ = nullptr;
  mjData_* data_ = nullptr;
  Eigen::MatrixXd coupling_;
  bool identity_coupling_ = false;
  Eigen::MatrixXd full_, full_times_coupling_;  // nv x nv, nv x n
  Eigen::VectorXd joint_, joint_tau_;           // nv
};

/// The description exported to MJCF (gen/export) in a temporary file, loaded, with the coupling
/// read from the joint expressions by joint name.
std::unique_ptr<MujocoBaseline> mujoco_baseline_for(const robot::RobotDescription& robot);

}  // namespace dyncc::bench
