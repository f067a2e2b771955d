// The contact's profile (gen/diagnose/contact_effect): the positions its gate reads keep a touch
// shorter than the filter's period, and the local search climbs from the coarse grid to a point
// the grid only comes near, keeping the best plausible point it passed. (That it names brief
// touches of a MuJoCo table as a contact is checked on the bench log it was found on, in
// diagnose_cli_test.)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "diagnose/contact_effect.hpp"
#include "diagnose/dataset.hpp"
#include "diagnose/synthetic_log.hpp"
#include "dynamics_support.hpp"
#include "temp_path.hpp"

namespace dyncc::test {
namespace {

// A Kraft log at 1 kHz, its forearm swinging slowly, with one 30 ms dip of 10 mrad at 10 s (a
// hook pressed into a table and bouncing off), positions on 0.1 mrad steps.
constexpr double kDipAt = 10.0, kDipLength = 0.03, kDipDepth = 0.01;

diagnose::JointLog dipping_log() {
  constexpr Eigen::Index kSamples = 20000;
  diagnose::JointLog log;
  log.path = "dip.csv";
  log.t = Eigen::VectorXd::LinSpaced(kSamples, 0.0, 0.001 * static_cast<double>(kSamples - 1));
  log.q.resize(kSamples, 3);
  log.tau = Eigen::MatrixXd::Zero(kSamples, 3);
  for (Eigen::Index s = 0; s < kSamples; ++s) {
    const double t = log.t[s];
    const double into = t - kDipAt;
    const double dip =
        into >= 0 && into < kDipLength ? kDipDepth * std::sin(std::numbers::pi * into / kDipLength) : 0.0;
    const Eigen::Vector3d q(0.2 * std::sin(0.5 * t), -0.3 + 0.1 * std::sin(0.3 * t),
                            0.7 + 0.2 * std::sin(0.4 * t) - dip);
    for (Eigen::Index j = 0; j < 3; ++j) log.q(s, j) = 1e-4 * std::round(q[j] / 1e-4);
    log.tau.row(s) = Eigen::RowVector3d(0.1 * std::sin(0.5 * t), 0.5, 0.4);
  }
  return log;
}

// The forearm's dip on the evaluation rows, against the swing it rides on (the same rows
// without the dip's window): how deep each set of positions sees it.
double seen_depth(const diagnose::Dataset& d, const Eigen::MatrixXd& q) {
  double deepest = 0;
  for (Eigen::Index s = 0; s < d.samples(); ++s) {
    const double t = d.t[s];
    if (t < kDipAt - 0.2 || t > kDipAt + 0.2) continue;
    deepest = std::max(deepest, 0.7 + 0.2 * std::sin(0.4 * t) - q(s, 2));
  }
  return deepest;
}

// Low-passed at 4 Hz the dip is nearly gone; only anti-aliased (for rows at 100 Hz) it stays.
TEST(ContactRows, GatePositionsKeepATouchShorterThanTheFilterPeriod) {
  const diagnose::Dataset d = diagnose::build_dataset({dipping_log()}, kraft_derivation());
  EXPECT_GT(seen_depth(d, d.q_sharp), 0.6 * kDipDepth);
  EXPECT_LT(seen_depth(d, d.q), 0.25 * kDipDepth);
}

// A judge whose held-out shrink peaks at a point beyond the grid's farthest (x = 3.2 scales along
// the link, the grid ending at 2.5; z = -0.3 scales, the surface at the 0.4 % quantile), and calls
// a fit plausible only short of 3 scales along the link. The search from the grid's best point ends at the peak (to
// its finest step) and also returns the best plausible point it judged.
TEST(ContactSearch, ClimbsBeyondTheGridAndKeepsTheBestPlausiblePoint) {
  diagnose::SyntheticOptions options;
  options.duration = 10;
  const auto path = temp_path("contact_search.csv");
  diagnose::write_synthetic_log(kraft_derivation(), {}, options, path);
  const diagnose::Dataset d = diagnose::build_dataset({diagnose::read_joint_log(path.string(), 3)}, kraft_derivation());
  const diagnose::ContactRows rows(d, kraft_derivation());
  ASSERT_TRUE(rows.valid());
  const double scale = rows.scale(), x0 = 3.2 * scale, z0 = -0.3 * scale, q0 = 0.004;
  const diagnose::ContactJudge judge = [&](const diagnose::Effect& e) {
    const diagnose::ContactPoint p = diagnose::ContactPoint::of(e);
    const double dx = (p.point.x() - x0) / scale, dz = (p.point.z() - z0) / scale, dq = std::log2(p.quantile / q0);
    return diagnose::ContactFit{p.point.x() < 3.0 * scale, 0.6 - dx * dx - dz * dz - 0.02 * dq * dq};
  };
  diagnose::ContactPoint start;
  diagnose::ContactFit start_fit;
  for (const diagnose::ContactPoint& p : rows.grid()) {
    const diagnose::ContactFit f = judge(rows.effect(p));
    if (f.shrink > start_fit.shrink) {
      start = p;
      start_fit = f;
    }
  }
  EXPECT_LE(start.point.x(), 2.5 * scale + 1e-12);  // the grid stops short of the peak
  const std::vector<diagnose::ContactPoint> found = diagnose::search_contact(rows, start, start_fit, judge);
  ASSERT_EQ(found.size(), 2U);
  EXPECT_NEAR(found[0].point.x(), x0, 0.05 * scale);
  EXPECT_NEAR(found[0].point.z(), z0, 0.05 * scale);
  EXPECT_NEAR(std::log2(found[0].quantile / q0), 0.0, 0.5);
  EXPECT_FALSE(judge(rows.effect(found[0])).plausible);
  const diagnose::ContactFit plausible = judge(rows.effect(found[1]));
  EXPECT_TRUE(plausible.plausible);
  EXPECT_GT(plausible.shrink, start_fit.shrink);
}

}  // namespace
}  // namespace dyncc::test
