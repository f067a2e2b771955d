// `dyncc derive`: the model in readable form (placeholder until the printer lands).
#include <fmt/core.h>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "sym/print.hpp"

namespace dyncc::cli {

void register_derive_command(CLI::App& app, int& exit_code) {
  auto robot = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("derive", "Derive H, C, g, friction, base parameters and Y in readable form");
  cmd->add_option("ROBOT", *robot, "Robot description (YAML)")->required();
  cmd->callback([&exit_code, robot] {
    const auto d = load_and_derive(*robot);
    if (!d) {
      exit_code = kBadInput;
      return;
    }
    for (const auto& t : d->timings) fmt::print("{:<24} {:8.2f} ms\n", t.stage, t.milliseconds);
    for (const auto& b : d->base.list) fmt::print("{} = {}\n", b.name, sym::to_string(b.definition));
  });
}

}  // namespace dyncc::cli
