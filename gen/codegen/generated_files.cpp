#include "codegen/generated_files.hpp"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "base/initial_estimate.hpp"
#include "codegen/emit_cpp.hpp"
#include "codegen/templates.hpp"
#include "sym/print.hpp"

namespace dyncc::codegen {
namespace {

struct Sizes {
  std::size_t n = 0, r = 0, links = 0;
  [[nodiscard]] std::string of(const std::string& array) const {
    if (array == "H" || array == "C") return fmt::format("{}", n * n);
    if (array == "p" || array == "YTe") return fmt::format("{}", r);
    if (array == "Y") return fmt::format("{}", n * r);
    if (array == "link") return fmt::format("{}", links);
    return fmt::format("{}", n);
  }
};

std::string parameter_list(const Function& f, const std::string& scalar) {
  std::vector<std::string> items;
  for (std::size_t k = 0; k < f.parameters.size(); ++k) {
    items.push_back(fmt::format("{}{}* {}", f.parameter_is_output[k] ? "" : "const ", scalar, f.parameters[k]));
  }
  return fmt::format("{}", fmt::join(items, ", "));
}

std::string argument_sizes(const Function& f, const Sizes& sizes) {
  std::vector<std::string> items;
  items.reserve(f.parameters.size());
  for (const std::string& parameter : f.parameters)
    items.push_back(fmt::format("{}[{}]", parameter, sizes.of(parameter)));
  return fmt::format("{}", fmt::join(items, ", "));
}

std::string counts_text(const OpCounts& c) {
  return fmt::format("{} mul, {} add, {} div, {} sin/cos, {} sqrt", c.mul, c.add, c.div, c.trig, c.sqrt);
}

std::string quoted_list(const std::vector<std::string>& items) {
  std::vector<std::string> q;
  q.reserve(items.size());
  for (const auto& s : items) q.push_back(fmt::format("\"{}\"", s));
  return fmt::format("{}", fmt::join(q, ", "));
}

std::string number_list(const Eigen::VectorXd& v) {
  std::vector<std::string> items;
  for (Eigen::Index i = 0; i < v.size(); ++i) items.push_back(fmt::format("{}", v[i]));
  return fmt::format("{}", fmt::join(items, ", "));
}

std::string fill(std::string_view tmpl, const fmt::format_args& args) { return fmt::vformat(tmpl, args); }

}  // namespace

std::string sha256_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 failed");
  }
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

std::map<std::string, std::string> generated_files(const pipeline::Derivation& d, const ModelFunctions& functions,
                                                   const GenerationInfo& info) {
  const robot::RobotDescription& robot = d.robot;
  Sizes sizes{d.model.q.size(), d.base.list.size(), robot.parameters.size()};

  std::vector<std::string> coordinate_names, base_names, base_definitions, link_names;
  for (const sym::Expr q : d.model.q) coordinate_names.push_back(q.name());
  for (const auto& b : d.base.list) {
    base_names.push_back(b.name);
    base_definitions.push_back(fmt::format("    \"{}\",\n", sym::to_string(b.definition)));
  }
  Eigen::VectorXd link_nominal(static_cast<Eigen::Index>(robot.parameters.size()));
  for (std::size_t k = 0; k < robot.parameters.size(); ++k) {
    link_names.push_back(robot.parameters[k].name);
    link_nominal[static_cast<Eigen::Index>(k)] = robot.parameters[k].nominal;
  }
  const Eigen::VectorXd base_nominal = d.base.values(d.numeric->nominal_standard_values());
  Eigen::VectorXd initial = base_nominal;
  const bool has_initial = d.grouping && d.grouping->complete && !robot.initial_estimate.empty();
  if (has_initial) initial = base::map_initial_estimate(robot, *d.grouping).base_values;

  std::string declarations, forwarders, definitions, instantiations, rows;
  nlohmann::ordered_json report_functions = nlohmann::ordered_json::array();
  auto json_counts = [](const OpCounts& c) {
    return nlohmann::ordered_json{{"mul", c.mul},   {"add", c.add},     {"div", c.div}, {"trig", c.trig},
                                  {"sqrt", c.sqrt}, {"other", c.other}, {"neg", c.neg}};
  };
  for (const Function& f : functions.functions) {
    const RenderedFunction r = render_body(f);
    const std::string params = parameter_list(f, "S");
    declarations += fmt::format("/// {}\n/// {}; per call: {}.\ntemplate <typename S>\nvoid {}({});\n\n", f.summary,
                                argument_sizes(f, sizes), counts_text(r.counts), f.name, params);
    std::vector<std::string> args;
    for (const auto& p : f.parameters) args.push_back(p);
    forwarders += fmt::format("  template <typename S>\n  static void {}({}) {{\n    {}::{}<S>({});\n  }}\n", f.name,
                              params, fmt::format("dyncc::generated::{}", robot.name), f.name, fmt::join(args, ", "));
    std::string body;
    for (std::size_t k = 0; k < f.parameters.size(); ++k) {
      if (!r.parameter_used[k] && !f.parameter_is_output[k])
        body += fmt::format("  static_cast<void>({});  // not needed by this model\n", f.parameters[k]);
    }
    body += r.body;
    definitions +=
        fill(templates::function_cpp,
             fmt::make_format_args(fmt::arg("summary", f.summary), fmt::arg("operations", counts_text(r.counts)),
                                   fmt::arg("function", f.name), fmt::arg("parameters", params),
                                   fmt::arg("body", body)));
    for (const char* scalar : {"float", "double"}) {
      instantiations += fmt::format("template void {}<{}>({});\n", f.name, scalar, parameter_list(f, scalar));
    }
    rows += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} | {} |\n", f.name, r.counts.mul, r.counts.add,
                        r.counts.div, r.counts.trig, r.counts.sqrt, r.counts.other, r.temporaries);
    report_functions.push_back(
        {{"name", f.name}, {"operations", json_counts(r.counts)}, {"temporaries", r.temporaries}});
  }
  std::string standard_rows;
  nlohmann::ordered_json standard_json = nlohmann::ordered_json::array();
  for (const Function& f : functions.standard_parameter_variants) {
    const OpCounts c = f.program.count_operations();
    standard_rows +=
        fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n", f.name, c.mul, c.add, c.div, c.trig, c.sqrt, c.other);
    standard_json.push_back({{"name", f.name}, {"operations", json_counts(c)}});
  }

  const std::string dir_name =
      std::filesystem::path(info.out_dir).lexically_normal().filename().string().empty()
          ? std::filesystem::path(info.out_dir).lexically_normal().parent_path().filename().string()
          : std::filesystem::path(info.out_dir).lexically_normal().filename().string();
  const std::string description = robot.description.empty() ? robot.name : robot.description;
  const std::string dof = fmt::format("{}", sizes.n), r = fmt::format("{}", sizes.r),
                    links = fmt::format("{}", sizes.links), standard = fmt::format("{}", d.model.params.list.size());
  const std::string coordinate_list = quoted_list(coordinate_names), base_list = quoted_list(base_names),
                    link_list = quoted_list(link_names),
                    definitions_list = fmt::format("{}", fmt::join(base_definitions, "")),
                    link_values = number_list(link_nominal), base_values = number_list(base_nominal),
                    initial_values = number_list(initial);
  const auto common = [&](std::string_view tmpl) {
    return fill(tmpl,
                fmt::make_format_args(fmt::arg("version", info.version), fmt::arg("source", info.source),
                                      fmt::arg("source_hash", info.source_hash), fmt::arg("out_dir", info.out_dir),
                                      fmt::arg("name", robot.name), fmt::arg("description", description),
                                      fmt::arg("dof", dof), fmt::arg("base_count", r), fmt::arg("link_count", links),
                                      fmt::arg("standard_count", standard),
                                      fmt::arg("coordinate_names", coordinate_list), fmt::arg("base_names", base_list),
                                      fmt::arg("base_definitions", definitions_list), fmt::arg("link_names", link_list),
                                      fmt::arg("link_nominal", link_values), fmt::arg("base_nominal", base_values),
                                      fmt::arg("has_initial_estimate", has_initial ? "true" : "false"),
                                      fmt::arg("initial_estimate", initial_values),
                                      fmt::arg("declarations", declarations), fmt::arg("forwarders", forwarders),
                                      fmt::arg("definitions", definitions), fmt::arg("instantiations", instantiations),
                                      fmt::arg("rows", rows), fmt::arg("standard_rows", standard_rows),
                                      fmt::arg("dir_name", dir_name)));
  };

  std::map<std::string, std::string> files;
  files["model.hpp"] = common(templates::model_hpp);
  files["model.cpp"] = common(templates::model_cpp);
  files["CMakeLists.txt"] = common(templates::cmakelists_txt);
  files["REPORT.md"] = common(templates::report_md);
  nlohmann::ordered_json report = {{"robot", robot.name},
                                   {"generator", fmt::format("dyncc {}", info.version)},
                                   {"source", info.source},
                                   {"source_sha256", info.source_hash},
                                   {"dof", sizes.n},
                                   {"base_parameters", sizes.r},
                                   {"standard_parameters", d.model.params.list.size()},
                                   {"functions", report_functions},
                                   {"standard_parameter_variants", standard_json}};
  files["report.json"] = report.dump(2) + "\n";
  return files;
}

}  // namespace dyncc::codegen
