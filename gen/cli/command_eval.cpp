// `dyncc eval`: numbers of the derived model at one state, for the nominal parameters.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/initial_estimate.hpp"
#include "cli/commands.hpp"
#include "cli/robot_input.hpp"
#include "sym/print.hpp"

namespace dyncc::cli {
namespace {

nlohmann::json to_json(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

nlohmann::json to_json(const Eigen::VectorXd& v) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i]);
  return out;
}

void print_matrix(const std::string& name, const Eigen::MatrixXd& m) {
  fmt::print("{} =\n", name);
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    std::string row;
    for (Eigen::Index j = 0; j < m.cols(); ++j) row += fmt::format(" {:>13.6g}", m(i, j));
    fmt::print("  [{} ]\n", row);
  }
}

bool take(const std::vector<double>& given, std::size_t n, Eigen::VectorXd& out, const char* flag,
          const Eigen::VectorXd* fallback) {
  if (given.empty()) {
    out = fallback != nullptr ? *fallback : Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
    return true;
  }
  if (given.size() != n) {
    fmt::print(stderr, "error: {} needs {} comma-separated values (one per coordinate), found {}\n", flag, n,
               given.size());
    return false;
  }
  out = Eigen::Map<const Eigen::VectorXd>(given.data(), static_cast<Eigen::Index>(n));
  return true;
}

}  // namespace

int run_eval(const EvalOptions& o) {
  const auto d = load_and_derive(o.robot);
  if (!d) return kBadInput;
  const std::size_t n = d->model.q.size();
  dyn::State s;
  if (o.q.empty()) {
    fmt::print(stderr, "error: --q is required ({} values)\n", n);
    return kBadInput;
  }
  if (!take(o.q, n, s.q, "--q", nullptr) || !take(o.qd, n, s.qd, "--qd", nullptr) || !take(o.v, n, s.v, "--v", &s.qd) ||
      !take(o.a, n, s.a, "--a", nullptr)) {
    return kBadInput;
  }
  const Eigen::VectorXd standard = d->numeric->nominal_standard_values();
  const dyn::Evaluation e = d->numeric->evaluate(s, standard);
  const Eigen::VectorXd base_values = d->base.values(standard);
  const Eigen::MatrixXd Yb = base::base_regressor(d->base, e.Y);
  const Eigen::VectorXd tau = Yb * base_values;
  // The description's initial_estimate (e.g. the paper's p0..p20) on the base set.
  std::optional<base::InitialEstimate> estimate;
  if (!d->robot.initial_estimate.empty() && d->grouping && d->grouping->complete) {
    estimate = base::map_initial_estimate(d->robot, *d->grouping);
  }

  if (o.json) {
    nlohmann::json j;
    j["robot"] = d->robot.name;
    j["coordinates"] = nlohmann::json::array();
    for (const auto& q : d->model.q) j["coordinates"].push_back(q.name());
    j["state"] = {{"q", to_json(s.q)}, {"qd", to_json(s.qd)}, {"v", to_json(s.v)}, {"a", to_json(s.a)}};
    j["H"] = to_json(e.H);
    j["C"] = to_json(e.C);
    j["g"] = to_json(e.g);
    j["friction"] = to_json(e.friction);
    j["tau"] = to_json(tau);
    j["Y"] = to_json(Yb);
    nlohmann::json names = nlohmann::json::array();
    nlohmann::json defs = nlohmann::json::array();
    for (const auto& b : d->base.list) {
      names.push_back(b.name);
      defs.push_back(sym::to_string(b.definition));
    }
    j["base_parameters"] = {{"names", names}, {"definitions", defs}, {"values", to_json(base_values)}};
    if (estimate) {
      j["initial_estimate"] = {{"names", names},
                               {"values", to_json(estimate->base_values)},
                               {"from_nominal_values", estimate->from_nominal_values}};
    }
    nlohmann::json snames = nlohmann::json::array();
    nlohmann::json sdefs = nlohmann::json::array();
    for (const auto& p : d->model.params.list) {
      snames.push_back(p.name);
      sdefs.push_back(sym::to_string(p.definition));
    }
    j["standard_parameters"] = {{"names", snames}, {"definitions", sdefs}, {"values", to_json(standard)}};
    j["Y_standard"] = to_json(e.Y);
    fmt::print("{}\n", j.dump(2));
    return kSuccess;
  }
  fmt::print("{} at q = [{}]\n", d->robot.name, fmt::join(o.q, ", "));
  print_matrix("H", e.H);
  print_matrix("C", e.C);
  print_matrix("g", e.g);
  print_matrix("friction", e.friction);
  print_matrix("tau", tau);
  print_matrix("Y (base parameters)", Yb);
  fmt::print("base parameters{}:\n", estimate ? " (nominal value, initial_estimate mapped onto the base set)" : "");
  for (std::size_t b = 0; b < d->base.list.size(); ++b) {
    const auto i = static_cast<Eigen::Index>(b);
    const std::string mapped = estimate ? fmt::format(" {:>13.6g}", estimate->base_values[i]) : std::string();
    fmt::print("  {:<8} = {:>13.6g}{}   = {}\n", d->base.list[b].name, base_values[i], mapped,
               sym::to_string(d->base.list[b].definition));
  }
  if (estimate && !estimate->from_nominal_values.empty()) {
    fmt::print("  (initial_estimate gives no value for {}: nominal values used)\n",
               fmt::join(estimate->from_nominal_values, ", "));
  }
  return kSuccess;
}

}  // namespace dyncc::cli
