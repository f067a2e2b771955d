// Fresh paths for the files a test writes. ctest runs tests in parallel, and the Release and the
// sanitizer builds may run the same test at once, so a path names the test (suite and name, with
// the parameter's instance) and the process: two instances of one parameterised test that wrote
// the same file once read each other's half-written log.
//
// The files go once the test has passed (a failed test's stay, to be looked at): every run of the
// suite used to leave some 2 GB of logs and reports behind in the temp directory. What goes is
// everything whose name starts with the test's prefix, so files and folders a command derives
// from a temp path (a report folder, a `.json` beside a log) go with it.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>

namespace dyncc::test {

/// The start of the name of every temp file of the test `suite`.`name` in this process.
inline std::string temp_prefix(const char* suite, const char* name) {
  std::string prefix = "dyncc";
  if (suite != nullptr && name != nullptr) prefix.append(".").append(suite).append(".").append(name);
  std::replace(prefix.begin(), prefix.end(), '/', '_');  // parameterised names hold '/'
  prefix.append(".").append(std::to_string(getpid())).append(".");
  return prefix;
}

/// Removes the temp files of a test once it has passed.
class TempFileSweeper : public ::testing::EmptyTestEventListener {
 public:
  void OnTestEnd(const ::testing::TestInfo& info) override {
    if (info.result() == nullptr || info.result()->Failed()) return;
    sweep(temp_prefix(info.test_suite_name(), info.name()));
  }
  // Files written outside any test (a suite's set-up) go at the end of the program.
  void OnTestProgramEnd(const ::testing::UnitTest& unit) override {
    if (!unit.Failed()) sweep(temp_prefix(nullptr, nullptr));
  }

 private:
  static void sweep(const std::string& prefix) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(::testing::TempDir(), error)) {
      if (entry.path().filename().string().starts_with(prefix)) std::filesystem::remove_all(entry.path(), error);
    }
  }
};

/// A path under the test temp directory unique to this test and process, ending in `name`.
inline std::filesystem::path temp_path(const std::string& name) {
  // Installed on first use, so only programs that write temp files sweep; gtest owns the listener.
  static const bool sweeper_installed = [] {
    ::testing::UnitTest::GetInstance()->listeners().Append(
        new TempFileSweeper);  // NOLINT(cppcoreguidelines-owning-memory)
    return true;
  }();
  (void)sweeper_installed;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string prefix =
      info != nullptr ? temp_prefix(info->test_suite_name(), info->name()) : temp_prefix(nullptr, nullptr);
  return std::filesystem::path(::testing::TempDir()) / (prefix + name);
}

}  // namespace dyncc::test
