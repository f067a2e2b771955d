#include "export/mujoco_inertia.hpp"

#include <fmt/core.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <functional>

namespace dyncc::exporting {
namespace {

// MuJoCo's own threshold is 1e-15 absolute; ours are relative to the robot's inertia scale and
// leave room for the round trip through decimal text and MuJoCo's eigen-decomposition.
constexpr double kMomentMargin = 1e-9;    // smallest principal moment after a repair, x scale
constexpr double kRepairMass = 1e-9;      // x the heaviest mass: a mass added where one is needed
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
  if (!body.moves || body.joint == robot::JointType::Prismatic) return Eigen::Matrix3d::Identity();
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
  // A zero moment (a thin rod) may come out of the solver as -1e-18: it is 0.
  const double rounding = kTriangleSlack * std::abs(out.moments.sum());
  for (double& m : out.moments) m = m < 0.0 && m >= -rounding ? 0.0 : m;
  close_triangle_by_rounding(out.moments);
  return out;
}

bool admissible_for_mujoco(const Body& body) {
  const Principal p = principal(body.inertial.inertia);
  const double rounding = kTriangleSlack * p.trace;
  const bool triangle = p.slack >= -rounding;
  // MuJoCo asks positive mass and moments only of bodies with a joint.
  if (!body.moves) return body.inertial.mass >= 0.0 && p.smallest >= -rounding && triangle;
  return body.inertial.mass > 0.0 && p.smallest > std::max(rounding, kMujocoMinimum) && triangle;
}

namespace {

/// Runs the repairs of the header over a tree, children first.
class Repairer {
 public:
  explicit Repairer(std::vector<Body> bodies) : bodies_(std::move(bodies)) {
    for (const Body& b : bodies_) {
      scale_ = std::max(scale_, b.inertial.inertia.trace());
      heaviest_ = std::max(heaviest_, b.inertial.mass);
    }
    if (scale_ <= 0.0) scale_ = 1.0;
    if (heaviest_ <= 0.0) heaviest_ = 1.0;
  }

  InertiaRepair run() {
    for (std::size_t i = bodies_.size(); i-- > 0;) {
      Body& body = bodies_[i];
      if (admissible_for_mujoco(body)) continue;
      if (add_mass_on_fixed_axis(body)) {
        note(i, true,
             fmt::format("mass 0 -> {:.3g} kg on its fixed joint axis (a point that never moves)", body.inertial.mass));
      }
      if (!admissible_for_mujoco(body)) move_from_parent(i);
      if (!admissible_for_mujoco(body)) approximate(i);
      if (!admissible_for_mujoco(body)) out_.unrepaired.push_back(static_cast<int>(i));
    }
    out_.bodies = std::move(bodies_);
    return std::move(out_);
  }

 private:
  // A mass on the fixed axis of a revolute joint on the base never moves; it goes where the axis
  // passes nearest the (irrelevant) centre of mass.
  bool add_mass_on_fixed_axis(Body& body) const {
    const bool on_fixed_axis = body.moves && body.parent < 0 && body.joint == robot::JointType::Revolute;
    if (body.inertial.mass != 0.0 || !on_fixed_axis) return false;
    add_point_mass(body.inertial, kRepairMass * heaviest_, Eigen::Vector3d(0, 0, body.inertial.com.z()));
    return true;
  }

  /// Smallest amount of `unit` that makes the tensor admissible, -1 if there is none. A thin rod
  /// or plate keeps a zero second moment that `unit` may not reach: the triangle inequality is
  /// then only asked to hold with equality, which MuJoCo accepts.
  [[nodiscard]] double amount_needed(const Eigen::Matrix3d& inertia, const Eigen::Matrix3d& unit) const {
    const double margin = kMomentMargin * scale_;
    const double rounding = kTriangleSlack * scale_;
    const double reachable = principal(inertia + kLargestAmount * scale_ * unit).slack;
    const double required_slack = std::min(margin, reachable) - rounding;
    const auto ok = [&](double amount) {
      const Principal p = principal(inertia + amount * unit);
      return p.smallest >= margin && p.slack >= required_slack;
    };
    return smallest_amount(ok, margin, kLargestAmount * scale_);
  }

  /// Whether the parent, after giving `taken`, is still admissible or can repair itself exactly
  /// (its own turn comes later).
  [[nodiscard]] bool parent_can_give(const Body& parent, const Eigen::Matrix3d& taken) const {
    Body copy = parent;
    copy.inertial.inertia -= taken;
    add_mass_on_fixed_axis(copy);
    return admissible_for_mujoco(copy) || amount_needed(copy.inertial.inertia, movable_tensor(copy)) > 0.0;
  }

  void move_from_parent(std::size_t i) {
    Body& body = bodies_[i];
    const Eigen::Matrix3d unit = movable_tensor(body);
    const double amount = amount_needed(body.inertial.inertia, unit);
    if (amount <= 0.0) return;
    const Eigen::Matrix3d in_parent = body.rotation * (amount * unit) * body.rotation.transpose();
    if (body.parent >= 0 && !parent_can_give(bodies_[static_cast<std::size_t>(body.parent)], in_parent)) return;
    body.inertial.inertia += amount * unit;
    std::string from = "added: the parent is the fixed base";
    if (body.parent >= 0) {
      Body& parent = bodies_[static_cast<std::size_t>(body.parent)];
      parent.inertial.inertia -= in_parent;
      from = "moved from " + parent.name;
    }
    const char* what = unit == Eigen::Matrix3d::Identity() ? "1" : "(1 - z z^T)";
    note(i, true,
         fmt::format("inertia + {:.6g} * {} about its joint ({}; the dynamics are unchanged)", amount, what, from));
  }

  // The last resort when no exact move exists: the smallest mass and isotropic inertia MuJoCo
  // takes (1e-9 of the robot's scale), which changes the dynamics by about that much.
  void approximate(std::size_t i) {
    Inertial& in = bodies_[i].inertial;
    if (bodies_[i].moves && in.mass == 0.0) {
      add_point_mass(in, kRepairMass * heaviest_, in.com);
      note(i, false, fmt::format("mass 0 -> {:.3g} kg at its centre of mass", in.mass));
    }
    const double amount = amount_needed(in.inertia, Eigen::Matrix3d::Identity());
    if (amount <= 0.0) return;
    in.inertia += amount * Eigen::Matrix3d::Identity();
    note(i, false, fmt::format("inertia + {:.3g} * 1 ({:.1g} of the largest inertia)", amount, amount / scale_));
  }

  void note(std::size_t i, bool exact, const std::string& what) {
    out_.notes.push_back({static_cast<int>(i), exact, bodies_[i].name + ": " + what});
  }

  std::vector<Body> bodies_;
  InertiaRepair out_;
  double scale_ = 0.0;     // the largest trace of an inertia tensor
  double heaviest_ = 0.0;  // the largest mass
};

}  // namespace

InertiaRepair repair_for_mujoco(std::vector<Body> bodies) { return Repairer(std::move(bodies)).run(); }

}  // namespace dyncc::exporting
