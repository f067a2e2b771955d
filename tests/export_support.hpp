// Shared helpers of the export tests: the description's joint variables as functions of the
// coordinates (running dyncc and temporary paths: cli_support.hpp).
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <Eigen/Dense>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "cli_support.hpp"
#include "robot/description.hpp"
#include "sym/diff.hpp"
#include "sym/evaluate.hpp"

namespace dyncc::test {

/// The description's joint variables (theta of revolute links, d of prismatic ones) and their
/// gradients by the coordinates, from the joint expressions themselves: the rows of
/// G = d(joint variables)/dq. Independent of gen/export and of dyncc's dynamics.
class JointVariables {
 public:
  explicit JointVariables(const robot::RobotDescription& robot) : robot_(robot) {
    for (const auto& [name, value] : robot.constant_doubles()) values_[name] = value;
    for (const robot::Link& link : robot.links) {
      std::vector<sym::Expr> rates;
      for (const sym::Expr q : robot.coordinates) rates.push_back(sym::diff(link.joint_expression(), q));
      rates_.push_back(std::move(rates));
    }
  }

  /// Joint variable of a link at q, measured from its value at q = 0 (as exported joints read).
  [[nodiscard]] double value(std::size_t link, const Eigen::VectorXd& q) {
    const sym::Expr e = robot_.links[link].joint_expression();
    set(Eigen::VectorXd::Zero(q.size()));
    const double at_zero = sym::evaluate(e, values_);
    set(q);
    return sym::evaluate(e, values_) - at_zero;
  }

  [[nodiscard]] Eigen::RowVectorXd gradient(std::size_t link, const Eigen::VectorXd& q) {
    set(q);
    Eigen::RowVectorXd row(q.size());
    for (Eigen::Index k = 0; k < q.size(); ++k)
      row[k] = sym::evaluate(rates_[link][static_cast<std::size_t>(k)], values_);
    return row;
  }

  [[nodiscard]] bool moves(std::size_t link) {
    return !gradient(link, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot_.coordinates.size()))).isZero(0.0);
  }

 private:
  void set(const Eigen::VectorXd& q) {
    for (std::size_t k = 0; k < robot_.coordinates.size(); ++k) {
      values_[robot_.coordinates[k].name()] = q[static_cast<Eigen::Index>(k)];
    }
  }

  const robot::RobotDescription& robot_;
  std::unordered_map<std::string, double> values_;
  std::vector<std::vector<sym::Expr>> rates_;
};

/// Reflected rotor inertia per coordinate (what a format without armature leaves out of H).
inline Eigen::VectorXd rotor_inertias(const robot::RobotDescription& robot) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.coordinates.size()));
  std::unordered_map<std::string, double> values;
  for (const auto& [name, value] : robot.constant_doubles()) values[name] = value;
  for (const auto& [name, value] : robot.nominal_values()) values[name] = value;
  for (const robot::Rotor& r : robot.rotors) out[r.coordinate] = sym::evaluate(r.reflected_inertia(), values);
  return out;
}

}  // namespace dyncc::test
