#include "robot/load.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <exception>
#include <fstream>
#include <sstream>

#include "robot/load_state.hpp"

namespace dyncc::robot {

namespace {

using detail::LoadState;
using detail::Located;
using detail::YamlReader;

const std::vector<std::string> kTopLevelFields = {"name",
                                                  "description",
                                                  "convention",
                                                  "gravity",
                                                  "coordinates",
                                                  "constants",
                                                  "links",
                                                  "friction",
                                                  "rotor",
                                                  "joint_limits",
                                                  "parameters",
                                                  "loops",
                                                  "base_parameters",
                                                  "initial_estimate",
                                                  "physical_consistency"};

LoadResult finish(const DiagnosticSink& sink, std::optional<RobotDescription> robot) {
  LoadResult result;
  result.diagnostics = sink.sorted();
  if (!sink.has_errors()) result.robot = std::move(robot);
  return result;
}

// Parameter names given nominal values, read before the links so an unknown parameter used in
// geometry gets "is an unknown parameter" rather than "unknown symbol".
std::vector<std::string> prescan_parameter_names(const std::map<std::string, Located>& top) {
  std::vector<std::string> names;
  const auto parameters = top.find("parameters");
  if (parameters == top.end() || !parameters->second.node.IsMap()) return names;
  for (auto it = parameters->second.node.begin(); it != parameters->second.node.end(); ++it) {
    if (it->first.IsScalar() && detail::is_identifier(it->first.Scalar())) names.push_back(it->first.Scalar());
  }
  return names;
}

void read_document(YamlReader& reader, LoadState& state, const YAML::Node& document) {
  const Located root = reader.root(document);
  if (!document.IsDefined() || document.IsNull()) {
    reader.sink().error({1, 1}, "",
                        "the file is empty; expected a robot description (a map with name, convention, "
                        "gravity, coordinates and links)");
    return;
  }
  if (!reader.expect_map(root, "a robot description with name, convention, gravity, coordinates and links")) return;
  const auto top = reader.fields(root, kTopLevelFields);
  for (const char* required : {"name", "convention", "gravity", "coordinates", "links"}) {
    if (!top.contains(required)) {
      reader.sink().error(root.location, "", std::string("missing required field '") + required + "'");
    }
  }
  state.nominal_names = prescan_parameter_names(top);
  // Order matters: each section may refer to names declared by the ones before it.
  detail::read_header(reader, state, top);
  const auto section = [&](const char* key, void (*read)(YamlReader&, LoadState&, const Located&)) {
    if (const auto found = top.find(key); found != top.end()) read(reader, state, found->second);
  };
  section("coordinates", detail::read_coordinates);
  section("constants", detail::read_constants);
  section("links", detail::read_links);
  section("friction", detail::read_friction);
  section("rotor", detail::read_rotors);
  section("joint_limits", detail::read_joint_limits);
  section("parameters", detail::read_parameters);
  section("loops", detail::read_loops);
  section("base_parameters", detail::read_base_parameters);
  section("initial_estimate", detail::read_initial_estimate);
  if (top.contains("links")) detail::validate(state, reader.sink());
}

}  // namespace

std::size_t LoadResult::error_count() const {
  return static_cast<std::size_t>(
      std::count_if(diagnostics.begin(), diagnostics.end(), [](const Diagnostic& d) { return d.is_error(); }));
}

std::size_t LoadResult::warning_count() const { return diagnostics.size() - error_count(); }

LoadResult load_robot_from_string(std::string_view text, const std::string& file_label) {
  DiagnosticSink sink(file_label);
  LoadState state;
  state.robot.source_path = file_label;
  try {
    YamlReader reader(text, sink);
    YAML::Node document;
    try {
      document = YAML::Load(std::string(text));
    } catch (const YAML::DeepRecursion& e) {
      sink.error(SourceLocation{e.mark.line + 1, e.mark.column + 1}, "",
                 "invalid YAML: nested too deeply (a robot description needs only a few levels)");
      return finish(sink, std::nullopt);
    } catch (const YAML::Exception& e) {
      // yaml-cpp marks are 0-based; a null mark means "somewhere in the file".
      const SourceLocation at =
          e.mark.is_null() ? SourceLocation{1, 1} : SourceLocation{e.mark.line + 1, e.mark.column + 1};
      sink.error(at, "", "invalid YAML: " + e.msg);
      return finish(sink, std::nullopt);
    }
    read_document(reader, state, document);
  } catch (const YAML::Exception& e) {
    // A conversion the readers did not foresee: report it rather than let it escape.
    sink.error({1, 1}, "", "cannot read the description: " + e.msg);
  } catch (const std::exception& e) {
    sink.error({1, 1}, "", std::string("cannot read the description: ") + e.what());
  }
  return finish(sink, std::move(state.robot));
}

LoadResult load_robot(const std::filesystem::path& path) {
  const std::string label = path.string();
  DiagnosticSink sink(label);
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    sink.error({}, "", std::filesystem::exists(path, error) ? "not a regular file" : "no such file");
    return finish(sink, std::nullopt);
  }
  const auto size = std::filesystem::file_size(path, error);
  if (error) {
    sink.error({}, "", "cannot determine the file size: " + error.message());
    return finish(sink, std::nullopt);
  }
  if (size > kMaxFileSize) {
    sink.error({}, "",
               "file is " + std::to_string(size) + " bytes; a robot description may be at most " +
                   std::to_string(kMaxFileSize) + " bytes");
    return finish(sink, std::nullopt);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    sink.error({}, "", "cannot open the file for reading");
    return finish(sink, std::nullopt);
  }
  std::ostringstream contents;
  contents << in.rdbuf();
  LoadResult result = load_robot_from_string(contents.str(), label);
  if (result.robot) result.robot->source_path = path;
  return result;
}

}  // namespace dyncc::robot
