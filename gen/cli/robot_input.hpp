// Loading a description for a subcommand: diagnostics to stderr, exit code on failure.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "pipeline/derivation.hpp"
#include "robot/description.hpp"

namespace dyncc::cli {

/// Loads and validates; prints every diagnostic (errors and warnings) to stderr.
/// Returns nothing on error (the caller exits with kBadInput).
std::optional<robot::RobotDescription> load_description(const std::string& path);

/// Loads and derives the model; prints diagnostics and derivation errors. Null on failure.
std::unique_ptr<pipeline::Derivation> load_and_derive(const std::string& path,
                                                      const pipeline::DerivationOptions& options = {});

}  // namespace dyncc::cli
