// dyncc export: the arm as MJCF or URDF (being written; see issue 4).
#include <cstdio>

#include "cli/commands.hpp"

namespace dyncc::cli {

int run_export(const ExportOptions& o) {
  std::fprintf(stderr, "dyncc export --format %s: not implemented yet\n", o.format.c_str());
  return kBadInput;
}

}  // namespace dyncc::cli
