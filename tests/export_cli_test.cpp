// `dyncc export` as a command: output to a file or to standard output, and bad input (a
// description that does not load, one with no tree-of-joints form, an unknown format, an
// unwritable output) rejected with exit code 2 and a message at the right place.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "dynamics_support.hpp"
#include "export_support.hpp"

namespace dyncc::test {
namespace {

TEST(ExportCli, WritesToStandardOutputWithoutOutputFile) {
  const std::filesystem::path out = output_path("stdout.xml");
  const std::string command = std::string("'") + DYNCC_BINARY + "' export " + quoted(robots_dir() / "kraft.yaml") +
                              " --format mjcf > " + quoted(out) + " 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string text = read_text(out);
  EXPECT_NE(text.find("<mujoco model=\"kraft_right\">"), std::string::npos);
  EXPECT_NE(text.find("</mujoco>"), std::string::npos);
}

TEST(ExportCli, DescriptionThatDoesNotLoadIsBadInput) {
  const std::filesystem::path broken =
      std::filesystem::path(DYNCC_SOURCE_DIR) / "tests/data/broken/convention_typo.yaml";
  for (const char* format : {"mjcf", "urdf"}) {
    const DynccRun run =
        run_dyncc("export " + quoted(broken) + " --format " + format + " -o " + quoted(output_path("x")));
    EXPECT_EQ(run.exit_code, 2) << run.errors;
    // The loader's diagnostic, "file:line:column: error: ...".
    EXPECT_NE(run.errors.find("convention_typo.yaml:"), std::string::npos) << run.errors;
    EXPECT_NE(run.errors.find(": error: "), std::string::npos) << run.errors;
  }
}

TEST(ExportCli, MissingFileIsBadInput) {
  const DynccRun run = run_dyncc("export /nonexistent/robot.yaml --format mjcf");
  EXPECT_EQ(run.exit_code, 2) << run.errors;
}

// A joint variable that is not affine in the coordinates loads and derives, but no MJCF or URDF
// joint can follow it: the error points at the expression.
TEST(ExportCli, NonAffineJointVariableIsBadInputAtItsPlace) {
  std::string text = read_text(robots_dir() / "planar_2link.yaml");
  const std::string from = "theta: q2\n";
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "theta: q2 + q1^2\n");
  const std::size_t line =
      static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n')) + 1;
  const std::filesystem::path yaml = output_path("yaml");
  std::ofstream(yaml) << text;
  const DynccRun run = run_dyncc("export " + quoted(yaml) + " --format urdf -o " + quoted(output_path("urdf")));
  EXPECT_EQ(run.exit_code, 2) << run.errors;
  const std::string where = yaml.string() + ":" + std::to_string(line) + ":";
  EXPECT_NE(run.errors.find(where), std::string::npos) << "expected " << where << " in\n" << run.errors;
  EXPECT_NE(run.errors.find("error: links[1].theta: 'q1^2 + q2' is not affine in the coordinates"), std::string::npos)
      << run.errors;
}

TEST(ExportCli, UnknownFormatIsBadInput) {
  const DynccRun run = run_dyncc("export " + quoted(robots_dir() / "kraft.yaml") + " --format sdf");
  EXPECT_EQ(run.exit_code, 2) << run.errors;
}

TEST(ExportCli, UnwritableOutputIsBadInput) {
  const DynccRun run =
      run_dyncc("export " + quoted(robots_dir() / "kraft.yaml") + " --format mjcf -o /nonexistent/dir/kraft.xml");
  EXPECT_EQ(run.exit_code, 2) << run.errors;
  EXPECT_NE(run.errors.find("cannot write /nonexistent/dir/kraft.xml"), std::string::npos) << run.errors;
}

}  // namespace
}  // namespace dyncc::test
