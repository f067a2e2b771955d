// `dyncc simulate` and `dyncc report` run the tele-operation simulation, which lives in sim/ and
// is built as the program dyncc-sim next to dyncc. Why a separate program: the simulation links
// the runtime (the controller under test) and the generated Kraft model, and the generator must
// not depend on either (the layout rule gen/ <-/-> runtime/). The arguments pass through as they
// are, and so does the exit code (exec replaces this process).
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.hpp"

namespace dyncc::cli {
namespace {

std::filesystem::path simulator_path() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  return (error ? std::filesystem::path(".") : self.parent_path()) / "dyncc-sim";
}

int exec_simulator(const std::string& command, const std::vector<std::string>& arguments) {
  const std::string program = simulator_path().string();
  std::vector<std::string> words{program, command};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  argv.reserve(words.size() + 1);
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  ::execv(program.c_str(), argv.data());
  std::fprintf(stderr, "dyncc %s: cannot run %s: %s (it is built with dyncc: cmake --build the same tree)\n",
               command.c_str(), program.c_str(), std::strerror(errno));
  return kBadInput;
}

}  // namespace

int run_simulator(const std::string& command, const std::vector<std::string>& arguments) {
  return exec_simulator(command, arguments);
}

}  // namespace dyncc::cli
