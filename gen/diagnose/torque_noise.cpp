#include "diagnose/torque_noise.hpp"

#include <cmath>
#include <random>

namespace dyncc::diagnose {

NoiseDraws carried_torque_noise(const Dataset& d, const ModelSensitivity& m) {
  const Eigen::Index n = d.n, samples = d.samples();
  NoiseDraws out;
  for (Eigen::Index j = 0; j < n; ++j) out.at.push_back(j);
  std::mt19937_64 random(0x5eed);  // NOLINT(cert-msc32-c,cert-msc51-cpp): the same draws every run, on purpose
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int draw = 0; draw < kTorqueNoiseDraws; ++draw) {
    Eigen::MatrixXd noise(samples, n);
    for (const Dataset::Segment& g : d.segments) {
      const Audit& audit = d.audits[static_cast<std::size_t>(d.log_of[static_cast<std::size_t>(g.begin)])];
      // Evaluation rows thinner than the log's keep its noise density in the band (anti-aliased,
      // then decimated): per row a variance smaller by the ratio of the rates.
      const double thinning = audit.rate > 0 ? std::sqrt(std::min(1.0, g.rate / audit.rate)) : 1.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        const double sigma = audit.joints[static_cast<std::size_t>(j)].torque_noise * thinning;
        for (Eigen::Index s = g.begin; s < g.end; ++s) noise(s, j) = sigma * unit(random);
      }
    }
    out.columns.emplace_back(d.condition(shift_tangents(d, m, filtered_shift(d, noise))));
    const Eigen::MatrixXd transposed = noise.transpose();  // stacked: row s*n + j
    // Into the residual through both passes, as the logged torque (Dataset::prefilter).
    out.target.emplace_back(
        d.condition(d.prefilter(Eigen::Map<const Eigen::VectorXd>(transposed.data(), samples * n))).col(0));
  }
  return out;
}

}  // namespace dyncc::diagnose
