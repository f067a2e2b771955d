// `dyncc verify` (symbolic skew-symmetry proof, numeric checks of H, Y, energy, loops and the
// base-parameter proofs) passes, exit code 0, on every description shipped in robots/.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <nlohmann/json.hpp>
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

CliRun run_dyncc(const std::string& args, bool with_stderr = true) {
  const std::string command =
      "timeout 300 " + quote(DYNCC_BINARY) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
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

// `dyncc eval --json`: the keys the derivation issue names, matrices as arrays of rows, and the
// regressor's torque equal to Y times the base-parameter values (checked here, not trusted).
TEST(EvalCommand, JsonKeysAndTorqueEqualsRegressorTimesBaseValues) {
  ASSERT_EQ(access(DYNCC_BINARY, X_OK), 0) << "dyncc is not built at " << DYNCC_BINARY;
  const std::string robot = quote((robots_dir() / "kraft.yaml").string());
  const CliRun r =
      run_dyncc("eval " + robot + " --q 0.3,-0.4,0.5 --qd 0.7,-0.2,0.9 --v 0.1,0.2,-0.3 --a 1,-2,0.5 --json",
                /*with_stderr=*/false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"H", "C", "g", "friction", "tau", "Y", "base_parameters", "initial_estimate"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const auto& base = j["base_parameters"];
  ASSERT_TRUE(base.contains("names") && base.contains("definitions") && base.contains("values"));
  const std::size_t b = base["names"].size();
  EXPECT_EQ(b, 19U);  // 13 inertial + 6 friction (the paper's assumptions)
  ASSERT_EQ(j["H"].size(), 3U);
  ASSERT_EQ(j["Y"].size(), 3U);
  ASSERT_EQ(j["Y"][0].size(), b);
  for (std::size_t i = 0; i < 3; ++i) {
    double y_p = 0;
    for (std::size_t k = 0; k < b; ++k) y_p += j["Y"][i][k].get<double>() * base["values"][k].get<double>();
    EXPECT_NEAR(y_p, j["tau"][i].get<double>(), 1e-12) << "row " << i;
    for (std::size_t k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(j["H"][i][k].get<double>(), j["H"][k][i].get<double>());
  }
  // The paper's initial estimate on the same base set: one value per base parameter, names shared.
  EXPECT_EQ(j["initial_estimate"]["names"], base["names"]);
  EXPECT_EQ(j["initial_estimate"]["values"].size(), b);
}

}  // namespace
}  // namespace dyncc::test
