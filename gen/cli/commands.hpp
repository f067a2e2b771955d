// Each dyncc subcommand registers itself on the CLI11 app; main() only wires them up.
#pragma once

#include <CLI/CLI.hpp>

namespace dyncc::cli {

/// Exit codes shared by every subcommand.
enum ExitCode : int { kSuccess = 0, kCheckFailed = 1, kBadInput = 2 };

void register_expr_command(CLI::App& app, int& exit_code);
void register_check_command(CLI::App& app, int& exit_code);
void register_eval_command(CLI::App& app, int& exit_code);
void register_derive_command(CLI::App& app, int& exit_code);
void register_verify_command(CLI::App& app, int& exit_code);

}  // namespace dyncc::cli
