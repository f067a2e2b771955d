#include "pipeline/derivation.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "sym/modular.hpp"

namespace dyncc::pipeline {
namespace {

class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>& out) : out_(out), start_(std::chrono::steady_clock::now()) {}
  void lap(std::string stage) {
    const auto now = std::chrono::steady_clock::now();
    out_.push_back({std::move(stage), std::chrono::duration<double, std::milli>(now - start_).count()});
    start_ = now;
  }

 private:
  std::vector<StageTime>& out_;
  std::chrono::steady_clock::time_point start_;
};

std::string loop_error(const robot::RobotDescription& robot, const robot::Loop& loop, const kin::LoopCheck& check) {
  std::string at;
  for (const auto& [name, value] : check.sample) at += fmt::format("{}{}={}", at.empty() ? "" : ", ", name, value);
  return fmt::format(
      "{}:{}:{}: error: loops.{}: the loop does not close: at {} the two points are {:.6g} m apart (gap "
      "[{:.6g}, {:.6g}, {:.6g}] in the base frame)",
      robot.source_path.string(), loop.location.line, loop.location.column, loop.name, at,
      std::hypot(check.residual[0], check.residual[1], check.residual[2]), check.residual[0], check.residual[1],
      check.residual[2]);
}

}  // namespace

double Derivation::total_milliseconds() const {
  double total = 0.0;
  for (const auto& t : timings) total += t.milliseconds;
  return total;
}

std::unique_ptr<Derivation> derive(robot::RobotDescription robot, const DerivationOptions& options) {
  auto d = std::make_unique<Derivation>();
  d->robot = std::move(robot);
  StageClock clock(d->timings);
  try {
    d->kinematics = kin::compute_kinematics(d->robot);
  } catch (const std::invalid_argument& e) {
    throw DerivationError{d->robot.source_path.string() + ": error: " + e.what()};
  }
  clock.lap("kinematics");
  d->loops = kin::check_loops(d->robot, d->kinematics);
  for (std::size_t i = 0; i < d->loops.size(); ++i) {
    if (!d->loops[i].closed) throw DerivationError{loop_error(d->robot, d->robot.loops[i], d->loops[i])};
  }
  clock.lap("loop closure proofs");
  d->model = dyn::derive_model(d->robot, d->kinematics);
  clock.lap("H, C, gravity");
  d->regressor = dyn::derive_regressor(d->model);
  clock.lap("regressor");
  d->numeric = std::make_unique<dyn::NumericModel>(d->robot, d->model, d->regressor);
  clock.lap("numeric compilation");
  base::BaseParameterOptions base_options;
  base_options.prove = options.prove_base_parameters;
  try {
    d->base = base::find_base_parameters(d->robot, d->model, d->regressor, *d->numeric, base_options);
  } catch (const sym::NotModular& e) {
    throw DerivationError{d->robot.source_path.string() +
                          ": error: the base parameters cannot be found exactly: " + e.what()};
  }
  clock.lap("base parameters");
  if (!d->robot.base_parameters.empty()) {
    d->grouping = base::check_grouping(d->robot, d->model, d->base);
    const robot::SourceLocation at = d->robot.base_parameters.front().location;
    const std::string where = fmt::format("{}:{}:{}", d->robot.source_path.string(), at.line, at.column);
    for (const std::string& w : d->grouping->warnings)
      d->warnings.push_back(fmt::format("{}: warning: base_parameters: {}", where, w));
    if (!d->grouping->errors.empty()) {
      std::string message;
      for (const std::string& e : d->grouping->errors)
        message += fmt::format("{}{}: error: base_parameters: {}", message.empty() ? "" : "\n", where, e);
      throw DerivationError{message};
    }
    clock.lap("user grouping check");
  }
  return d;
}

}  // namespace dyncc::pipeline
