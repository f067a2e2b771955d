// NumericModel at many states at once (the tapes over blocks of states) against the same model
// one state at a time: the same numbers, bit for bit, on a closed-chain arm and a 7-joint arm.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "dynamics_support.hpp"

namespace dyncc::test {
namespace {

void expect_batch_is_one_by_one(const pipeline::Derivation& d, std::uint64_t seed) {
  const dyn::NumericModel& model = *d.numeric;
  const auto n = static_cast<Eigen::Index>(model.dof());
  std::mt19937_64 rng(seed);
  std::vector<dyn::State> states;
  for (int k = 0; k < 150; ++k) states.push_back(random_state(n, rng));  // more than two blocks
  const Eigen::VectorXd standard = model.nominal_standard_values();
  const std::vector<dyn::Evaluation> batch = model.evaluate(states, standard);
  const std::vector<Eigen::MatrixXd> ys = model.regressor(states);
  const std::vector<double> energies = model.energy(states, standard);
  ASSERT_EQ(batch.size(), states.size());
  for (std::size_t k = 0; k < states.size(); ++k) {
    const dyn::Evaluation one = model.evaluate(states[k], standard);
    EXPECT_EQ(batch[k].H, one.H) << "state " << k;
    EXPECT_EQ(batch[k].C, one.C) << "state " << k;
    EXPECT_EQ(batch[k].g, one.g) << "state " << k;
    EXPECT_EQ(batch[k].friction, one.friction) << "state " << k;
    EXPECT_EQ(batch[k].tau, one.tau) << "state " << k;
    EXPECT_EQ(batch[k].Y, one.Y) << "state " << k;
    EXPECT_EQ(ys[k], one.Y) << "state " << k;
    EXPECT_EQ(energies[k], model.energy(states[k].q, states[k].qd, standard)) << "state " << k;
    // And the regressor is the model: tau = Y standard.
    EXPECT_LT((one.Y * standard - one.tau).norm(), 1e-9 * (1.0 + one.tau.norm())) << "state " << k;
  }
  EXPECT_TRUE(model.evaluate(std::vector<dyn::State>{}, standard).empty());
}

TEST(NumericModelBatch, KraftAtManyStatesIsTheKraftAtEachState) { expect_batch_is_one_by_one(kraft_derivation(), 11); }

TEST(NumericModelBatch, PandaAtManyStatesIsThePandaAtEachState) {
  const auto panda = derive_file(robots_dir() / "panda.yaml");
  ASSERT_NE(panda, nullptr);
  expect_batch_is_one_by_one(*panda, 12);
}

}  // namespace
}  // namespace dyncc::test
