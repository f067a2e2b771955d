// Loading a robot description: YAML file -> validated RobotDescription, or diagnostics.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "robot/description.hpp"
#include "robot/diagnostics.hpp"

namespace dyncc::robot {

struct LoadResult {
  std::optional<RobotDescription> robot;  // set when there is no error
  std::vector<Diagnostic> diagnostics;    // errors and warnings, in file order

  [[nodiscard]] bool ok() const { return robot.has_value(); }
  [[nodiscard]] std::size_t error_count() const;
  [[nodiscard]] std::size_t warning_count() const;
};

/// Largest file accepted: a hand-written description is a few kB; anything near this is a mistake.
inline constexpr std::size_t kMaxFileSize = std::size_t{1024} * 1024;

/// Reads, parses and validates a robot description. Never throws for bad input: every problem
/// (unreadable file, YAML syntax, schema, names, expressions, physics) becomes a diagnostic.
LoadResult load_robot(const std::filesystem::path& path);

/// The same for text in memory; `file_label` is what diagnostics name as the file.
LoadResult load_robot_from_string(std::string_view text, const std::string& file_label);

}  // namespace dyncc::robot
