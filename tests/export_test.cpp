// `dyncc export --format mjcf` checked in MuJoCo (2.2, Debian's libmujoco): every shipped robot
// is exported by the command, loaded by MuJoCo, and MuJoCo's own dynamics of the model must be
// dyncc's. MuJoCo works on the tree of joints (5 for the Kraft arm); its results are projected
// onto the coordinates with G = d(joint variables)/dq taken from the description's joint
// expressions (export_support.hpp), which is exact because the joint variables are affine:
//   H = G^T M G               (M from mj_fullM after mj_forward, armature included)
//   g = G^T qfrc_bias         at qvel = 0
//   C qd = G^T qfrc_bias - g  at qvel = G qd
// and the model's equality constraints (couplings, loop closure) must hold at every
// configuration the coordinates produce (efc_pos = 0) and admit every motion they produce
// (efc_J G = 0).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <iostream>
#include <memory>
#include <random>

#include "dynamics_support.hpp"
#include "export_random_robot.hpp"
#include "export_support.hpp"

namespace dyncc::test {
namespace {

constexpr double kTolerance = 1e-8;  // relative
constexpr int kSamples = 20;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

ModelPtr load_mjcf(const std::filesystem::path& file) {
  std::array<char, 1000> error{};
  ModelPtr m(mj_loadXML(file.c_str(), nullptr, error.data(), static_cast<int>(error.size())));
  mj_freeLastXML();  // MuJoCo keeps the parsed XML until the next load: LeakSanitizer would see it
  EXPECT_TRUE(m) << "MuJoCo does not load " << file << ": " << error.data() << "\n" << read_text(file);
  return m;
}

/// The exported joint of each moving link, found by its documented name "<link>_joint".
std::vector<int> dof_of_links(const robot::RobotDescription& robot, const mjModel* m, JointVariables& joints) {
  std::vector<int> dofs;
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    if (!joints.moves(l)) {
      dofs.push_back(-1);
      continue;
    }
    const int id = mj_name2id(m, mjOBJ_JOINT, (robot.links[l].name + "_joint").c_str());
    EXPECT_GE(id, 0) << "no joint " << robot.links[l].name << "_joint";
    dofs.push_back(id < 0 ? -1 : m->jnt_dofadr[id]);
  }
  return dofs;
}

struct MujocoWorst {
  double H = 0, g = 0, coriolis = 0, constraint = 0, admissible_motion = 0;
};

MujocoWorst check_in_mujoco(const std::filesystem::path& description, const std::string& label) {
  MujocoWorst w;
  const auto d = derive_file(description);
  if (!d) return w;
  const std::filesystem::path xml = output_path(label + ".xml");
  const DynccRun run = run_dyncc("export " + quoted(description) + " --format mjcf -o " + quoted(xml));
  EXPECT_EQ(run.exit_code, 0) << run.errors;
  const ModelPtr m = load_mjcf(xml);
  if (!m) return w;
  m->opt.jacobian = mjJAC_DENSE;  // efc_J as a dense nefc x nv matrix
  const DataPtr data(mj_makeData(m.get()));
  JointVariables joints(d->robot);
  const std::vector<int> dofs = dof_of_links(d->robot, m.get(), joints);
  const auto n = static_cast<Eigen::Index>(d->robot.coordinates.size());
  const auto nv = static_cast<Eigen::Index>(m->nv);
  const Eigen::VectorXd standard = d->numeric->nominal_standard_values();

  std::mt19937_64 rng(20261122);
  for (int k = 0; k < kSamples; ++k) {
    const dyn::State s = random_state(n, rng);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nv, n);
    mju_zero(data->qpos, m->nq);
    for (std::size_t l = 0; l < dofs.size(); ++l) {
      if (dofs[l] < 0) continue;
      data->qpos[m->jnt_qposadr[m->dof_jntid[dofs[l]]]] = joints.value(l, s.q);
      G.row(dofs[l]) = joints.gradient(l, s.q);
    }
    const dyn::Evaluation e = d->numeric->evaluate(s, standard, false);

    mju_zero(data->qvel, m->nv);
    mj_forward(m.get(), data.get());
    Eigen::MatrixXd M(nv, nv);
    mj_fullM(m.get(), M.data(), data->qM);  // symmetric: the storage order does not matter
    const Eigen::VectorXd bias_at_rest = Eigen::Map<const Eigen::VectorXd>(data->qfrc_bias, nv);
    const Eigen::MatrixXd H = G.transpose() * M * G;
    const Eigen::VectorXd g = G.transpose() * bias_at_rest;
    w.H = std::max(w.H, relative_difference(H, e.H, max_abs(e.H)));
    // Relative to g, unless gravity hardly loads the joints (then rounding dominates g).
    w.g = std::max(w.g, relative_difference(g, e.g, std::max(max_abs(e.g), 1e-6 * max_abs(e.H))));

    // The equality constraints at this configuration: residuals and Jacobian.
    for (int r = 0; r < data->nefc; ++r) {
      if (data->efc_type[r] != mjCNSTR_EQUALITY) continue;
      w.constraint = std::max(w.constraint, std::abs(data->efc_pos[r]));
      const Eigen::Map<const Eigen::RowVectorXd> row(data->efc_J + static_cast<std::ptrdiff_t>(r) * m->nv, nv);
      w.admissible_motion = std::max(w.admissible_motion, (row * G).cwiseAbs().maxCoeff());
    }

    Eigen::Map<Eigen::VectorXd>(data->qvel, nv) = G * s.qd;
    mj_forward(m.get(), data.get());
    const Eigen::VectorXd cqd = G.transpose() * Eigen::Map<const Eigen::VectorXd>(data->qfrc_bias, nv) - g;
    const Eigen::VectorXd ours = e.C * s.qd;
    w.coriolis = std::max(w.coriolis, relative_difference(cqd, ours, std::max(max_abs(ours), 1e-6 * max_abs(e.H))));
  }
  EXPECT_LT(w.H, kTolerance) << label << ": G^T M G differs from dyncc's H";
  EXPECT_LT(w.g, kTolerance) << label << ": G^T qfrc_bias (qvel = 0) differs from dyncc's g";
  EXPECT_LT(w.coriolis, kTolerance) << label << ": the velocity part of qfrc_bias differs from dyncc's C qd";
  EXPECT_LT(w.constraint, 1e-9) << label << ": an equality constraint does not hold";
  EXPECT_LT(w.admissible_motion, 1e-9) << label << ": an equality constraint forbids a motion of the coordinates";
  return w;
}

void check_shipped_mjcf(const std::string& file) {
  const MujocoWorst w = check_in_mujoco(robots_dir() / file, file);
  ::testing::Test::RecordProperty("max_relative_error_H", scientific(w.H));
  ::testing::Test::RecordProperty("max_relative_error_g", scientific(w.g));
  std::cout << file << ": max relative error vs MuJoCo  H " << scientific(w.H) << "  g " << scientific(w.g) << "  C qd "
            << scientific(w.coriolis) << "  constraint residual " << scientific(w.constraint) << "\n";
}

TEST(ExportMjcf, KraftClosedChainMatchesMuJoCo) { check_shipped_mjcf("kraft.yaml"); }

TEST(ExportMjcf, Puma560MatchesMuJoCo) { check_shipped_mjcf("puma560.yaml"); }

TEST(ExportMjcf, PandaMatchesMuJoCo) { check_shipped_mjcf("panda.yaml"); }

TEST(ExportMjcf, PlanarArmMatchesMuJoCo) { check_shipped_mjcf("planar_2link.yaml"); }

// Random descriptions (export_random_robot.hpp): prismatic joints, branches, scaled and coupled
// joints, welded links, a massless link and thin rods that MuJoCo only takes after the export's
// repairs, rotors, friction, limits, gravity in any direction.
TEST(ExportMjcf, RandomDescriptionsMatchMuJoCo) {
  std::mt19937_64 rng(4242);
  MujocoWorst largest;
  for (int r = 0; r < 12; ++r) {
    const std::string label = cat({"random", std::to_string(r)});
    const std::string text = random_export_robot(rng, r);
    const std::filesystem::path yaml = output_path(label + ".yaml");
    std::ofstream(yaml) << text;
    const MujocoWorst w = check_in_mujoco(yaml, label);
    largest.H = std::max(largest.H, w.H);
    largest.g = std::max(largest.g, w.g);
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << label << ":\n" << text;
      return;
    }
  }
  std::cout << "random descriptions: max relative error vs MuJoCo  H " << scientific(largest.H) << "  g "
            << scientific(largest.g) << "\n";
}

// The Kraft arm's closure is in MuJoCo's own terms: the coupled joints and the parallelogram.
TEST(ExportMjcf, KraftStatesItsCouplingsAndLoop) {
  const std::filesystem::path xml = output_path("xml");
  ASSERT_EQ(run_dyncc("export " + quoted(robots_dir() / "kraft.yaml") + " --format mjcf -o " + quoted(xml)).exit_code,
            0);
  const ModelPtr m = load_mjcf(xml);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->nv, 5);  // five bodies on the tree
  EXPECT_EQ(m->nu, 3);  // one motor per coordinate
  int connect = 0, couplings = 0;
  for (int i = 0; i < m->neq; ++i) {
    connect += m->eq_type[i] == mjEQ_CONNECT ? 1 : 0;
    couplings += m->eq_type[i] == mjEQ_TENDON || m->eq_type[i] == mjEQ_JOINT ? 1 : 0;
  }
  EXPECT_EQ(connect, 1);
  EXPECT_EQ(couplings, 2);  // forearm and coupler follow two joints each
}

}  // namespace
}  // namespace dyncc::test
