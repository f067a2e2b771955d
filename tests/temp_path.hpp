// Fresh paths for the files a test writes. ctest runs tests in parallel, and the Release and the
// sanitizer builds may run the same test at once, so a path names the test (suite and name, with
// the parameter's instance) and the process: two instances of one parameterised test that wrote
// the same file once read each other's half-written log.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace dyncc::test {

/// A path under the test temp directory unique to this test and process, ending in `name`.
inline std::filesystem::path temp_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = "dyncc";
  if (info != nullptr) test.append(".").append(info->test_suite_name()).append(".").append(info->name());
  std::replace(test.begin(), test.end(), '/', '_');  // parameterised names hold '/'
  test.append(".").append(std::to_string(getpid())).append(".").append(name);
  return std::filesystem::path(::testing::TempDir()) / test;
}

}  // namespace dyncc::test
