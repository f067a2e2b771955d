#include "export/mujoco_inertia.hpp"

#include <fmt/core.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <functional>

namespace dyncc::exporting {
namespace {

// MuJoCo's own threshold is 1e-15 absolute; ours are relative to the robot's inertia scale and
// leave room for the round trip through decimal text and MuJoCo's eigen-decomposition.
constexpr double kMomentMargin = 1e-6;    // smallest principal moment after a repair, x scale
constexpr double kTriangleSlack = 1e-12;  // A + B - C may be this far below 0 (rounding), x trace
constexpr double kMujocoMinimum = 1e-14;  // mjEPS, what MuJoCo requires of the smallest moment
constexpr double kLargestAmount = 1e6;    // x scale: beyond this a repair is not worth having

struct Principal {
  double smallest = 0.0;  // smallest principal moment
  double slack = 0.0;     // A + B - C with C the largest principal moment
  double trace = 0.0;
};

Principal principal(const Eigen::Matrix3d& inertia) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d& l = eig.eigenvalues();  // ascending
  return {l[0], l[0] + l[1] - l[2], l.sum()};
}

/// The tensor a joint lets move between a body and its parent (see the header), per unit amount.
Eigen::Matrix3d movable_tensor(const Body& body) {
  if (body.joint == robot::JointType::Prismatic) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  return Eigen::Matrix3d::Identity() - axis * axis.transpose();
}

/// |r|^2 1 - r r^T: the inertia of a unit mass at r about the origin.
Eigen::Matrix3d point_inertia(const Eigen::Vector3d& r) {
  return r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose();
}

/// Adds a mass at a point, keeping the inertia about the (new) centre of mass.
void add_point_mass(Inertial& in, double mass, const Eigen::Vector3d& at) {
  const double total = in.mass + mass;
  const Eigen::Vector3d com = (in.mass * in.com + mass * at) / total;
  in.inertia += in.mass * point_inertia(in.com - com) + mass * point_inertia(at - com);
  in.mass = total;
  in.com = com;
}

/// Smallest amount in (0, limit] for which `ok` holds, assuming ok is monotone; -1 if none.
double smallest_amount(const std::function<bool(double)>& ok, double start, double limit) {
  double hi = start;
  while (!ok(hi)) {
    hi *= 2;
    if (hi > limit) return -1.0;
  }
  double lo = hi / 2 > start ? hi / 2 : 0.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ok(mid) ? hi : lo) = mid;
  }
  return hi;
}

/// Shaves the largest moment by ulps until A + B >= C holds in floating point (see the header).
void close_triangle_by_rounding(Eigen::Vector3d& moments) {
  for (int guard = 0; guard < 8; ++guard) {
    Eigen::Index largest = 0;
    const double c = moments.maxCoeff(&largest);
    const double a = moments[(largest + 1) % 3], b = moments[(largest + 2) % 3];
    if (a + b >= c) return;
    moments[largest] = std::nextafter(c, 0.0);
  }
}

}  // namespace

PrincipalInertia principal_inertia(const Eigen::Matrix3d& inertia) {
  PrincipalInertia out;
  if (inertia(0, 1) == 0.0 && inertia(0, 2) == 0.0 && inertia(1, 2) == 0.0) {
    out.moments = inertia.diagonal();
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia);
    Eigen::Matrix3d axes = eig.eigenvectors();  // columns: principal axes in the body frame
    if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
    out.orientation = Eigen::Quaterniond(axes).normalized();
    out.moments = eig.eigenvalues();
  }
  close_triangle_by_rounding(out.moments);
  return out;
}

bool admissible_for_mujoco(const Inertial& inertial) {
  const Principal p = principal(inertial.inertia);
  return inertial.mass > 0.0 && p.smallest > std::max(kTriangleSlack * p.trace, kMujocoMinimum) &&
         p.slack >= -kTriangleSlack * p.trace;
}

InertiaRepair repair_for_mujoco(std::vector<Body> bodies) {
  InertiaRepair out;
  double scale = 0.0, heaviest = 0.0;
  for (const Body& b : bodies) {
    scale = std::max(scale, b.inertial.inertia.trace());
    heaviest = std::max(heaviest, b.inertial.mass);
  }
  if (scale <= 0.0) scale = 1.0;
  const double margin = kMomentMargin * scale;
  const double tolerance = kTriangleSlack * scale;

  for (std::size_t i = bodies.size(); i-- > 0;) {
    Body& body = bodies[i];
    if (!body.moves || admissible_for_mujoco(body.inertial)) continue;
    Inertial& in = body.inertial;
    const bool on_fixed_axis = body.parent < 0 && body.joint == robot::JointType::Revolute;
    if (in.mass == 0.0 && on_fixed_axis) {
      // A mass on the fixed joint axis never moves: put it where the axis passes nearest the
      // (irrelevant) centre of mass.
      const double mass = std::max(1e-6 * heaviest, 1e-9);
      add_point_mass(in, mass, Eigen::Vector3d(0, 0, in.com.z()));
      out.notes.push_back(
          {static_cast<int>(i),
           fmt::format("{}: mass 0 -> {:.3g} kg on its fixed joint axis (a point that never moves)", body.name, mass)});
    }
    if (!admissible_for_mujoco(in)) {
      const Eigen::Matrix3d unit = movable_tensor(body);
      const auto slack_with = [&](double amount) { return principal(in.inertia + amount * unit).slack; };
      // The slack only grows with the amount, but a thin rod or plate (a zero second moment
      // across the joint axis) keeps it at 0: then 0 is all that is asked, and MuJoCo accepts
      // the equality A + B = C.
      const double required_slack = std::min(margin, slack_with(kLargestAmount * scale)) - tolerance;
      const auto ok = [&](double amount) {
        const Principal p = principal(in.inertia + amount * unit);
        return p.smallest >= margin && p.slack >= required_slack;
      };
      const double amount = smallest_amount(ok, margin, kLargestAmount * scale);
      if (amount > 0.0) {
        in.inertia += amount * unit;
        std::string from = "added: the parent is the fixed base";
        if (body.parent >= 0) {
          Body& parent = bodies[static_cast<std::size_t>(body.parent)];
          parent.inertial.inertia -= body.rotation * (amount * unit) * body.rotation.transpose();
          from = "moved from " + parent.name;
        }
        const char* what = body.joint == robot::JointType::Prismatic ? "1" : "(1 - z z^T)";
        out.notes.push_back({static_cast<int>(i),
                             fmt::format("{}: inertia + {:.6g} * {} about its joint ({}; the dynamics are unchanged)",
                                         body.name, amount, what, from)});
      }
    }
    if (!admissible_for_mujoco(in)) out.unrepaired.push_back(static_cast<int>(i));
  }
  out.bodies = std::move(bodies);
  return out;
}

}  // namespace dyncc::exporting
