// `dyncc expr ...` run as a subprocess: exit codes, verdict lines, and numbers that are
// checked against independent computations (never against a stored copy of our output).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <unordered_map>

#include "sym/diff.hpp"
#include "sym/evaluate.hpp"
#include "sym/parse.hpp"
#include "sym/print.hpp"

namespace dyncc::sym {
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

// Runs dyncc with the given (already quoted) arguments; `timeout` turns a hang into a failure.
CliRun dyncc(const std::string& args, bool with_stderr = true) {
  const std::string command =
      "timeout 60 " + quote(DYNCC_BINARY) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  CliRun r;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  for (std::size_t n = 0; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) r.out.append(buffer, n);
  const int status = pclose(pipe);
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  return r;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

class SymCli : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(access(DYNCC_BINARY, X_OK), 0) << "dyncc is not built at " << DYNCC_BINARY; }
};

TEST_F(SymCli, ZeroProvesAnIdentity) {
  const CliRun r = dyncc("expr zero " + quote("sin(q1 + q2) - sin(q1)*cos(q2) - cos(q1)*sin(q2)"));
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(trimmed(r.out), "identically zero");
}

TEST_F(SymCli, ZeroRefutesANonIdentityWithAWitness) {
  const CliRun r = dyncc("expr zero " + quote("sin(2*x) - 2*sin(x)"));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("not identically zero"), std::string::npos) << r.out;
  // "witness: x=<value> gives <value>" (parsed by hand: <regex> trips GCC 12 warnings under ASan)
  const std::size_t at = r.out.find("witness: x=");
  ASSERT_NE(at, std::string::npos) << r.out;
  std::istringstream line(r.out.substr(at + 11));
  double x = 0.0;
  double value = 0.0;
  std::string gives;
  ASSERT_TRUE(line >> x >> gives >> value) << r.out;
  EXPECT_EQ(gives, "gives");
  EXPECT_NEAR(value, std::sin(2 * x) - 2 * std::sin(x), 1e-12);
  EXPECT_GT(std::abs(value), 1e-6);
}

TEST_F(SymCli, ZeroNeverCallsRoundingNoiseAWitness) {
  const CliRun r = dyncc("expr zero " + quote("(sqrt((x + 10)^2) - sqrt(x^2 + 20*x + 100))*(x + 10)^8"));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_EQ(r.out.find("not identically zero"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("undecided"), std::string::npos) << r.out;
}

TEST_F(SymCli, DiffPrintsTheDerivative) {
  const CliRun r = dyncc("expr diff x " + quote("x*sin(x) + x^3/3"), false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const Expr x = symbol("x");
  EXPECT_EQ(parse_or_throw(trimmed(r.out)), sin(x) + x * cos(x) + x * x) << r.out;  // derived by hand

  const CliRun a = dyncc("expr diff q1 " + quote("atan2(q1, 1 + q2^2)"), false);
  ASSERT_EQ(a.exit_code, 0) << a.out;
  const Expr d = parse_or_throw(trimmed(a.out));
  for (const double q1 : {-1.3, 0.2, 2.0}) {
    for (const double q2 : {-0.7, 0.0, 1.1}) {
      const double c = 1 + q2 * q2;  // d/dq1 atan2(q1, c) = c / (c^2 + q1^2)
      const std::unordered_map<std::string, double> values{{"q1", q1}, {"q2", q2}};
      EXPECT_NEAR(evaluate(d, values), c / (c * c + q1 * q1), 1e-12);
    }
  }
  const CliRun latex = dyncc("expr diff x --latex " + quote("sin(x^2)"), false);
  EXPECT_EQ(latex.exit_code, 0);
  EXPECT_NE(latex.out.find("\\cos"), std::string::npos) << latex.out;
  EXPECT_EQ(dyncc("expr diff 2 " + quote("x")).exit_code, 2);
  EXPECT_EQ(dyncc("expr diff x " + quote("x +")).exit_code, 2);
}

TEST_F(SymCli, EvalPrintsTheValue) {
  const CliRun r = dyncc("expr eval " + quote("x*y + 1/3") + " x=2 y=0.5", false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(std::stod(r.out), 2 * 0.5 + 1.0 / 3.0);
  const CliRun t = dyncc("expr eval " + quote("sin(q1)^2 + cos(q2)") + " q1=pi/6 q2=1/4", false);
  ASSERT_EQ(t.exit_code, 0) << t.out;
  EXPECT_NEAR(std::stod(t.out), std::pow(std::sin(std::numbers::pi / 6), 2) + std::cos(0.25), 1e-15);
  const CliRun missing = dyncc("expr eval " + quote("x + y") + " x=1");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.out.find("no value given for 'y'"), std::string::npos) << missing.out;
  EXPECT_EQ(dyncc("expr eval x x").exit_code, 2);
  EXPECT_EQ(dyncc("expr eval x x=y").exit_code, 2);
  EXPECT_EQ(dyncc("expr eval x x=1/").exit_code, 2);
}

TEST_F(SymCli, SimplifyAndExpand) {
  const CliRun s = dyncc("expr simplify " + quote("sin(x)^2 + cos(x)^2"), false);
  EXPECT_EQ(s.exit_code, 0);
  EXPECT_EQ(trimmed(s.out), "1");
  const CliRun e = dyncc("expr expand " + quote("(x + 1)^3"), false);
  ASSERT_EQ(e.exit_code, 0);
  const Expr x = symbol("x");
  EXPECT_EQ(parse_or_throw(trimmed(e.out)), x * x * x + Expr(3) * x * x + Expr(3) * x + Expr(1)) << e.out;
  // Extreme input must neither hang nor crash.
  const CliRun big = dyncc("expr simplify " + quote("sqrt(9223372036854775807)"), false);
  EXPECT_EQ(big.exit_code, 0);
  EXPECT_EQ(trimmed(big.out), "sqrt(9223372036854775807)");
}

TEST_F(SymCli, ParseErrorsExitTwoWithTheColumn) {
  struct Case {
    const char* text;
    const char* location;
  };
  for (const Case& c : {Case{"1/(x", "EXPR:1:5: error: expected ')'"}, Case{"x $ y", "EXPR:1:3: error:"},
                        Case{"2x", "EXPR:1:2: error:"}}) {
    for (const char* sub : {"zero", "simplify", "expand", "eval"}) {
      const CliRun r = dyncc(std::string("expr ") + sub + " " + quote(c.text));
      EXPECT_EQ(r.exit_code, 2) << sub << " " << c.text << "\n" << r.out;
      EXPECT_NE(r.out.find(c.location), std::string::npos) << r.out;
    }
  }
  // The caret sits under the column.
  const CliRun r = dyncc("expr zero " + quote("1/(x"));
  EXPECT_NE(r.out.find("\n  1/(x\n      ^"), std::string::npos) << r.out;
}

TEST_F(SymCli, VersionHelpAndUsage) {
  const CliRun v = dyncc("--version");
  EXPECT_EQ(v.exit_code, 0);
  const std::size_t name = v.out.find("dyncc ");
  ASSERT_NE(name, std::string::npos) << v.out;
  std::istringstream version(v.out.substr(name + 6));
  int major = -1;
  char dot = 0;
  int minor = -1;
  EXPECT_TRUE(version >> major >> dot >> minor && dot == '.' && major >= 0 && minor >= 0) << v.out;
  const CliRun h = dyncc("--help");
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("expr"), std::string::npos) << h.out;
  const CliRun eh = dyncc("expr --help");
  EXPECT_EQ(eh.exit_code, 0);
  EXPECT_NE(eh.out.find("zero"), std::string::npos) << eh.out;
  EXPECT_EQ(dyncc("").exit_code, 2);
  EXPECT_EQ(dyncc("expr").exit_code, 2);
  EXPECT_EQ(dyncc("no-such-command").exit_code, 2);
  EXPECT_EQ(dyncc("expr zero").exit_code, 2);
}

}  // namespace
}  // namespace dyncc::sym
