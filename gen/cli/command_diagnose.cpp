// `dyncc diagnose ROBOT LOG...`: why the model and the logs of a real arm disagree (gen/diagnose).
#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/diagnosis_output.hpp"
#include "diagnose/diagnosis_report.hpp"
#include "diagnose/joint_log.hpp"

namespace dyncc::cli {

int run_diagnose(const DiagnoseOptions& o) {
  pipeline::DerivationOptions derive_options;
  derive_options.prove_base_parameters = false;  // the base set is needed, its proof is `verify`'s job
  const auto derivation = load_and_derive(o.robot, derive_options);
  if (!derivation) return kBadInput;
  std::vector<diagnose::JointLog> logs;
  diagnose::Dataset data;
  try {
    const diagnose::ColumnMap renames = diagnose::parse_column_map(o.map);
    for (const std::string& path : o.logs) {
      logs.push_back(
          diagnose::read_joint_log(path, static_cast<Eigen::Index>(derivation->robot.coordinates.size()), renames));
    }
    diagnose::ConditioningOptions conditioning;
    conditioning.held_torque = o.held_torque;
    data = diagnose::build_dataset(logs, *derivation, conditioning);
  } catch (const diagnose::LogError& e) {
    fmt::print(stderr, "{}\n", e.what());
    return kBadInput;
  }
  const diagnose::Diagnosis d = diagnose::diagnose(data, *derivation);
  const std::string text = diagnose::diagnosis_text(data, d);
  fmt::print("{}", text);
  const std::string json = diagnose::diagnosis_json(data, d).dump(2) + "\n";
  auto write = [](const std::filesystem::path& path, const std::string& content) {
    std::ofstream out(path);
    out << content;
    if (!out) {
      fmt::print(stderr, "{}: error: cannot write\n", path.string());
      return false;
    }
    return true;
  };
  if (!o.json.empty() && !write(o.json, json)) return kBadInput;
  if (!o.out.empty()) {
    std::error_code error;
    std::filesystem::create_directories(o.out, error);
    if (error || !write(std::filesystem::path(o.out) / "diagnosis.json", json) ||
        !write(std::filesystem::path(o.out) / "summary.txt", text)) {
      if (error) fmt::print(stderr, "{}: error: cannot create the folder: {}\n", o.out, error.message());
      return kBadInput;
    }
    try {
      diagnose::write_diagnosis_report(data, *derivation, d, o.out);
    } catch (const std::runtime_error& e) {
      fmt::print(stderr, "{}: error: cannot write the report: {}\n", o.out, e.what());
      return kBadInput;
    }
  }
  return kSuccess;
}

}  // namespace dyncc::cli
