// The dyncc subcommands: each takes its parsed options and returns an exit code. Only main.cpp
// knows the command-line library (CLI11 is heavy to compile; one translation unit pays for it).
#pragma once

#include <string>
#include <vector>

namespace dyncc::cli {

/// Exit codes shared by every subcommand.
enum ExitCode : int { kSuccess = 0, kCheckFailed = 1, kBadInput = 2 };

struct CheckOptions {
  std::string robot;
};
int run_check(const CheckOptions& o);

struct DeriveOptions {
  std::string robot;
  bool latex = false;
};
int run_derive(const DeriveOptions& o);

struct EvalOptions {
  std::string robot;
  std::vector<double> q, qd, v, a;
  bool json = false;
};
int run_eval(const EvalOptions& o);

struct VerifyOptions {
  std::string robot;
  bool json = false;
  int samples = 1000;
};
int run_verify(const VerifyOptions& o);

struct GenerateOptions {
  std::string robot;
  std::string out_dir;  // generated/<robot>/
  bool check = false;   // compare with what is in out_dir instead of writing; exit 1 on a difference
};
int run_generate(const GenerateOptions& o);

struct ExportOptions {
  std::string robot;
  std::string format;  // "mjcf" or "urdf"
  std::string out;     // file; empty = standard output
};
int run_export(const ExportOptions& o);

struct ExprOptions {
  std::string variable;
  std::string expression;
  std::vector<std::string> assignments;
  bool latex = false;
};
int run_expr_diff(const ExprOptions& o);
int run_expr_simplify(const ExprOptions& o);
int run_expr_expand(const ExprOptions& o);
int run_expr_zero(const ExprOptions& o);
int run_expr_eval(const ExprOptions& o);

struct DiagnoseOptions {
  std::string robot;
  std::vector<std::string> logs;
  std::string out, json, map;
  bool held_torque = false;  // the torque columns are commands held until the next row
};
int run_diagnose(const DiagnoseOptions& o);

struct BenchOptions {
  int cases = 20;
  unsigned seed = 1;
  std::string out = "sim2real-bench";
  std::string robots = "robots";
  std::vector<std::string> arms{"kraft", "puma560", "panda"};
  bool closed_loop = true;  // Kraft logs at 200 Hz and above from the closed-loop simulation (dyncc-sim excite)
  std::vector<std::string> effects;  // the effects drawn from (default: every injectable one)
  bool rescore = false;              // score the cases already in `out` again (their truth.json and diagnosis.json)
  std::string rediagnose;            // a stored bench whose logs to diagnose again into `out`, then score
};
int run_sim2real_bench(const BenchOptions& o);

/// `simulate`, `report` and `excite`: run dyncc-sim (built next to dyncc) with the same arguments.
int run_simulator(const std::string& command, const std::vector<std::string>& arguments);

}  // namespace dyncc::cli
