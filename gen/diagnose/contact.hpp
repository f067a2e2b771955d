// Where a point of the payload link is, seen by a horizontal surface: its height along -gravity
// and the joint torque of a unit upward force on it. Both are linear in the point's coordinates
// c in the link frame, so they come from four basis terms (the link origin and its three axes),
// read off the model itself: the potential energy of a unit mass (first moment) is |g| times the
// height of the origin (axis), and the gravity part of its regressor column is the gradient.
// Sliding along the surface needs the point's horizontal velocity, which gravity does not see:
// for that the payload link's frame and velocity Jacobians (kinematics) are compiled once.
// Shared by the contact effect (gen/diagnose/effects.cpp) and the synthetic logs that inject one.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <memory>

#include "pipeline/derivation.hpp"
#include "sym/evaluate.hpp"

namespace dyncc::diagnose {

class ContactGeometry {
 public:
  /// Empty (valid() false) when the robot has no payload link with mass and first moments, or no
  /// gravity.
  explicit ContactGeometry(const pipeline::Derivation& derivation);
  [[nodiscard]] bool valid() const { return link_ >= 0; }

  struct Basis {
    Eigen::Vector4d height;  // of the origin, then of the unit x, y, z axes (m)
    Eigen::MatrixXd lever;   // n x 4: minus the torque of a unit upward force at each (N m / N)
  };
  /// The basis at a configuration.
  [[nodiscard]] Basis at(const Eigen::VectorXd& q) const;
  /// The bases at many configurations (one per row of q), computed together: the same numbers.
  [[nodiscard]] std::vector<Basis> at_rows(const Eigen::MatrixXd& q) const;

  /// The payload link's frame and velocity Jacobians at a configuration, in base coordinates.
  struct Frame {
    Eigen::Matrix3d rotation;         // link -> base
    Eigen::Vector3d origin;           // of the link frame, base coordinates
    Eigen::MatrixXd linear, angular;  // 3 x n: origin velocity and angular velocity per coordinate rate
    /// The velocity Jacobian of the point c of the link (3 x n, base coordinates).
    [[nodiscard]] Eigen::MatrixXd point_jacobian(const Eigen::Vector3d& c) const;
  };
  [[nodiscard]] Frame frame(const Eigen::VectorXd& q) const;
  [[nodiscard]] std::vector<Frame> frames(const Eigen::MatrixXd& q) const;  // one per row of q
  /// Unit vector along gravity (base coordinates).
  [[nodiscard]] Eigen::Vector3d down() const { return down_; }

  /// Height of the point c and minus the torque of a unit upward force on it, from a basis.
  static double height(const Basis& b, const Eigen::Vector3d& c) { return b.height[0] + b.height.tail<3>().dot(c); }
  static Eigen::VectorXd lever(const Basis& b, const Eigen::Vector3d& c) {
    return b.lever.col(0) + b.lever.rightCols(3) * c;
  }
  /// The arm's length scale from the heights of the link origin over a motion: how far it sits
  /// from the base plus how far it travels (at least 5 cm). Contact points are sought within it.
  static double scale(const Eigen::VectorXd& origin_heights) {
    return std::max(0.05, origin_heights.cwiseAbs().maxCoeff() + origin_heights.maxCoeff() - origin_heights.minCoeff());
  }

 private:
  const pipeline::Derivation* derivation_;
  int link_ = -1;
  int columns_[4] = {-1, -1, -1, -1};
  double g_ = 0;
  Eigen::Vector3d down_ = Eigen::Vector3d::Zero();
  std::shared_ptr<const sym::CompiledFunction> kinematics_;  // q -> rotation (9), origin (3), linear (3n), angular (3n)
};

}  // namespace dyncc::diagnose
