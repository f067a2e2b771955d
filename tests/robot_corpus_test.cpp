// `dyncc check` on the corpus of broken descriptions (tests/data/broken/*.yaml), as a subprocess:
// each file must be rejected with exit code 2, its intended message at its intended place, and
// no crash. Each file starts with
//   # expect: <substring of the intended message>
//   # at: LINE:COL            (or "none" where the position is the engine's choice)
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kSource = DYNCC_SOURCE_DIR;

struct RunResult {
  int exit_code = -1;
  bool crashed = false;  // killed by a signal
  std::string output;
};

// Runs `dyncc check FILE` with stderr captured (stdout discarded unless asked for).
RunResult run_check(const fs::path& file, bool capture_stdout = false) {
  // `timeout` turns a hang into exit code 124 instead of a stuck test run.
  const std::string command = std::string("timeout 60 '") + DYNCC_BINARY + "' check '" + file.string() + "' 2>&1" +
                              (capture_stdout ? "" : " 1>/dev/null");
  RunResult result;
  // Redirection order matters: 2>&1 first sends stderr into the pipe, then stdout goes to /dev/null.
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t read = 0;
  while ((read = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), read);
  const int status = pclose(pipe);
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
    // timeout reports a child killed by a signal as 128 + signal.
    result.crashed = result.exit_code > 128 || result.exit_code == 124;
  } else {
    result.crashed = true;
  }
  return result;
}

struct Expectation {
  std::string message;
  std::string at;  // "LINE:COL" or empty
};

Expectation read_expectation(const fs::path& file) {
  std::ifstream in(file);
  std::string first;
  std::string second;
  std::getline(in, first);
  std::getline(in, second);
  Expectation expectation;
  const std::string expect_prefix = "# expect: ";
  const std::string at_prefix = "# at: ";
  if (first.rfind(expect_prefix, 0) == 0) expectation.message = first.substr(expect_prefix.size());
  if (second.rfind(at_prefix, 0) == 0 && second != "# at: none") expectation.at = second.substr(at_prefix.size());
  return expectation;
}

std::vector<std::string> broken_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(kSource / "tests/data/broken")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class BrokenDescription : public testing::TestWithParam<std::string> {};

TEST_P(BrokenDescription, IsRejectedWithItsIntendedMessage) {
  const fs::path file = kSource / "tests/data/broken" / GetParam();
  const Expectation expectation = read_expectation(file);
  ASSERT_FALSE(expectation.message.empty()) << file << " lacks its '# expect:' line";
  const RunResult result = run_check(file);
  EXPECT_FALSE(result.crashed) << result.output;
  EXPECT_EQ(result.exit_code, 2) << result.output;
  // The message must be on a line that carries the intended position.
  const std::string position = file.string() + ":" + expectation.at + ":";
  std::istringstream lines(result.output);
  bool found = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.find(expectation.message) == std::string::npos) continue;
    if (expectation.at.empty() || line.rfind(position, 0) == 0) found = true;
  }
  EXPECT_TRUE(found) << "expected '" << expectation.message << "'"
                     << (expectation.at.empty() ? "" : " at " + expectation.at) << "\ngot:\n"
                     << result.output;
}

std::string test_name(const testing::TestParamInfo<std::string>& info) {
  std::string name = fs::path(info.param).stem().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BrokenDescription, testing::ValuesIn(broken_files()), test_name);

TEST(BrokenCorpus, CoversEveryErrorKind) { EXPECT_GE(broken_files().size(), 30u); }

TEST(CheckCommand, ShippedRobotsPass) {
  for (const char* robot : {"robots/kraft.yaml", "robots/planar_2link.yaml"}) {
    const RunResult result = run_check(kSource / robot, true);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(result.output.find(": warning:"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("(0 warnings)"), std::string::npos) << result.output;
  }
  const RunResult kraft = run_check(kSource / "robots/kraft.yaml", true);
  for (const char* expected : {"robot kraft_right", "links (5)", "forearm [revolute] theta = q3 - q2",
                               "unknown parameters (41)", "elbow_parallelogram", "p13 ="}) {
    EXPECT_NE(kraft.output.find(expected), std::string::npos) << expected << "\n" << kraft.output;
  }
}

TEST(CheckCommand, PhysicalConsistencyWarnPassesWithAWarning) {
  const fs::path file = kSource / "tests/data/robot_warn/physical_warn.yaml";
  const RunResult result = run_check(file);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find(file.string() + ":"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("warning: links[1].inertia: physically inconsistent"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("warning: links[0].mass: physically inconsistent nominal values: negative mass"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("error"), std::string::npos) << result.output;
}

TEST(CheckCommand, MissingFileIsBadInput) {
  const RunResult result = run_check(kSource / "robots/no_such_robot.yaml");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("no such file"), std::string::npos) << result.output;
}

}  // namespace
