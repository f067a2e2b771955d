// `dyncc verify`: proofs and numeric checks of the derived model.
#include <fmt/core.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "sym/evaluate.hpp"
#include "sym/substitute.hpp"
#include "sym/trig_normal_form.hpp"

namespace dyncc::cli {
namespace {

struct CheckResult {
  std::string name;
  bool passed = false;
  std::string value;   // the figure the check measured
  std::string detail;  // how, or why it failed
};

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

CheckResult prove_skew_symmetry(const pipeline::Derivation& d, const dyn::Matrix& Hdot) {
  // N = Hdot - 2C is skew-symmetric iff Hdot_ij - C_ij - C_ji == 0 for all i <= j.
  const std::size_t n = d.model.q.size();
  std::size_t proved = 0;
  std::size_t failed = 0;
  std::string first_failure;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i; j < n; ++j) {
      const sym::Expr sum = Hdot[i][j] - d.model.C[i][j] - d.model.C[j][i];
      const sym::ZeroTestResult r = sym::test_zero(sum);
      if (r.verdict == sym::ZeroVerdict::Zero) {
        ++proved;
      } else if (failed++ == 0) {
        first_failure = fmt::format("N{}{} + N{}{} is not identically zero", i + 1, j + 1, j + 1, i + 1);
      }
    }
  }
  return {"Hdot - 2C skew-symmetric (symbolic proof)", failed == 0,
          fmt::format("{}/{} entries proved", proved, proved + failed),
          failed == 0 ? "normal form of every N_ij + N_ji is exactly 0" : first_failure};
}

std::vector<sym::Expr> flatten(const dyn::Matrix& m, const sym::Substitution& constants) {
  std::vector<sym::Expr> out;
  for (const auto& row : m) {
    for (const sym::Expr e : row) out.push_back(sym::substitute(e, constants));
  }
  return out;
}

// RK4 on the unforced, frictionless model; returns the largest relative energy drift.
double energy_drift(const pipeline::Derivation& d, const Eigen::VectorXd& standard, double duration, double dt) {
  const std::size_t n = d.model.q.size();
  const auto N = static_cast<Eigen::Index>(n);
  dyn::State s = dyn::random_state(n, 99);
  s.qd *= 0.5;
  auto accel = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
    dyn::State st{q, qd, qd, Eigen::VectorXd::Zero(N)};
    const dyn::Evaluation e = d.numeric->evaluate(st, standard, /*with_regressor=*/false);
    return Eigen::VectorXd(e.H.ldlt().solve(-(e.C * qd + e.g)));
  };
  Eigen::VectorXd q = s.q;
  Eigen::VectorXd qd = s.qd;
  const double e0 = d.numeric->energy(q, qd, standard);
  const double kinetic0 = e0 - d.numeric->energy(q, Eigen::VectorXd::Zero(N), standard);
  double worst = 0.0;
  const int steps = static_cast<int>(duration / dt);
  for (int k = 0; k < steps; ++k) {
    const Eigen::VectorXd k1v = accel(q, qd);
    const Eigen::VectorXd k1q = qd;
    const Eigen::VectorXd k2v = accel(q + 0.5 * dt * k1q, qd + 0.5 * dt * k1v);
    const Eigen::VectorXd k2q = qd + 0.5 * dt * k1v;
    const Eigen::VectorXd k3v = accel(q + 0.5 * dt * k2q, qd + 0.5 * dt * k2v);
    const Eigen::VectorXd k3q = qd + 0.5 * dt * k2v;
    const Eigen::VectorXd k4v = accel(q + dt * k3q, qd + dt * k3v);
    const Eigen::VectorXd k4q = qd + dt * k3v;
    q += dt / 6.0 * (k1q + 2 * k2q + 2 * k3q + k4q);
    qd += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    worst = std::max(worst, std::abs(d.numeric->energy(q, qd, standard) - e0));
  }
  return worst / std::max(kinetic0, 1e-12);
}

}  // namespace

int run_verify(const VerifyOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const auto d = load_and_derive(o.robot);
  if (!d) return kBadInput;
  const std::size_t n = d->model.q.size();
  const auto N = static_cast<Eigen::Index>(n);
  std::vector<CheckResult> checks;

  // (a) symbolic skew-symmetry
  const dyn::Matrix Hdot = dyn::mass_matrix_rate(d->model);
  checks.push_back(prove_skew_symmetry(*d, Hdot));

  // (b) the same numerically, at random states and random standard parameters
  const sym::Substitution constants = d->robot.constant_values();
  std::vector<sym::Expr> inputs = d->model.q;
  inputs.insert(inputs.end(), d->model.qd.begin(), d->model.qd.end());
  const auto ps = d->model.params.symbols();
  inputs.insert(inputs.end(), ps.begin(), ps.end());
  const sym::CompiledFunction hdot_fn(flatten(Hdot, constants), inputs);
  const Eigen::VectorXd nominal = d->numeric->nominal_standard_values();
  double worst_skew = 0.0;
  double worst_relation = 0.0;
  double min_eigen = 1e300;
  int not_pd = 0;
  // All the states at once (the tapes over blocks of states; the same numbers as one by one).
  std::vector<dyn::State> states;
  states.reserve(static_cast<std::size_t>(std::max(0, o.samples)));
  for (int k = 0; k < o.samples; ++k) states.push_back(dyn::random_state(n, 5000U + static_cast<std::uint64_t>(k)));
  const std::vector<dyn::Evaluation> evaluations = d->numeric->evaluate(states, nominal);
  const auto rows = static_cast<Eigen::Index>(states.size());
  // Row k: Hdot at state k, row-major.
  const Eigen::MatrixXd hdot_out = dyn::evaluate_rows(hdot_fn, dyn::state_rows(states, nominal));
  for (Eigen::Index k = 0; k < rows; ++k) {
    const dyn::Evaluation& e = evaluations[static_cast<std::size_t>(k)];
    const Eigen::RowVectorXd hd = hdot_out.row(k);
    const Eigen::MatrixXd HdotN = Eigen::Map<const RowMajor>(hd.data(), N, N);
    const Eigen::MatrixXd Nm = HdotN - 2.0 * e.C;
    const double scale = std::max(1.0, HdotN.cwiseAbs().maxCoeff());
    worst_skew = std::max(worst_skew, (Nm + Nm.transpose()).cwiseAbs().maxCoeff() / scale);
    // (c) H symmetric positive definite
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(e.H);
    min_eigen = std::min(min_eigen, eig.eigenvalues().minCoeff());
    if (eig.eigenvalues().minCoeff() <= 0.0 ||
        (e.H - e.H.transpose()).cwiseAbs().maxCoeff() > 1e-12 * e.H.cwiseAbs().maxCoeff())
      ++not_pd;
    // (d) regressor: Y p == H a + C v + g + friction, both with standard and base parameters
    const Eigen::VectorXd by_y = e.Y * nominal;
    const Eigen::VectorXd by_base = base::base_regressor(d->base, e.Y) * d->base.values(nominal);
    const double tscale = std::max(1e-9, e.tau.cwiseAbs().maxCoeff());
    worst_relation = std::max({worst_relation, (by_y - e.tau).cwiseAbs().maxCoeff() / tscale,
                               (by_base - e.tau).cwiseAbs().maxCoeff() / tscale});
  }
  checks.push_back({"|N + N^T| at random states", worst_skew < 1e-10, fmt::format("{:.3g}", worst_skew),
                    fmt::format("largest |N + N^T| / max(1, |Hdot|) over {} states", o.samples)});
  checks.push_back({"H symmetric positive definite", not_pd == 0, fmt::format("min eigenvalue {:.4g}", min_eigen),
                    fmt::format("{} of {} states failed (nominal parameters)", not_pd, o.samples)});
  checks.push_back(
      {"Y p == H a + C v + g + friction", worst_relation < 1e-9, fmt::format("{:.3g}", worst_relation),
       fmt::format("largest relative difference over {} states, standard and base parameters", o.samples)});

  // (e) energy conservation
  // Conserved up to integrator error: the drift must be tiny, or shrink like RK4's dt^4 when
  // the step is halved (a wrong C or g leaves a drift that does not go away).
  const double drift_coarse = energy_drift(*d, nominal, 1.0, 1e-3);
  const double drift_fine = energy_drift(*d, nominal, 1.0, 5e-4);
  const bool conserved = drift_fine < 1e-9 || drift_fine < drift_coarse / 8.0;
  checks.push_back({"energy conserved (unforced, frictionless RK4)", conserved,
                    fmt::format("{:.2g} -> {:.2g}", drift_coarse, drift_fine),
                    "largest |E(t) - E(0)| / T(0) over 1 s at dt = 1 ms -> 0.5 ms (RK4: ~16x smaller)"});

  // (f) loops
  for (const auto& loop : d->loops) {
    checks.push_back(
        {"loop " + loop.name + " closes", loop.closed,
         fmt::format("gap {:.3g} m at a sample", std::hypot(loop.residual[0], loop.residual[1], loop.residual[2])),
         loop.proved ? "proved: every component of the gap is identically zero" : "by evaluation: " + loop.detail});
  }
  // base parameters
  checks.push_back({"base parameters", d->base.proved,
                    fmt::format("{} of {} standard", d->base.list.size(), d->model.params.list.size()),
                    d->base.proved ? d->base.proof : d->base.note});

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bool all = true;
  for (const auto& c : checks) all = all && c.passed;
  if (o.json) {
    nlohmann::json j;
    j["robot"] = d->robot.name;
    j["passed"] = all;
    j["seconds"] = seconds;
    j["samples"] = o.samples;
    j["checks"] = nlohmann::json::array();
    for (const auto& c : checks)
      j["checks"].push_back({{"name", c.name}, {"passed", c.passed}, {"value", c.value}, {"detail", c.detail}});
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("verify {} ({} coordinates, {} samples)\n", d->robot.name, n, o.samples);
    for (const auto& c : checks)
      fmt::print("  {:<4} {:<48} {:<24} {}\n", c.passed ? "ok" : "FAIL", c.name, c.value, c.detail);
    fmt::print("{} in {:.2f} s\n", all ? "all checks passed" : "SOME CHECKS FAILED", seconds);
  }
  return all ? kSuccess : kCheckFailed;
}

}  // namespace dyncc::cli
