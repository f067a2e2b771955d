#include "diagnose/contact_effect.hpp"

#include <algorithm>
#include <cmath>

#include "diagnose/model_batch.hpp"

namespace dyncc::diagnose {
namespace {

// Times the arm's scale (how far the link's origin sits and travels). A tool reaches beyond the
// link's origin: the Kraft's hook is 0.40 m along the forearm, 2.3 times the scale. Up to 1.5 times
// (until the twenty-first session) no gate held a rigid plant's touches of it, the best point
// explained 4.1 %, below what starts the search, and the contact was `unknown` (seed 107 case 48).
constexpr double kContactPoints[] = {-1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0, 2.5};
// Of the point's height over the log. The smallest ones for brief touches: a MuJoCo table 5 mm
// above the Kraft hook's lowest point is touched in 0.2 % of the rows (seed 107 case 3).
constexpr double kContactQuantiles[] = {0.003, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3};
// A point held on the surface rests there for a while (a tele-operator's hook put down on the table
// 17 % of the log).
constexpr double kHeldQuantiles[] = {0.05, 0.1, 0.2, 0.3};
constexpr double kSlipVelocity = 0.005;  // m/s: slower sliding is not resolved (friction turns over)

// The search. The grid's spacing (half the arm's scale) is far coarser than a touch resolves: on
// that log (seed 107 case 3) the hook was beyond the grid's farthest point then (0.26 m), and a
// gate on a point 5 cm off the hook holds rows where that point, not the hook, is low (about half
// of what the hook's own gate explains, and implausibly).
constexpr double kFirstStep = 0.25;      // of the scale
constexpr double kFinestStep = 0.03;     // of the scale: the search stops below it
constexpr double kQuantileFactor = 2.0;  // the quantile's first step (shrinks with the point's)
constexpr double kSmallestQuantile = 0.001;
constexpr double kLargestQuantile = 0.5;
constexpr Eigen::Index kFewestTouchRows = 5;  // evaluation rows below the surface, at least
constexpr int kMostJudged = 90;               // points judged per search

bool same(const ContactPoint& a, const ContactPoint& b) {
  return a.point == b.point && a.quantile == b.quantile && a.held == b.held;
}

}  // namespace

ContactPoint ContactPoint::of(const Effect& contact) {
  const std::vector<double>& c = contact.profile_point;
  return c.size() == 4 ? ContactPoint{Eigen::Vector3d(c[0], 0.0, c[1]), c[2], c[3] != 0.0} : ContactPoint{};
}

ContactRows::ContactRows(const Dataset& d, const pipeline::Derivation& derivation) : d_(&d) {
  const ContactGeometry geometry(derivation);
  if (!geometry.valid()) return;
  valid_ = true;
  const Eigen::Index n = d.n, samples = d.samples();
  height_.resize(samples, 4);
  lever_.resize(samples * n, 4);
  frames_.reserve(static_cast<std::size_t>(samples));
  // On the positions only anti-aliased: a touch shorter than the filter's period is a dip that
  // the low-passed positions smooth away (see Dataset::q_sharp).
  for (Eigen::Index chunk = 0; chunk < samples; chunk += kModelRowsPerBatch) {
    const Eigen::MatrixXd q = d.q_sharp.middleRows(chunk, std::min(kModelRowsPerBatch, samples - chunk));
    const std::vector<ContactGeometry::Basis> bases = geometry.at_rows(q);
    for (Eigen::Index k = 0; k < q.rows(); ++k) {
      const ContactGeometry::Basis& b = bases[static_cast<std::size_t>(k)];
      height_.row(chunk + k) = b.height.transpose();
      lever_.middleRows((chunk + k) * n, n) = b.lever;
    }
    for (ContactGeometry::Frame& f : geometry.frames(q)) frames_.push_back(std::move(f));
  }
  scale_ = ContactGeometry::scale(height_.col(0));
  down_ = geometry.down();
}

double ContactRows::clamped(double quantile) const {
  const double fewest =
      static_cast<double>(kFewestTouchRows) / static_cast<double>(std::max<Eigen::Index>(1, d_->samples()));
  return std::clamp(quantile, std::max(kSmallestQuantile, fewest), kLargestQuantile);
}

std::vector<ContactPoint> ContactRows::grid() const {
  std::vector<ContactPoint> out;
  for (const double cx : kContactPoints) {
    for (const double cz : kContactPoints) {
      const Eigen::Vector3d point(cx * scale_, 0.0, cz * scale_);
      for (const double quantile : kContactQuantiles) out.push_back({point, quantile, false});
      for (const double quantile : kHeldQuantiles) out.push_back({point, quantile, true});
    }
  }
  return out;
}

Effect ContactRows::effect(const ContactPoint& at) const {
  const Dataset& d = *d_;
  const Eigen::Index n = d.n, samples = d.samples();
  const Eigen::Vector3d& c = at.point;
  const Eigen::VectorXd z = height_.col(0) + height_.rightCols(3) * c;
  std::vector<double> sorted(z.data(), z.data() + z.size());
  const auto k = static_cast<std::ptrdiff_t>(at.quantile * static_cast<double>(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  const double h = sorted[static_cast<std::size_t>(k)];
  Effect e;
  e.name = e.family = "contact";
  e.profile_name = "surface_height";
  e.profile = h;
  e.profile_point = at.coordinates();
  if (at.held) {  // minus the torque of the upward push at c
    e.columns = Eigen::MatrixXd::Zero(samples * n, 1);
    for (Eigen::Index s = 0; s < samples; ++s) {
      if (z[s] >= h) continue;
      const auto rows = lever_.middleRows(s * n, n);
      e.columns.block(s * n, 0, n, 1) = rows.col(0) + rows.rightCols(3) * c;
    }
    e.parameters = {"force"};
    e.joint_of = {-1};
    e.reading = {Reading::as_is};
    e.columns = d.condition(e.columns);  // one pass: see Dataset (a contact is the measured exception)
    return e;
  }
  e.columns = Eigen::MatrixXd::Zero(samples * n, 8);
  // The spring's columns are taken about the mean depth over the rows in contact, so that `force`
  // (and `friction_force`) is the push there, the point at rest: what a table that pushes gives
  // above zero (reading.cpp reads the push at the surface from it).
  double mean_depth = 0, touching = 0;
  for (Eigen::Index s = 0; s < samples; ++s) {
    if (z[s] >= h) continue;
    mean_depth += h - z[s];
    touching += 1;
  }
  if (touching > 0) mean_depth /= touching;
  for (Eigen::Index s = 0; s < samples; ++s) {
    if (z[s] >= h) continue;
    // The point's sinking rate (down . v) and J_c^T of its sliding direction.
    const Eigen::MatrixXd jacobian = frames_[static_cast<std::size_t>(s)].point_jacobian(c);
    const Eigen::Vector3d v = jacobian * d.qd.row(s).transpose();
    const double sinking = down_.dot(v);
    const Eigen::Vector3d horizontal = v - sinking * down_;
    const Eigen::Vector3d direction = horizontal / std::sqrt(horizontal.squaredNorm() + kSlipVelocity * kSlipVelocity);
    const Eigen::VectorXd sliding = jacobian.transpose() * direction;
    const auto rows = lever_.middleRows(s * n, n);
    const Eigen::VectorXd at_point = rows.col(0) + rows.rightCols(3) * c;
    e.columns.block(s * n, 0, n, 4) = rows;
    e.columns.block(s * n, 4, n, 1) = at_point * (h - z[s] - mean_depth);
    e.columns.block(s * n, 5, n, 1) = at_point * sinking;
    e.columns.block(s * n, 6, n, 1) = sliding;
    e.columns.block(s * n, 7, n, 1) = sliding * (h - z[s] - mean_depth);
  }
  for (const char* name :
       {"force", "moment_x", "moment_y", "moment_z", "stiffness", "damping", "friction_force", "friction_stiffness"}) {
    e.parameters.emplace_back(name);
    e.joint_of.push_back(-1);
    e.reading.push_back(Reading::as_is);
  }
  e.columns = d.condition(e.columns);  // one pass: see Dataset (a contact is the measured exception)
  e.shape.push_back({"mean_depth", mean_depth, 0.0});
  return e;
}

std::vector<ContactPoint> search_contact(const ContactRows& rows, const ContactPoint& start, const ContactFit& fit,
                                         const ContactJudge& judge) {
  ContactPoint at = start, plausible = start;
  ContactFit at_fit = fit, plausible_fit = fit.plausible ? fit : ContactFit{};
  double step = kFirstStep * rows.scale(), factor = kQuantileFactor;
  int judged = 0;
  while (step >= kFinestStep * rows.scale() && judged < kMostJudged) {
    ContactPoint best = at;
    ContactFit best_fit = at_fit;
    const ContactPoint moves[] = {
        {at.point + Eigen::Vector3d(step, 0, 0), at.quantile, at.held},
        {at.point - Eigen::Vector3d(step, 0, 0), at.quantile, at.held},
        {at.point + Eigen::Vector3d(0, 0, step), at.quantile, at.held},
        {at.point - Eigen::Vector3d(0, 0, step), at.quantile, at.held},
        {at.point, rows.clamped(at.quantile * factor), at.held},
        {at.point, rows.clamped(at.quantile / factor), at.held},
    };
    for (const ContactPoint& next : moves) {
      if (same(next, at)) continue;
      const ContactFit next_fit = judge(rows.effect(next));
      ++judged;
      if (next_fit.shrink > best_fit.shrink) {
        best = next;
        best_fit = next_fit;
      }
      if (next_fit.plausible && next_fit.shrink > plausible_fit.shrink) {
        plausible = next;
        plausible_fit = next_fit;
      }
    }
    if (best_fit.shrink > at_fit.shrink) {
      at = best;
      at_fit = best_fit;
    } else {
      step *= 0.5;
      factor = std::sqrt(factor);
    }
  }
  std::vector<ContactPoint> out{at};
  if (plausible_fit.plausible && !same(plausible, at)) out.push_back(plausible);
  return out;
}

}  // namespace dyncc::diagnose
