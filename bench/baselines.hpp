// The speed-comparison baselines for one robot description, ready to call: the plain Eigen
// rigid-body algorithms (eigen_rbd.hpp) and MuJoCo on the exported MJCF (mujoco_baseline.hpp).
// Benchmark programs (baseline_bench.cpp, and the generated-code benchmarks beside it) load them
// here so every program times the same baselines on the same models.
#pragma once

#include <filesystem>
#include <memory>

#include "eigen_rbd.hpp"
#include "mujoco_baseline.hpp"
#include "robot/description.hpp"

namespace dyncc::bench {

struct Baselines {
  robot::RobotDescription robot;
  std::unique_ptr<EigenRbd> eigen;
  std::unique_ptr<MujocoBaseline> mujoco;
};

/// Loads the description (nominal parameter values) and builds both baselines. Throws
/// std::runtime_error when the description does not load, std::invalid_argument when it has
/// no tree-of-joints form.
Baselines load_baselines(const std::filesystem::path& description);

}  // namespace dyncc::bench
