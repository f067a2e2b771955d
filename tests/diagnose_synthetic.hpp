// Synthetic logs for the diagnosis tests: an exciting trajectory (a sum of sines per joint, with
// exact rates), the torque of the description's model with one effect injected, positions
// quantised and torques noisy, written as the CSV `dyncc diagnose` reads.
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "pipeline/derivation.hpp"

namespace dyncc::test {

struct Injection {
  std::string effect =
      "none";       // coulomb_friction, viscous_friction, payload, torque_gain, sensor_delay, position_offset
  int joint = 0;    // 0-based, for per-joint effects
  double size = 0;  // fc (N m), fv (N m s), mass (kg), gain, delay (s), offset (rad)
};

struct SyntheticLog {
  double rate = 200;           // Hz
  double duration = 40;        // s
  double quantum = 2e-4;       // rad
  double torque_noise = 0.01;  // N m
  unsigned seed = 1;
};

/// Writes the log to `path`; returns the torque RMS per joint of the clean model torque.
inline Eigen::VectorXd write_synthetic_log(const pipeline::Derivation& d, const Injection& inject,
                                           const SyntheticLog& s, const std::filesystem::path& path) {
  const auto n = static_cast<Eigen::Index>(d.robot.coordinates.size());
  const dyn::NumericModel& model = *d.numeric;
  Eigen::VectorXd standard = model.nominal_standard_values();
  if (inject.effect == "payload") {
    // A point mass at (0.05, 0, 0) in the payload link's frame: its standard parameters.
    int link = -1, depth = -1;
    double heaviest = -1;
    for (std::size_t l = 0; l < d.robot.links.size(); ++l) {
      bool leaf = true;
      for (const auto& other : d.robot.links) leaf = leaf && other.parent != static_cast<int>(l);
      int k = 0;
      for (int p = static_cast<int>(l); p >= 0; p = d.robot.links[static_cast<std::size_t>(p)].parent) ++k;
      const int m = d.model.params.of_link[l][0];
      const double mass = m >= 0 ? standard[m] : 0;
      if (leaf && (k > depth || (k == depth && mass > heaviest))) {
        link = static_cast<int>(l);
        depth = k;
        heaviest = mass;
      }
    }
    const double m = inject.size, x = 0.05;
    const std::array<double, 10> delta{m, m * x, 0,         0, 0,
                                       0, 0,     m * x * x, 0, m * x * x};  // M MX MY MZ XX XY XZ YY YZ ZZ
    for (int k = 0; k < 10; ++k) {
      const int index = d.model.params.of_link[static_cast<std::size_t>(link)][static_cast<std::size_t>(k)];
      if (index >= 0) standard[index] += delta[static_cast<std::size_t>(k)];
    }
  }
  std::mt19937 random(s.seed);
  std::normal_distribution<double> noise(0.0, s.torque_noise);
  std::uniform_real_distribution<double> phase(0.0, 6.283185307179586);
  // Per joint: three sines at incommensurate low frequencies (0.1..0.6 Hz), 0.3..0.6 rad.
  std::vector<std::array<double, 6>> waves(static_cast<std::size_t>(n));
  for (auto& w : waves) w = {phase(random), phase(random), phase(random), 0.3 + 0.1 * phase(random) / 6.3, 0.2, 0.15};
  auto trajectory = [&](double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) {
    q.resize(n);
    qd.resize(n);
    qdd.resize(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      const auto& w = waves[static_cast<std::size_t>(j)];
      q[j] = qd[j] = qdd[j] = 0;
      const double freq[3] = {0.11 + 0.03 * static_cast<double>(j), 0.29 + 0.05 * static_cast<double>(j), 0.53};
      for (int k = 0; k < 3; ++k) {
        const double omega = 2 * 3.141592653589793 * freq[k], a = w[static_cast<std::size_t>(3 + k)];
        q[j] += a * std::sin(omega * t + w[static_cast<std::size_t>(k)]);
        qd[j] += a * omega * std::cos(omega * t + w[static_cast<std::size_t>(k)]);
        qdd[j] -= a * omega * omega * std::sin(omega * t + w[static_cast<std::size_t>(k)]);
      }
    }
  };
  std::ofstream out(path);
  out << "t";
  for (Eigen::Index j = 1; j <= n; ++j) out << ",q" << j;
  for (Eigen::Index j = 1; j <= n; ++j) out << ",tau" << j;
  out << "\n";
  out.precision(10);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n);
  const auto samples = static_cast<long>(s.duration * s.rate);
  for (long i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / s.rate;
    Eigen::VectorXd q, qd, qdd;
    trajectory(t, q, qd, qdd);
    const dyn::Evaluation e = model.evaluate({q, qd, qd, qdd}, standard, false);
    Eigen::VectorXd tau = e.tau;
    sum += e.tau.cwiseAbs2();
    const auto j = static_cast<Eigen::Index>(inject.joint);
    if (inject.effect == "coulomb_friction") tau[j] += inject.size * (qd[j] > 0 ? 1.0 : (qd[j] < 0 ? -1.0 : 0.0));
    if (inject.effect == "viscous_friction") tau[j] += inject.size * qd[j];
    if (inject.effect == "torque_gain") tau[j] /= inject.size;  // the logged command; the motor gives gain * it
    Eigen::VectorXd logged_q = q;
    if (inject.effect == "sensor_delay") {
      Eigen::VectorXd qd2, qdd2;
      trajectory(t - inject.size, logged_q, qd2, qdd2);
    }
    if (inject.effect == "position_offset") logged_q[j] += inject.size;
    out << t;
    for (Eigen::Index k = 0; k < n; ++k) out << ',' << s.quantum * std::round(logged_q[k] / s.quantum);
    for (Eigen::Index k = 0; k < n; ++k) out << ',' << tau[k] + noise(random);
    out << "\n";
  }
  return (sum / static_cast<double>(samples)).cwiseSqrt();
}

}  // namespace dyncc::test
