#include "diagnose/gap.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "diagnose/crossval.hpp"

namespace dyncc::diagnose {
namespace {

// What the model's own friction is uncertain by: its Coulomb term with the velocity estimate off
// by one standard error (from the positions' noise and quantisation through the filter's
// bandwidth), through the same filter as the residual. A reversal's sign change is placed only
// as well as the velocity's zero is known, so this much residual at reversals is no evidence of a
// missing effect.
Eigen::VectorXd sign_floor(const Dataset& d, const pipeline::Derivation& derivation) {
  const Eigen::Index n = d.n, samples = d.samples();
  const Eigen::VectorXd nominal = derivation.numeric->nominal_standard_values();
  const auto& coulomb_of = derivation.model.params.coulomb_of;
  const Eigen::VectorXd error = velocity_error(d);
  Eigen::VectorXd floor = Eigen::VectorXd::Zero(n);
  for (Eigen::Index j = 0; j < n && j < static_cast<Eigen::Index>(coulomb_of.size()); ++j) {
    const int index = coulomb_of[static_cast<std::size_t>(j)];
    if (index < 0 || nominal[index] == 0) continue;
    const double velocity_error = error[j];
    Eigen::MatrixXd change = Eigen::MatrixXd::Zero(samples * n, 1);
    for (Eigen::Index s = 0; s < samples; ++s) {
      const double v = d.qd(s, j);
      change(s * n + j, 0) = 0.5 * nominal[index] * (smooth_sign(v + velocity_error) - smooth_sign(v - velocity_error));
    }
    floor[j] = joint_rms(d.condition(d.prefilter(change)).col(0), n)[j];  // sharp: both passes
  }
  return floor;
}

}  // namespace

Gap locate_gap(const Dataset& d, const Eigen::VectorXd& heldout, const pipeline::Derivation& derivation) {
  Gap g;
  const Eigen::Index n = d.n, samples = d.rows();
  g.residual_rms = joint_rms(heldout, n);
  g.torque_rms = analysis_torque_rms(d);
  g.percent = 100.0 * g.residual_rms.cwiseQuotient(g.torque_rms.cwiseMax(1e-12));
  g.noise_floor = Eigen::VectorXd::Zero(n);
  for (std::size_t l = 0; l < d.audits.size(); ++l) {
    const Audit& a = d.audits[l];
    const double band = std::sqrt(std::min(1.0, 2.0 * d.cutoff / a.rate));
    for (Eigen::Index j = 0; j < n; ++j) {
      g.noise_floor[j] = std::max(g.noise_floor[j], a.joints[static_cast<std::size_t>(j)].torque_noise * band);
    }
  }
  g.position_floor = d.position_noise_torque;
  g.position_resolution = Eigen::VectorXd::Zero(n);
  for (const Audit& a : d.audits) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const JointAudit& joint = a.joints[static_cast<std::size_t>(j)];
      g.position_resolution[j] = std::max({g.position_resolution[j], joint.quantum, joint.position_noise});
    }
  }
  g.sign_floor = sign_floor(d, derivation);
  // Time windows of about 2 s (at least 10 rows), flagged at twice the median window RMS.
  const auto length = std::max<Eigen::Index>(10, static_cast<Eigen::Index>(2.0 / d.step));
  std::vector<std::pair<Eigen::Index, double>> windows;
  for (Eigen::Index begin = 0; begin + length <= samples; begin += length) {
    double sum = 0;
    for (Eigen::Index s = begin; s < begin + length; ++s) {
      for (Eigen::Index j = 0; j < n; ++j) sum += std::pow(heldout[s * n + j] / std::max(g.torque_rms[j], 1e-12), 2);
    }
    windows.emplace_back(begin, std::sqrt(sum / static_cast<double>(length * n)));
  }
  if (!windows.empty()) {
    std::vector<double> values;
    values.reserve(windows.size());
    for (const auto& w : windows) values.push_back(w.second);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
    const double median = values[values.size() / 2];
    for (const auto& [begin, value] : windows) {
      if (median > 0 && value > 2.0 * median) {
        const Eigen::Index last = begin + length - 1;
        g.windows.push_back(
            {d.analysis_log[static_cast<std::size_t>(begin)], d.analysis_t[begin], d.analysis_t[last], value / median});
      }
    }
  }
  // Regimes per joint: near-zero velocity, reversals (sign change within 0.2 s), high acceleration.
  const char* names[] = {"near_zero_velocity", "reversal", "high_acceleration", "other"};
  std::vector<Regime> regimes(4);
  for (int k = 0; k < 4; ++k) {
    regimes[static_cast<std::size_t>(k)] = {names[k], Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  }
  const auto reach = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(0.2 / d.step));
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd acc = d.analysis_qdd.col(j).cwiseAbs();
    std::vector<double> sorted(acc.data(), acc.data() + acc.size());
    std::sort(sorted.begin(), sorted.end());
    const double high = sorted[static_cast<std::size_t>(0.85 * static_cast<double>(sorted.size() - 1))];
    const double vmax = d.analysis_qd.col(j).cwiseAbs().maxCoeff();
    std::array<double, 4> sum{}, count{};
    for (Eigen::Index s = 0; s < samples; ++s) {
      bool reversal = false;
      for (Eigen::Index o = std::max<Eigen::Index>(1, s - reach); o <= std::min(samples - 1, s + reach); ++o) {
        reversal = reversal ||
                   (d.analysis_qd(o - 1, j) * d.analysis_qd(o, j) < 0 &&
                    d.analysis_log[static_cast<std::size_t>(o)] == d.analysis_log[static_cast<std::size_t>(o - 1)]);
      }
      int k = 3;
      if (std::abs(d.analysis_qd(s, j)) < 0.05 * vmax)
        k = 0;
      else if (reversal)
        k = 1;
      else if (acc[s] >= high)
        k = 2;
      sum[static_cast<std::size_t>(k)] += heldout[s * n + j] * heldout[s * n + j];
      count[static_cast<std::size_t>(k)] += 1;
    }
    for (std::size_t k = 0; k < 4; ++k) {
      regimes[k].rms[j] = count[k] > 0 ? std::sqrt(sum[k] / count[k]) : 0.0;
      regimes[k].share[j] = count[k] / static_cast<double>(samples);
    }
  }
  g.regimes = regimes;
  return g;
}
}  // namespace dyncc::diagnose
