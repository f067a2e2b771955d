// The speed-comparison baselines of bench/ compute dyncc's quantities: the plain Eigen CRBA and
// RNEA (bench/eigen_rbd.hpp, built from the description by bench/rbd_from_description.hpp) and
// MuJoCo on the exported MJCF (bench/mujoco_baseline.hpp), against dyncc's NumericModel at
// random states: H, tau = H qdd + C qd + g, and g.
#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "dynamics_support.hpp"
#include "eigen_rbd.hpp"
#include "mujoco_baseline.hpp"
#include "rbd_from_description.hpp"

namespace dyncc::test {
namespace {

constexpr int kSamples = 25;

struct Worst {
  double H = 0, tau = 0, g = 0;
};

/// Compares any baseline with mass_matrix and inverse_dynamics calls against dyncc's model.
template <typename Baseline>
Worst compare(Baseline& baseline, const pipeline::Derivation& d) {
  const auto n = static_cast<Eigen::Index>(d.robot.coordinates.size());
  const Eigen::VectorXd standard = d.numeric->nominal_standard_values();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  std::mt19937_64 rng(31);
  Worst w;
  for (int k = 0; k < kSamples; ++k) {
    const dyn::State s = random_state(n, rng);
    const dyn::Evaluation e = d.numeric->evaluate(s, standard, false);
    Eigen::MatrixXd H(n, n);
    Eigen::VectorXd tau(n), g(n);
    baseline.mass_matrix(s.q.data(), H.data());
    baseline.inverse_dynamics(s.q.data(), s.qd.data(), s.a.data(), tau.data());
    baseline.inverse_dynamics(s.q.data(), zero.data(), zero.data(), g.data());
    const Eigen::VectorXd expected = e.H * s.a + e.C * s.qd + e.g;
    const double scale = std::max({max_abs(e.H * s.a), max_abs(e.C * s.qd), max_abs(e.g)});
    w.H = std::max(w.H, relative_difference(H, e.H, max_abs(e.H)));
    w.tau = std::max(w.tau, relative_difference(tau, expected, scale));
    w.g = std::max(w.g, relative_difference(g, e.g, max_abs(e.g)));
  }
  return w;
}

void check_eigen(const std::string& file) {
  const auto d = derive_file(robots_dir() / file);
  ASSERT_TRUE(d);
  bench::EigenRbd rbd(bench::tree_from_description(d->robot));
  const Worst w = compare(rbd, *d);
  EXPECT_LT(w.H, 1e-9) << file << ": Eigen CRBA differs from dyncc's H";
  EXPECT_LT(w.tau, 1e-9) << file << ": Eigen RNEA differs from dyncc's H qdd + C qd + g";
  EXPECT_LT(w.g, 1e-9) << file << ": Eigen RNEA at rest differs from dyncc's g";
  // gravity_torque is the RNEA at rest too, by its own entry point.
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(rbd.dof(), -1.0, 1.0);
  Eigen::VectorXd g(rbd.dof()), g_rnea(rbd.dof());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(rbd.dof());
  rbd.gravity_torque(q.data(), g.data());
  rbd.inverse_dynamics(q.data(), zero.data(), zero.data(), g_rnea.data());
  EXPECT_EQ(g, g_rnea);
  std::cout << file << " Eigen baseline: max relative error H " << scientific(w.H) << "  tau " << scientific(w.tau)
            << "  g " << scientific(w.g) << "\n";
}

void check_mujoco(const std::string& file) {
  const auto d = derive_file(robots_dir() / file);
  ASSERT_TRUE(d);
  const auto mujoco = bench::mujoco_baseline_for(d->robot);
  const Worst w = compare(*mujoco, *d);
  EXPECT_LT(w.H, 1e-8) << file << ": MuJoCo's H differs from dyncc's";
  EXPECT_LT(w.tau, 1e-8) << file << ": MuJoCo's RNEA differs from dyncc's H qdd + C qd + g";
  EXPECT_LT(w.g, 1e-8) << file << ": MuJoCo's RNEA at rest differs from dyncc's g";
  std::cout << file << " MuJoCo baseline: max relative error H " << scientific(w.H) << "  tau " << scientific(w.tau)
            << "  g " << scientific(w.g) << "\n";
}

TEST(BaselineEigen, Puma560MatchesDyncc) { check_eigen("puma560.yaml"); }
TEST(BaselineEigen, PandaMatchesDyncc) { check_eigen("panda.yaml"); }
TEST(BaselineEigen, PlanarArmMatchesDyncc) { check_eigen("planar_2link.yaml"); }
// The five-body tree with the coupling G, projected onto the three coordinates.
TEST(BaselineEigen, KraftTreeMatchesDyncc) { check_eigen("kraft.yaml"); }

TEST(BaselineMujoco, Puma560MatchesDyncc) { check_mujoco("puma560.yaml"); }
TEST(BaselineMujoco, PandaMatchesDyncc) { check_mujoco("panda.yaml"); }
TEST(BaselineMujoco, KraftMatchesDyncc) { check_mujoco("kraft.yaml"); }

}  // namespace
}  // namespace dyncc::test
