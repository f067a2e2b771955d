// dyncc generate: emit the flat C++ of a robot's model (being written; see issue 4).
#include <cstdio>

#include "cli/commands.hpp"

namespace dyncc::cli {

int run_generate(const GenerateOptions& o) {
  std::fprintf(stderr, "dyncc generate %s: not implemented yet\n", o.robot.c_str());
  return kBadInput;
}

}  // namespace dyncc::cli
