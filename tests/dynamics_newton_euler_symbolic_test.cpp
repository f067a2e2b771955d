// The generator's symbolic recursive Newton-Euler torque and composite-rigid-body mass matrix
// (gen/dynamics/newton_euler.hpp, which
// the code generator emits when it is the cheaper program) against the Lagrangian model, for
// every shipped robot: standard and modified D-H, and the Kraft arm's closed chain through its
// affine joint map. Evaluated numerically at random states with nominal parameter values.
#include <gtest/gtest.h>

#include <string>
#include <unordered_map>

#include "dynamics/newton_euler.hpp"
#include "dynamics_support.hpp"
#include "sym/evaluate.hpp"

namespace dyncc::test {
namespace {

class SymbolicNewtonEuler : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(SymbolicNewtonEuler, EqualsTheLagrangianTorqueGravityAndMassMatrix) {
  const auto d = derive_file(GetParam());
  ASSERT_TRUE(d);
  const dyn::DynamicModel& m = d->model;
  const std::size_t n = m.q.size();
  const auto tau = dyn::newton_euler_torque(d->robot, m, dyn::NewtonEulerInputs{m.qd, m.a, true});
  ASSERT_TRUE(tau.has_value()) << "every shipped robot has an affine joint map";
  const std::vector<sym::Expr> zeros(n, sym::Expr(0));
  const auto gravity = dyn::newton_euler_torque(d->robot, m, dyn::NewtonEulerInputs{zeros, zeros, true});
  ASSERT_TRUE(gravity.has_value());
  const auto mass_matrix = dyn::composite_rigid_body_mass_matrix(d->robot, m);
  ASSERT_TRUE(mass_matrix.has_value());

  const Eigen::VectorXd standard = d->numeric->nominal_standard_values();
  for (std::uint64_t seed = 0; seed < 10; ++seed) {
    dyn::State s = dyn::random_state(n, 500 + seed);
    s.v = s.qd;  // inverse dynamics: C qd
    const dyn::Evaluation ev = d->numeric->evaluate(s, standard, false);
    std::unordered_map<std::string, double> values = {{"pi", 3.141592653589793}};
    for (std::size_t k = 0; k < n; ++k) {
      values[m.q[k].name()] = s.q[static_cast<Eigen::Index>(k)];
      values[m.qd[k].name()] = s.qd[static_cast<Eigen::Index>(k)];
      values[m.a[k].name()] = s.a[static_cast<Eigen::Index>(k)];
    }
    for (std::size_t l = 0; l < m.params.list.size(); ++l) {
      values[m.params.list[l].name] = standard[static_cast<Eigen::Index>(l)];
    }
    const Eigen::VectorXd rigid = ev.tau - ev.friction;
    for (std::size_t k = 0; k < n; ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      EXPECT_NEAR(sym::evaluate((*tau)[k], values), rigid[i], 1e-10 * (1 + rigid.norm())) << "joint " << k + 1;
      EXPECT_NEAR(sym::evaluate((*gravity)[k], values), ev.g[i], 1e-10 * (1 + ev.g.norm())) << "joint " << k + 1;
      for (std::size_t j = 0; j < n; ++j) {
        EXPECT_NEAR(sym::evaluate((*mass_matrix)[k][j], values), ev.H(i, static_cast<Eigen::Index>(j)),
                    1e-10 * (1 + ev.H.norm()))
            << "H(" << k + 1 << "," << j + 1 << ")";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, SymbolicNewtonEuler, ::testing::ValuesIn(shipped_robots()),
                         [](const ::testing::TestParamInfo<std::filesystem::path>& info) {
                           std::string s = info.param.stem().string();
                           for (char& c : s) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return s;
                         });

}  // namespace
}  // namespace dyncc::test
