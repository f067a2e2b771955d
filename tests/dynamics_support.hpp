// Shared helpers of the dynamics tests: loading and deriving a description, random states and
// parameter values from the tests' own generator, and relative comparisons.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "pipeline/derivation.hpp"
#include "robot/load.hpp"

namespace dyncc::test {

inline std::filesystem::path robots_dir() { return std::filesystem::path(DYNCC_SOURCE_DIR) / "robots"; }

/// Every description shipped in robots/, sorted.
inline std::vector<std::filesystem::path> shipped_robots() {
  std::vector<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(robots_dir())) {
    if (entry.path().extension() == ".yaml") out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

inline std::string load_messages(const robot::LoadResult& r) {
  std::string s;
  for (const auto& d : r.diagnostics) s += d.format() + "\n";
  return s;
}

/// Loads and derives; fails the current test (returns null) when either step fails.
/// The symbolic proof of the base-parameter regrouping is skipped by default: these tests check
/// the dynamics against independent references; `dyncc verify` runs the proofs.
inline std::unique_ptr<pipeline::Derivation> derive_text(const std::string& text, const std::string& label,
                                                         bool prove_base = false) {
  robot::LoadResult r = robot::load_robot_from_string(text, label);
  if (!r.ok()) {
    ADD_FAILURE() << label << " does not load:\n" << load_messages(r) << "\n" << text;
    return nullptr;
  }
  pipeline::DerivationOptions options;
  options.prove_base_parameters = prove_base;
  try {
    return pipeline::derive(std::move(*r.robot), options);
  } catch (const pipeline::DerivationError& e) {
    ADD_FAILURE() << label << " does not derive: " << e.message << "\n" << text;
  } catch (const std::exception& e) {
    ADD_FAILURE() << label << " does not derive, " << typeid(e).name() << ": " << e.what() << "\n" << text;
  }
  return nullptr;
}

inline std::unique_ptr<pipeline::Derivation> derive_file(const std::filesystem::path& path, bool prove_base = false) {
  robot::LoadResult r = robot::load_robot(path);
  if (!r.ok()) {
    ADD_FAILURE() << path << " does not load:\n" << load_messages(r);
    return nullptr;
  }
  pipeline::DerivationOptions options;
  options.prove_base_parameters = prove_base;
  try {
    return pipeline::derive(std::move(*r.robot), options);
  } catch (const pipeline::DerivationError& e) {
    ADD_FAILURE() << path << " does not derive: " << e.message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << " does not derive, " << typeid(e).name() << ": " << e.what();
  }
  return nullptr;
}

/// The Kraft arm's description (robots/kraft.yaml), derived once per test program.
inline const pipeline::Derivation& kraft_derivation() {
  static const std::unique_ptr<pipeline::Derivation> d = derive_file(robots_dir() / "kraft.yaml");
  return *d;
}

/// The PUMA 560's description (robots/puma560.yaml), derived once per test program.
inline const pipeline::Derivation& puma_derivation() {
  static const std::unique_ptr<pipeline::Derivation> d = derive_file(robots_dir() / "puma560.yaml");
  return *d;
}

/// The Franka Panda's description (robots/panda.yaml), derived once per test program.
inline const pipeline::Derivation& panda_derivation() {
  static const std::unique_ptr<pipeline::Derivation> d = derive_file(robots_dir() / "panda.yaml");
  return *d;
}

/// A random state from the tests' own generator (not dyncc's random_state): angles in
/// [-pi, pi], rates, reference velocities and accelerations in [-2, 2].
inline dyn::State random_state(Eigen::Index n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(-3.14159, 3.14159);
  std::uniform_real_distribution<double> rate(-2.0, 2.0);
  dyn::State s{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    s.q[i] = angle(rng);
    s.qd[i] = rate(rng);
    s.v[i] = rate(rng);
    s.a[i] = rate(rng);
  }
  return s;
}

/// Largest entry of |a - b| relative to the largest entry of the references (at least `floor`).
inline double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double scale,
                                  double floor = 1e-12) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(scale, floor);
}

/// A figure for RecordProperty, in scientific notation (std::to_string would print 0.000000).
inline std::string scientific(double x) {
  std::ostringstream s;
  s << std::scientific << std::setprecision(2) << x;
  return s.str();
}

inline double max_abs(const Eigen::MatrixXd& m) { return m.size() == 0 ? 0.0 : m.cwiseAbs().maxCoeff(); }

}  // namespace dyncc::test
