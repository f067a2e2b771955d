// Running the dyncc command as a subprocess from a test, and fresh paths for its output files.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "temp_path.hpp"

namespace dyncc::test {

/// A path in single quotes for the shell (built with append: GCC 12 warns falsely, -Wrestrict,
/// on "literal" + std::string at -O3).
inline std::string quoted(const std::filesystem::path& p) {
  std::string s = "'";
  s.append(p.string()).append("'");
  return s;
}

struct DynccRun {
  int exit_code = -1;
  std::string errors;  // stderr
};

/// Runs `dyncc ARGUMENTS` (already quoted as needed) with stdout discarded and stderr captured;
/// killed after `seconds` (a hang is a failure; a run of many logs, under the sanitizers and beside
/// other tests, may need more than the default).
inline DynccRun run_dyncc(const std::string& arguments, int seconds = 120) {
  // `timeout` turns a hang into a failure; 2>&1 first sends stderr to the pipe, then stdout away.
  std::string command = "timeout " + std::to_string(seconds) + " ";
  command.append(quoted(DYNCC_BINARY)).append(" ").append(arguments).append(" 2>&1 1>/dev/null");
  DynccRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  std::size_t read = 0;
  while ((read = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.errors.append(buffer.data(), read);
  const int status = pclose(pipe);
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  return run;
}

/// A fresh path for an output file of this test.
inline std::filesystem::path output_path(const std::string& name) { return temp_path(name); }

/// Writes `text` to a fresh output path of this test and returns the path.
inline std::filesystem::path write_text(const std::string& name, const std::string& text) {
  const auto path = output_path(name);
  std::ofstream(path) << text;
  return path;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A CSV log as columns by header name.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  [[nodiscard]] int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    return -1;
  }
};

inline Csv read_csv(const std::filesystem::path& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line, cell;
  std::getline(in, line);
  std::stringstream head(line);
  while (std::getline(head, cell, ',')) csv.header.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream cells(line);
    std::vector<double> row;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    csv.rows.push_back(row);
  }
  return csv;
}

}  // namespace dyncc::test
