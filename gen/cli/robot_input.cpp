#include "cli/robot_input.hpp"

#include <fmt/core.h>

#include "robot/load.hpp"

namespace dyncc::cli {

std::optional<robot::RobotDescription> load_description(const std::string& path) {
  robot::LoadResult result = robot::load_robot(path);
  for (const robot::Diagnostic& d : result.diagnostics) fmt::print(stderr, "{}\n", d.format());
  if (!result.ok()) return std::nullopt;
  return std::move(result.robot);
}

std::unique_ptr<pipeline::Derivation> load_and_derive(const std::string& path,
                                                      const pipeline::DerivationOptions& options) {
  auto robot = load_description(path);
  if (!robot) return nullptr;
  try {
    auto d = pipeline::derive(std::move(*robot), options);
    for (const std::string& w : d->warnings) fmt::print(stderr, "{}\n", w);
    return d;
  } catch (const pipeline::DerivationError& e) {
    fmt::print(stderr, "{}\n", e.message);
    return nullptr;
  }
}

}  // namespace dyncc::cli
