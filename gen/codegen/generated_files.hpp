// The files of a generated model: the templates in templates/ filled with the rendered
// functions, names, nominal values and operation counts. Pure: returns file name -> content, so
// writing and the CI freshness check (--check) compare the same bytes.
#pragma once

#include <map>
#include <string>

#include "codegen/model_functions.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::codegen {

struct GenerationInfo {
  std::string version;      // generator version
  std::string source;       // the description's path as given (printed in the files)
  std::string source_hash;  // SHA-256 of its bytes, hex
  std::string out_dir;      // as given
};

/// File name (no directory) -> content: model.hpp, model.cpp, CMakeLists.txt, REPORT.md,
/// report.json.
std::map<std::string, std::string> generated_files(const pipeline::Derivation& derivation,
                                                   const ModelFunctions& functions, const GenerationInfo& info);

/// SHA-256 of a file's bytes as lowercase hex; throws std::runtime_error when unreadable.
std::string sha256_of_file(const std::string& path);

}  // namespace dyncc::codegen
