#include "export/joint_coupling.hpp"

#include <fmt/core.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "export/export_error.hpp"

namespace dyncc::exporting {
namespace {

/// The coordinate a joint follows alone, or -1 when it mixes several (or none).
int single_coordinate(const JointCoordinate& joint) {
  int found = -1;
  for (std::size_t k = 0; k < joint.coefficients.size(); ++k) {
    if (joint.coefficients[k] == 0.0) continue;
    if (found >= 0) return -1;
    found = static_cast<int>(k);
  }
  return found;
}

Eigen::RowVectorXd row_of(const JointCoordinate& joint) {
  return Eigen::Map<const Eigen::RowVectorXd>(joint.coefficients.data(),
                                              static_cast<Eigen::Index>(joint.coefficients.size()));
}

Eigen::Index rank_of(const Eigen::MatrixXd& rows) {
  if (rows.rows() == 0) return 0;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(rows);
  lu.setThreshold(1e-10);
  return lu.rank();
}

}  // namespace

JointCoupling couple_joints(const robot::RobotDescription& robot, const std::vector<JointCoordinate>& joints) {
  const std::size_t n = robot.coordinates.size();
  JointCoupling out;
  out.coordinate_joints.resize(n);
  std::vector<bool> chosen(joints.size(), false);

  // First the joints driven by one coordinate alone (the first such joint per coordinate).
  for (std::size_t b = 0; b < joints.size(); ++b) {
    const int k = single_coordinate(joints[b]);
    if (k < 0) continue;
    CoordinateJoint& cj = out.coordinate_joints[static_cast<std::size_t>(k)];
    if (cj.body >= 0) continue;
    cj = {static_cast<int>(b), joints[b].coefficients[static_cast<std::size_t>(k)]};
    chosen[b] = true;
    out.independent.push_back(static_cast<int>(b));
  }
  // Then any joint that adds a direction, in file order, until the coordinates are determined.
  Eigen::MatrixXd basis(0, static_cast<Eigen::Index>(n));
  auto append = [&basis](const Eigen::RowVectorXd& row) {
    basis.conservativeResize(basis.rows() + 1, Eigen::NoChange);
    basis.row(basis.rows() - 1) = row;
  };
  for (const int b : out.independent) append(row_of(joints[static_cast<std::size_t>(b)]));
  for (std::size_t b = 0; b < joints.size() && out.independent.size() < n; ++b) {
    if (chosen[b] || !joints[b].moves()) continue;
    const Eigen::Index before = rank_of(basis);
    append(row_of(joints[b]));
    if (rank_of(basis) > before) {
      chosen[b] = true;
      out.independent.push_back(static_cast<int>(b));
    } else {
      basis.conservativeResize(basis.rows() - 1, Eigen::NoChange);
    }
  }
  if (out.independent.size() < n) {
    throw ExportError{fmt::format(
        "{}: error: the joint variables determine only {} of the {} coordinates (some coordinates only ever "
        "appear in fixed combinations), so no tree of joints can represent them",
        robot.source_path.string(), out.independent.size(), n)};
  }
  std::sort(out.independent.begin(), out.independent.end());

  // q = A_S^-1 joint_S, so joint_b = A_b A_S^-1 joint_S: the factors are A_S^-T A_b^T.
  Eigen::MatrixXd a_independent(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    a_independent.row(static_cast<Eigen::Index>(i)) = row_of(joints[static_cast<std::size_t>(out.independent[i])]);
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> solver(a_independent.transpose());
  for (std::size_t b = 0; b < joints.size(); ++b) {
    if (chosen[b] || !joints[b].moves()) continue;
    const Eigen::VectorXd factors = solver.solve(row_of(joints[b]).transpose());
    const double largest = factors.cwiseAbs().maxCoeff();
    Coupling c{static_cast<int>(b), {}};
    for (std::size_t i = 0; i < n; ++i) {
      double f = factors[static_cast<Eigen::Index>(i)];
      // The rows are exact small rationals, so factors are usually integers: drop and snap the
      // solve's round-off rather than write 0.9999999999999998 into a constraint.
      if (std::abs(f - std::round(f)) <= 1e-12 * largest) f = std::round(f);
      if (f != 0.0) c.terms.push_back({out.independent[i], f});
    }
    out.couplings.push_back(std::move(c));
  }
  return out;
}

}  // namespace dyncc::exporting
