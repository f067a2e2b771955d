// Where the cross-validation's blocks go (gen/diagnose/fold_plan): on synthetic residuals of
// noise and short bumps (a touch's filtered torque), checked by what the blocks hold, counted here
// from the bumps as they were made: a residual without bursts, with bursts already spread, or
// raised over a long stretch, keeps even blocks; two touches in one block are parted between them, away from either; a
// single touch is cut through, half on each side; no block is shorter than half an even one.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "diagnose/fold_plan.hpp"

namespace dyncc::test {
namespace {

constexpr Eigen::Index kJoints = 2, kSamples = 2000;
constexpr double kRowStep = 0.03;  // s between rows: 60 s

struct Bump {
  Eigen::Index center;
  double height;
};

// Noise on every row, plus bumps of about 0.3 s (a filtered touch) on joint 2.
Eigen::VectorXd residual_with(const std::vector<Bump>& bumps, double smooth = 0.0) {
  std::mt19937 random(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd r(kSamples * kJoints);
  for (Eigen::Index s = 0; s < kSamples; ++s) {
    for (Eigen::Index j = 0; j < kJoints; ++j) r[s * kJoints + j] = normal(random);
    r[s * kJoints] += smooth * std::sin(2 * std::numbers::pi * static_cast<double>(s) / 400.0);
    for (const Bump& b : bumps) {
      const double x = static_cast<double>(s - b.center) / 5.0;
      r[s * kJoints + 1] += b.height * std::exp(-x * x);
    }
  }
  return r;
}

diagnose::Folds plan(const Eigen::VectorXd& r) {
  return diagnose::folds_sharing_bursts(r, Eigen::VectorXd::Ones(kJoints), kJoints, kRowStep);
}

// The share of the bumps' squared height (over their rows) in each block.
std::vector<double> bump_shares(const diagnose::Folds& folds, const std::vector<Bump>& bumps) {
  std::vector<double> share(diagnose::kFolds, 0.0);
  double total = 0;
  for (const Bump& b : bumps) {
    for (Eigen::Index s = b.center - 25; s <= b.center + 25; ++s) {
      const double x = static_cast<double>(s - b.center) / 5.0;
      const double e = std::pow(b.height * std::exp(-x * x), 2);
      total += e;
      for (int f = 0; f < diagnose::kFolds; ++f) {
        if (s >= folds.begin_of(f) && s < folds.end_of(f)) share[static_cast<std::size_t>(f)] += e;
      }
    }
  }
  for (double& x : share) x /= total;
  return share;
}

void expect_blocks_long_enough(const diagnose::Folds& folds) {
  EXPECT_EQ(folds.begin_of(0), 0);
  EXPECT_EQ(folds.end_of(diagnose::kFolds - 1), kSamples);
  for (int f = 0; f < diagnose::kFolds; ++f) {
    EXPECT_GE(folds.end_of(f) - folds.begin_of(f), kSamples / diagnose::kFolds / 2) << "block " << f;
  }
}

TEST(FoldPlan, NoiseAloneKeepsEvenBlocks) { EXPECT_EQ(plan(residual_with({})), diagnose::Folds::even(kSamples)); }

TEST(FoldPlan, BurstsAlreadyInDifferentBlocksKeepEvenBlocks) {
  EXPECT_EQ(plan(residual_with({{300, 60.0}, {1500, 60.0}})), diagnose::Folds::even(kSamples));
}

// A smooth effect carries most of the residual: the bumps beside it are not what it is about.
TEST(FoldPlan, BurstsBesideALargerSmoothEffectKeepEvenBlocks) {
  const Eigen::VectorXd r = residual_with({{1000, 400.0}}, 40.0);
  ASSERT_NE(plan(residual_with({{1000, 400.0}})), diagnose::Folds::even(kSamples)) << "the bump alone moves them";
  EXPECT_EQ(plan(r), diagnose::Folds::even(kSamples));
}

// A load carried for 9 s raises the residual over a stretch, not in a touch: blind seed 193 case 32
// (a Panda payload carried 15-24 s) had its blocks moved through the stretch and its mass read
// 18 % light from a window the payload search widened.
TEST(FoldPlan, AStretchLongerThanATouchKeepsEvenBlocks) {
  Eigen::VectorXd r = residual_with({});
  for (Eigen::Index s = 900; s < 1200; ++s) r[s * kJoints + 1] += 60.0;  // 9 s at 0.03 s
  ASSERT_GT(300 * kRowStep, diagnose::kLongestBurst);
  EXPECT_EQ(plan(r), diagnose::Folds::even(kSamples));
}

TEST(FoldPlan, TwoTouchesInOneBlockArePartedBetweenThem) {
  const std::vector<Bump> bumps{{1630, 60.0}, {1900, 60.0}};  // both in the last even block
  const diagnose::Folds folds = plan(residual_with(bumps));
  ASSERT_NE(folds, diagnose::Folds::even(kSamples));
  expect_blocks_long_enough(folds);
  const std::vector<double> share = bump_shares(folds, bumps);
  EXPECT_NEAR(*std::max_element(share.begin(), share.end()), 0.5, 1e-6);
  // The edge between them is at least the margin (1 s) from each.
  const auto margin = static_cast<Eigen::Index>(diagnose::kBurstMargin / kRowStep);
  for (int f = 1; f < diagnose::kFolds; ++f) {
    for (const Bump& b : bumps) EXPECT_GT(std::abs(folds.begin_of(f) - b.center), margin) << "edge " << f;
  }
}

TEST(FoldPlan, ASingleTouchIsCutThroughItsMiddle) {
  const std::vector<Bump> bumps{{1000, 80.0}};  // mid-block
  const diagnose::Folds folds = plan(residual_with(bumps));
  expect_blocks_long_enough(folds);
  const std::vector<double> share = bump_shares(folds, bumps);
  EXPECT_LT(*std::max_element(share.begin(), share.end()), 0.6);
  EXPECT_GT(*std::max_element(share.begin(), share.end()), 0.4);
}

// Near the log's start, a touch cannot be cut without a block shorter than half an even one.
TEST(FoldPlan, BlocksStayLongEnoughWhenATouchIsNearTheStart) {
  const diagnose::Folds folds = plan(residual_with({{60, 80.0}}));
  expect_blocks_long_enough(folds);
}

}  // namespace
}  // namespace dyncc::test
