// dyncc: robot description -> verified dynamics -> generated controller code.
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <exception>

#include "cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"dyncc: derives verified rigid-body dynamics from a robot description and emits controller code"};
  app.set_version_flag("--version", std::string("dyncc ") + DYNCC_VERSION);
  app.require_subcommand(1);
  int exit_code = dyncc::cli::kSuccess;
  dyncc::cli::register_expr_command(app, exit_code);
  dyncc::cli::register_check_command(app, exit_code);
  dyncc::cli::register_derive_command(app, exit_code);
  dyncc::cli::register_eval_command(app, exit_code);
  dyncc::cli::register_verify_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    // CLI11 returns 0 for --help/--version; every real usage error is our "bad input".
    return code == 0 ? 0 : dyncc::cli::kBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "dyncc: internal error: {}\n", e.what());
    return dyncc::cli::kBadInput;
  }
  return exit_code;
}
