// Shared helpers of the export tests: running `dyncc export` as a subprocess, temporary output
// paths, and the description's joint variables as functions of the coordinates.
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

#include "robot/description.hpp"
#include "sym/diff.hpp"
#include "sym/evaluate.hpp"

namespace dyncc::test {

/// A path in single quotes for the shell (built with append: GCC 12 warns falsely, -Wrestrict,
/// on "literal" + std::string at -O3).
inline std::string quoted(const std::filesystem::path& p) {
  std::string s = "'";
  s.append(p.string()).append("'");
  return s;
}

struct DynccRun {
  int exit_code = -1;
  std::string errors;  // stderr
};

/// Runs `dyncc ARGUMENTS` (already quoted as needed) with stdout discarded and stderr captured.
inline DynccRun run_dyncc(const std::string& arguments) {
  // `timeout` turns a hang into a failure; 2>&1 first sends stderr to the pipe, then stdout away.
  std::string command = "timeout 120 ";
  command.append(quoted(DYNCC_BINARY)).append(" ").append(arguments).append(" 2>&1 1>/dev/null");
  DynccRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  std::size_t read = 0;
  while ((read = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.errors.append(buffer.data(), read);
  const int status = pclose(pipe);
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  return run;
}

/// A fresh path for an output file of this test.
inline std::filesystem::path output_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "dyncc_export_tests";
  std::filesystem::create_directories(dir);
  return dir / (std::string(info->test_suite_name()) + "." + info->name() + "." + name);
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

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
