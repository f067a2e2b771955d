#include "mujoco_baseline.hpp"

#include <mujoco/mujoco.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "export/export_model.hpp"
#include "export/mjcf_writer.hpp"

namespace dyncc::bench {
namespace {

using RowMajorMap = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;

}  // namespace

MujocoBaseline::MujocoBaseline(const std::string& mjcf_path, Eigen::MatrixXd coupling)
    : coupling_(std::move(coupling)) {
  std::array<char, 1000> error{};
  model_ = mj_loadXML(mjcf_path.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  mj_freeLastXML();  // MuJoCo keeps the parsed XML for mj_saveLastXML; nothing here needs it
  if (model_ == nullptr) throw std::runtime_error("MuJoCo cannot load " + mjcf_path + ": " + error.data());
  if (model_->nq != model_->nv || coupling_.rows() != model_->nv) {
    mj_deleteModel(model_);
    throw std::runtime_error("MujocoBaseline: the coupling needs one row per hinge or slide joint");
  }
  data_ = mj_makeData(model_);
  identity_coupling_ = coupling_.rows() == coupling_.cols() && coupling_.isIdentity(0.0);
  full_.resize(model_->nv, model_->nv);
  full_times_coupling_.resize(model_->nv, coupling_.cols());
  joint_.resize(model_->nv);
  joint_tau_.resize(model_->nv);
}

MujocoBaseline::~MujocoBaseline() {
  mj_deleteData(data_);
  mj_deleteModel(model_);
}

void MujocoBaseline::set_positions(const double* q) {
  Eigen::Map<Eigen::VectorXd>(data_->qpos, model_->nq).noalias() =
      coupling_ * Eigen::Map<const Eigen::VectorXd>(q, coupling_.cols());
}

void MujocoBaseline::mass_matrix(const double* q, double* H) {
  set_positions(q);
  mj_kinematics(model_, data_);
  mj_comPos(model_, data_);
  mj_crb(model_, data_);
  const auto n = coupling_.cols();
  if (identity_coupling_) {
    mj_fullM(model_, H, data_->qM);  // symmetric, so row- and column-major agree
    return;
  }
  // mj_fullM writes row-major; M is symmetric, so the column-major view is the same matrix.
  mj_fullM(model_, full_.data(), data_->qM);
  full_times_coupling_.noalias() = full_ * coupling_;
  RowMajorMap(H, n, n).noalias() = coupling_.transpose() * full_times_coupling_;
}

void MujocoBaseline::inverse_dynamics(const double* q, const double* qd, const double* qdd, double* tau) {
  const auto n = coupling_.cols();
  set_positions(q);
  Eigen::Map<Eigen::VectorXd>(data_->qvel, model_->nv).noalias() = coupling_ * Eigen::Map<const Eigen::VectorXd>(qd, n);
  Eigen::Map<Eigen::VectorXd> qacc(data_->qacc, model_->nv);
  qacc.noalias() = coupling_ * Eigen::Map<const Eigen::VectorXd>(qdd, n);
  mj_kinematics(model_, data_);
  mj_comPos(model_, data_);
  mj_comVel(model_, data_);
  mj_rne(model_, data_, 1, joint_tau_.data());
  joint_tau_ += Eigen::Map<const Eigen::VectorXd>(model_->dof_armature, model_->nv).cwiseProduct(qacc);
  Eigen::Map<Eigen::VectorXd> out(tau, n);
  if (identity_coupling_) {
    out = joint_tau_;
  } else {
    out.noalias() = coupling_.transpose() * joint_tau_;
  }
}

void MujocoBaseline::forward(const double* q, const double* qd) {
  set_positions(q);
  Eigen::Map<Eigen::VectorXd>(data_->qvel, model_->nv).noalias() =
      coupling_ * Eigen::Map<const Eigen::VectorXd>(qd, coupling_.cols());
  mj_forward(model_, data_);
}

std::unique_ptr<MujocoBaseline> mujoco_baseline_for(const robot::RobotDescription& robot) {
  const exporting::ExportModel model = exporting::build_export_model(robot);
  std::vector<robot::Diagnostic> warnings;  // inertia repairs keep the dynamics; nothing to report here
  const std::string mjcf = exporting::write_mjcf(model, warnings);
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("dyncc-baseline-" + robot.name + "-" + std::to_string(::getpid()) + ".xml");
  std::ofstream(path) << mjcf;

  // Load once to find the joints' degrees of freedom by name, then build the coupling.
  std::array<char, 1000> error{};
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  mj_freeLastXML();
  if (m == nullptr) throw std::runtime_error("MuJoCo cannot load the exported " + robot.name + ": " + error.data());
  Eigen::MatrixXd coupling = Eigen::MatrixXd::Zero(m->nv, static_cast<Eigen::Index>(robot.coordinates.size()));
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!model.bodies[b].moves) continue;
    const int joint = mj_name2id(m, mjOBJ_JOINT, exporting::joint_name(model.bodies[b]).c_str());
    const std::vector<double>& c = model.joints[b].coefficients;
    coupling.row(m->jnt_dofadr[joint]) =
        Eigen::Map<const Eigen::RowVectorXd>(c.data(), static_cast<Eigen::Index>(c.size()));
  }
  mj_deleteModel(m);
  auto baseline = std::make_unique<MujocoBaseline>(path.string(), std::move(coupling));
  std::filesystem::remove(path);
  return baseline;
}

}  // namespace dyncc::bench
