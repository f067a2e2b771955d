#include "baselines.hpp"

#include <stdexcept>
#include <string>

#include "export/export_error.hpp"
#include "rbd_from_description.hpp"
#include "robot/load.hpp"

namespace dyncc::bench {

Baselines load_baselines(const std::filesystem::path& description) {
  robot::LoadResult loaded = robot::load_robot(description);
  if (!loaded.ok()) {
    std::string messages;
    for (const robot::Diagnostic& d : loaded.diagnostics) messages += d.format() + "\n";
    throw std::runtime_error(description.string() + " does not load:\n" + messages);
  }
  Baselines b{std::move(*loaded.robot), nullptr, nullptr};
  b.eigen = std::make_unique<EigenRbd>(tree_from_description(b.robot));
  try {
    b.mujoco = mujoco_baseline_for(b.robot);
  } catch (const exporting::ExportError& e) {
    throw std::invalid_argument(e.message);
  }
  return b;
}

}  // namespace dyncc::bench
