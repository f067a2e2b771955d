// `dyncc verify` (symbolic skew-symmetry proof, numeric checks of H, Y, energy, loops and the
// base-parameter proofs) passes, exit code 0, on every description shipped in robots/.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <string>

#include "dynamics_support.hpp"

namespace dyncc::test {
namespace {

struct CliRun {
  int exit_code = -1;
  std::string out;
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

CliRun run_dyncc(const std::string& args) {
  const std::string command = "timeout 300 " + quote(DYNCC_BINARY) + " " + args + " 2>&1";
  CliRun r;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  for (std::size_t n = 0; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) r.out.append(buffer, n);
  const int status = pclose(pipe);
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  return r;
}

class VerifyShippedRobot : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(VerifyShippedRobot, PassesWithExitCodeZero) {
  ASSERT_EQ(access(DYNCC_BINARY, X_OK), 0) << "dyncc is not built at " << DYNCC_BINARY;
  // 200 random states per numeric check (the default is 1000) keeps the suite fast; the
  // symbolic proofs do not depend on the sample count.
  const CliRun r = run_dyncc("verify " + quote(GetParam().string()) + " --samples 200");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("all checks passed"), std::string::npos) << r.out;
}

INSTANTIATE_TEST_SUITE_P(Robots, VerifyShippedRobot, ::testing::ValuesIn(shipped_robots()),
                         [](const ::testing::TestParamInfo<std::filesystem::path>& info) {
                           std::string s = info.param.stem().string();
                           for (char& c : s) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return s;
                         });

}  // namespace
}  // namespace dyncc::test
