// Base parameters of every description in robots/: the base regressor reproduces the full one
// (Y_b * base == Y * standard for ANY standard values, i.e. Y == Y_b * map), its columns are
// independent (full column rank over stacked random samples) and span everything the torque
// depends on (the stacked full regressor has the same rank). Samples come from the tests' own
// generator, not from the states dyncc used to find the base parameters.
#include <gtest/gtest.h>

#include <cctype>
#include <random>

#include "dynamics_support.hpp"

namespace dyncc::test {
namespace {

constexpr int kBaseSamples = 30;

// Rank of a stacked regressor with its columns scaled to unit norm (rank does not change, and
// Eigen's relative threshold is then not fooled by columns of very different magnitude).
Eigen::Index column_rank(const Eigen::MatrixXd& W) {
  Eigen::MatrixXd scaled = W;
  for (Eigen::Index c = 0; c < W.cols(); ++c) {
    const double norm = W.col(c).norm();
    if (norm > 0) scaled.col(c) /= norm;
  }
  return Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(scaled).rank();
}

std::size_t friction_count(const pipeline::Derivation& d) {
  std::size_t count = 0;
  for (const auto& b : d.base.list) {
    const auto kind = d.model.params.list[static_cast<std::size_t>(b.kept)].kind;
    if (kind == dyn::StandardKind::FC || kind == dyn::StandardKind::FV) ++count;
  }
  return count;
}

class ShippedRobotBase : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(ShippedRobotBase, BaseRegressorReproducesFullRegressorAndHasFullColumnRank) {
  const auto d = derive_file(GetParam());
  ASSERT_TRUE(d);
  const auto n = static_cast<Eigen::Index>(d->model.q.size());
  const auto p = static_cast<Eigen::Index>(d->model.params.list.size());
  const auto r = static_cast<Eigen::Index>(d->base.list.size());
  ASSERT_GT(r, 0);
  ASSERT_LE(r, p);

  // map(:, l) = base values of the l-th unit standard vector.
  Eigen::MatrixXd map(r, p);
  for (Eigen::Index l = 0; l < p; ++l) map.col(l) = d->base.values(Eigen::VectorXd::Unit(p, l));
  const Eigen::VectorXd nominal = d->numeric->nominal_standard_values();

  std::mt19937_64 rng(4242);
  Eigen::MatrixXd W(kBaseSamples * n, p), WB(kBaseSamples * n, r);
  double worst_matrix = 0.0, worst_nominal = 0.0;
  for (int k = 0; k < kBaseSamples; ++k) {
    const dyn::State s = random_state(n, rng);
    const Eigen::MatrixXd Y = d->numeric->regressor(s);
    const Eigen::MatrixXd Yb = base::base_regressor(d->base, Y);
    ASSERT_EQ(Yb.cols(), r);
    worst_matrix = std::max(worst_matrix, relative_difference(Yb * map, Y, std::max(1.0, max_abs(Y))));
    const Eigen::VectorXd full = Y * nominal;
    worst_nominal =
        std::max(worst_nominal, relative_difference(Yb * d->base.values(nominal), full, std::max(1e-9, max_abs(full))));
    W.middleRows(k * n, n) = Y;
    WB.middleRows(k * n, n) = Yb;
  }
  EXPECT_LT(worst_matrix, 1e-9) << "Y != Y_b * map: the regrouping coefficients are wrong";
  EXPECT_LT(worst_nominal, 1e-9) << "Y_b * base(nominal) != Y * nominal";
  EXPECT_EQ(column_rank(WB), r) << "base regressor columns are dependent";
  EXPECT_EQ(column_rank(W), r) << "the full regressor has rank beyond the base parameters";
  RecordProperty("base_parameters", std::to_string(r));
  RecordProperty("largest_relative_error", scientific(std::max(worst_matrix, worst_nominal)));

  const std::string name = d->robot.name;
  if (name == "kraft_right") {
    // ERRATA 10: 13 identifiable inertial combinations + 6 friction coefficients.
    EXPECT_EQ(r, 19);
    EXPECT_EQ(friction_count(*d), 6U);
  } else if (name == "panda") {
    // Gaz et al. (RA-L 2019) identify 43 dynamic coefficients (plus friction) for the Panda.
    EXPECT_EQ(r - static_cast<Eigen::Index>(friction_count(*d)), 43);
    EXPECT_EQ(friction_count(*d), 14U);
  } else if (name == "planar_2link") {
    // Per link: the moment about the joint axis and the first moment along the link (gravity
    // and coupling); the rotor folds into ZZ1; viscous friction on both joints (coulomb of q2 is 0).
    EXPECT_EQ(r, 6);
  }
}

std::string robot_test_name(const ::testing::TestParamInfo<std::filesystem::path>& info) {
  std::string s = info.param.stem().string();
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return s;
}

INSTANTIATE_TEST_SUITE_P(Robots, ShippedRobotBase, ::testing::ValuesIn(shipped_robots()), robot_test_name);

}  // namespace
}  // namespace dyncc::test
