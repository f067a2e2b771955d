// `dyncc export`: the arm for other tools, as MuJoCo MJCF or URDF (gen/export/).
#include <fmt/core.h>

#include <fstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "export/export_error.hpp"
#include "export/export_model.hpp"
#include "export/mjcf_writer.hpp"
#include "export/urdf_writer.hpp"

namespace dyncc::cli {

int run_export(const ExportOptions& o) {
  const auto robot = load_description(o.robot);
  if (!robot) return kBadInput;
  std::string document;
  std::vector<robot::Diagnostic> warnings;
  try {
    const exporting::ExportModel model = exporting::build_export_model(*robot);
    warnings = model.warnings;
    document = o.format == "urdf" ? exporting::write_urdf(model, warnings) : exporting::write_mjcf(model, warnings);
  } catch (const exporting::ExportError& e) {
    fmt::print(stderr, "{}\n", e.message);
    return kBadInput;
  }
  for (const robot::Diagnostic& w : warnings) fmt::print(stderr, "{}\n", w.format());
  if (o.out.empty()) {
    fmt::print("{}", document);
    return kSuccess;
  }
  std::ofstream file(o.out, std::ios::binary);
  file << document;
  file.close();
  if (!file) {
    fmt::print(stderr, "error: cannot write {}\n", o.out);
    return kBadInput;
  }
  return kSuccess;
}

}  // namespace dyncc::cli
