// `dyncc generate ROBOT -o DIR`: the model as flat C++ (generated/<robot>/), or with --check, whether
// DIR already holds exactly that (what CI runs to keep generated/ current).
#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "codegen/generated_files.hpp"
#include "codegen/model_functions.hpp"

namespace dyncc::cli {
namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int run_generate(const GenerateOptions& o) {
  const auto derivation = load_and_derive(o.robot);
  if (!derivation) return kBadInput;
  codegen::GenerationInfo info;
  info.version = DYNCC_VERSION;
  info.source = std::filesystem::path(o.robot).lexically_normal().generic_string();
  info.source_hash = codegen::sha256_of_file(o.robot);
  info.out_dir = std::filesystem::path(o.out_dir).lexically_normal().generic_string();
  const codegen::ModelFunctions functions = codegen::build_model_functions(*derivation);
  const auto files = codegen::generated_files(*derivation, functions, info);

  const std::filesystem::path dir(o.out_dir);
  if (o.check) {
    int stale = 0;
    for (const auto& [name, content] : files) {
      if (read_file(dir / name) != content) {
        fmt::print(stderr, "{}: differs from what `dyncc generate {} -o {}` produces\n", (dir / name).generic_string(),
                   info.source, info.out_dir);
        ++stale;
      }
    }
    if (stale > 0) return kCheckFailed;
    fmt::print("{}: {} files current\n", info.out_dir, files.size());
    return kSuccess;
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    fmt::print(stderr, "error: cannot create {}: {}\n", dir.generic_string(), ec.message());
    return kBadInput;
  }
  for (const auto& [name, content] : files) {
    std::ofstream out(dir / name, std::ios::binary);
    out << content;
    if (!out) {
      fmt::print(stderr, "error: cannot write {}\n", (dir / name).generic_string());
      return kBadInput;
    }
  }
  fmt::print("wrote {} files to {}\n", files.size(), info.out_dir);
  return kSuccess;
}

}  // namespace dyncc::cli
