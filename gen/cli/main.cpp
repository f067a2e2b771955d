// dyncc: robot description -> verified dynamics -> generated controller code.
// The command line is declared here, in one place; the commands live in command_*.cpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "diagnose/synthetic_log.hpp"

namespace {

using namespace dyncc::cli;

// Options live in shared_ptrs owned by the callbacks, so they outlive this function's frame.
void add_expr_commands(CLI::App& app, int& exit_code) {
  auto* expr = app.add_subcommand("expr", "Differentiate, simplify, zero-test and evaluate expressions");
  expr->require_subcommand(1);
  auto o = std::make_shared<ExprOptions>();
  auto add = [&](const char* name, const char* help, int (*run)(const ExprOptions&)) {
    auto* sub = expr->add_subcommand(name, help);
    sub->callback([&exit_code, o, run] { exit_code = run(*o); });
    return sub;
  };
  auto* diff = add("diff", "Derivative of EXPR with respect to VAR", run_expr_diff);
  diff->add_option("VAR", o->variable, "Variable")->required();
  diff->add_option("EXPR", o->expression, "Expression")->required();
  diff->add_flag("--latex", o->latex, "Print LaTeX instead of plain text");
  auto* simplify =
      add("simplify", "Smallest equivalent form (canonical, expanded or trigonometric normal form)", run_expr_simplify);
  simplify->add_option("EXPR", o->expression, "Expression")->required();
  simplify->add_flag("--latex", o->latex, "Print LaTeX instead of plain text");
  auto* expand = add("expand", "Multiply out products and powers of sums", run_expr_expand);
  expand->add_option("EXPR", o->expression, "Expression")->required();
  expand->add_flag("--latex", o->latex, "Print LaTeX instead of plain text");
  auto* zero =
      add("zero", "Decide whether EXPR is identically zero (exit 0) or not (exit 1, with a witness)", run_expr_zero);
  zero->add_option("EXPR", o->expression, "Expression")->required();
  auto* eval = add("eval", "Evaluate EXPR at VAR=VALUE ...", run_expr_eval);
  eval->add_option("EXPR", o->expression, "Expression")->required();
  eval->add_option("ASSIGNMENTS", o->assignments, "VAR=VALUE pairs");
}

void add_robot_commands(CLI::App& app, int& exit_code) {
  auto check = std::make_shared<CheckOptions>();
  auto* check_cmd = app.add_subcommand("check", "Load and validate a robot description and print what was understood");
  check_cmd->add_option("robot", check->robot, "Robot description (YAML)")->required();
  check_cmd->callback([&exit_code, check] { exit_code = run_check(*check); });

  auto derive = std::make_shared<DeriveOptions>();
  auto* derive_cmd =
      app.add_subcommand("derive", "Derive H, C, g, friction, the base parameters and Y in readable form");
  derive_cmd->add_option("ROBOT", derive->robot, "Robot description (YAML)")->required();
  derive_cmd->add_flag("--latex", derive->latex, "Print LaTeX (an align* environment)");
  derive_cmd->callback([&exit_code, derive] { exit_code = run_derive(*derive); });

  auto eval = std::make_shared<EvalOptions>();
  auto* eval_cmd =
      app.add_subcommand("eval",
                         "Evaluate H, C, g, friction, tau, Y and the base parameters at a state (nominal parameters)");
  eval_cmd->add_option("ROBOT", eval->robot, "Robot description (YAML)")->required();
  eval_cmd->add_option("--q", eval->q, "Coordinates, comma-separated")->delimiter(',');
  eval_cmd->add_option("--qd", eval->qd, "Coordinate rates (default 0)")->delimiter(',');
  eval_cmd->add_option("--v", eval->v, "Reference velocity qd_r (default qd)")->delimiter(',');
  eval_cmd->add_option("--a", eval->a, "Reference acceleration qdd_r (default 0)")->delimiter(',');
  eval_cmd->add_flag("--json", eval->json, "Machine-readable output");
  eval_cmd->callback([&exit_code, eval] { exit_code = run_eval(*eval); });

  auto verify = std::make_shared<VerifyOptions>();
  auto* verify_cmd =
      app.add_subcommand("verify", "Prove Hdot-2C skew-symmetric and check H, Y, energy and loops at random states");
  verify_cmd->add_option("ROBOT", verify->robot, "Robot description (YAML)")->required();
  verify_cmd->add_option("--samples", verify->samples, "Random states for the numeric checks")
      ->check(CLI::Range(1, 10000000));
  verify_cmd->add_flag("--json", verify->json, "Machine-readable output");
  verify_cmd->callback([&exit_code, verify] { exit_code = run_verify(*verify); });
}

void add_output_commands(CLI::App& app, int& exit_code) {
  auto generate = std::make_shared<GenerateOptions>();
  auto* generate_cmd =
      app.add_subcommand("generate",
                         "Emit optimised, allocation-free C++ of the model (H, C, g, Y, fused control step)");
  generate_cmd->add_option("ROBOT", generate->robot, "Robot description (YAML)")->required();
  generate_cmd->add_option("-o,--out", generate->out_dir, "Output folder, e.g. generated/kraft")->required();
  generate_cmd->add_flag("--check", generate->check,
                         "Write nothing; exit 1 when the folder differs from what would be generated");
  generate_cmd->callback([&exit_code, generate] { exit_code = run_generate(*generate); });

  auto exp = std::make_shared<ExportOptions>();
  auto* export_cmd = app.add_subcommand("export", "Write the arm for other tools (MuJoCo MJCF or URDF)");
  export_cmd->add_option("ROBOT", exp->robot, "Robot description (YAML)")->required();
  export_cmd->add_option("--format", exp->format, "mjcf or urdf")->required()->check(CLI::IsMember({"mjcf", "urdf"}));
  export_cmd->add_option("-o,--out", exp->out, "Output file (default: standard output)");
  export_cmd->callback([&exit_code, exp] { exit_code = run_export(*exp); });

  auto diag = std::make_shared<DiagnoseOptions>();
  auto* diagnose_cmd = app.add_subcommand("diagnose",
                                          "Find where and why logs of a real arm disagree with the model, and how far "
                                          "the gap shrinks once the cause is added");
  diagnose_cmd->add_option("ROBOT", diag->robot, "Robot description (YAML)")->required();
  diagnose_cmd->add_option("LOGS", diag->logs, "CSV logs: t, q1..qn, tau1..taun (optional qd*, qdd*)")->required();
  diagnose_cmd->add_option("--out", diag->out,
                           "Folder for diagnosis.json, summary.txt and report.html (with its figures)");
  diagnose_cmd->add_option("--json", diag->json, "Write the JSON here");
  diagnose_cmd->add_option("--map", diag->map, "Rename foreign columns: THEIR=OURS,... (e.g. time=t,pos1=q1)");
  diagnose_cmd->add_flag("--held-torque", diag->held_torque,
                         "The torque columns are commands a digital controller held until the next row (zero-order "
                         "hold), not torques measured at their time stamps");
  diagnose_cmd->callback([&exit_code, diag] { exit_code = run_diagnose(*diag); });

  auto bench = std::make_shared<BenchOptions>();
  auto* bench_cmd = app.add_subcommand(
      "sim2real-bench", "Check the diagnosis blind: logs with hidden effects, diagnosed as a separate process, scored");
  bench_cmd->add_option("--cases", bench->cases, "Number of logs")->check(CLI::Range(1, 100000));
  bench_cmd->add_option("--seed", bench->seed, "Seed of the case generator");
  bench_cmd->add_option("--out", bench->out, "Folder for the logs, truths, diagnoses and summary.md");
  bench_cmd->add_option("--robots", bench->robots, "Folder with the descriptions (default robots)");
  bench_cmd->add_option("--arms", bench->arms, "Descriptions to use (default kraft puma560 panda)");
  bench_cmd->add_option("--closed-loop", bench->closed_loop,
                        "Kraft logs at 200 Hz and above from the closed-loop simulation on both plants (default true)");
  bench_cmd->add_option("--effects", bench->effects, "Effects to draw from (default all the bench can inject)")
      ->check(CLI::IsMember(dyncc::diagnose::injectable_effects()));
  bench_cmd->add_flag("--rescore", bench->rescore,
                      "Score the cases already in --out again (their truth.json and diagnosis.json); make and "
                      "diagnose nothing");
  bench_cmd
      ->add_option("--rediagnose", bench->rediagnose,
                   "Diagnose the logs of this stored bench's cases again into --out (their truth.json copied), "
                   "then score them; simulate nothing")
      ->excludes("--rescore");
  bench_cmd->callback([&exit_code, bench] { exit_code = run_sim2real_bench(*bench); });
}

// The simulation (sim/) is its own program, dyncc-sim: it links the runtime, which the generator
// must not. These commands hand every argument after their name to it, --help included.
void add_simulation_commands(CLI::App& app, int& exit_code) {
  struct Entry {
    const char* name;
    const char* help;
  };
  for (const Entry e :
       {Entry{"simulate", "Simulate the tele-operated Kraft arm in one of the paper's scenarios (--help for more)"},
        Entry{"report", "Run every scenario on both plants and write one HTML page with the figures and tables"},
        Entry{"excite", "Log the Kraft arm in closed loop with hidden effects, for checking the diagnosis (--help)"}}) {
    auto* sub = app.add_subcommand(e.name, e.help);
    sub->prefix_command();
    sub->set_help_flag();
    const std::string name = e.name;
    sub->callback([&exit_code, sub, name] { exit_code = run_simulator(name, sub->remaining()); });
  }
}

int run(int argc, char** argv) {
  CLI::App app{"dyncc: derives verified rigid-body dynamics from a robot description and emits controller code"};
  app.set_version_flag("--version", std::string("dyncc ") + DYNCC_VERSION);
  app.require_subcommand(1);
  int exit_code = kSuccess;
  add_expr_commands(app, exit_code);
  add_robot_commands(app, exit_code);
  add_output_commands(app, exit_code);
  add_simulation_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    // CLI11 returns 0 for --help/--version; every real usage error is our "bad input".
    return code == 0 ? 0 : kBadInput;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  // Commands report bad input themselves (exit 2); anything escaping to here is a bug in dyncc,
  // reported as such rather than as std::terminate's abort. C stdio here: it cannot throw.
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dyncc: internal error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "dyncc: internal error\n");
  }
  return kBadInput;
}
