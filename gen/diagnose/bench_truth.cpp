#include "diagnose/bench_truth.hpp"

#include <algorithm>

#include "diagnose/crossval.hpp"
#include "diagnose/effects.hpp"

namespace dyncc::diagnose {

bool names_injected_effect(const std::string& named, const std::vector<Injection>& injected) {
  if (injected.empty()) return named == "none";
  const Injection& largest = injected.front();
  if (named == largest.effect) return true;
  return named == "stribeck_friction" && largest.effect == "coulomb_friction" &&
         std::any_of(injected.begin() + 1, injected.end(),
                     [&](const Injection& e) { return e.effect == "stribeck_friction" && e.joint == largest.joint; });
}

std::optional<Eigen::VectorXd> closed_loop_effect_rms(const Dataset& data, const Injection& e) {
  constexpr double kSimStribeckVelocity = 0.1;  // rad/s, dyncc-sim's default vs
  const Eigen::Index n = data.n, j = e.joint;
  const double band = zero_velocity_band(data)[j];
  auto sign_of = [band](double v) { return std::abs(v) < band ? 0.0 : std::copysign(1.0, v); };
  Eigen::MatrixXd torque = Eigen::MatrixXd::Zero(data.samples() * n, 1);
  for (Eigen::Index s = 0; s < data.samples(); ++s) {
    const double v = data.qd(s, j);
    if (e.effect == "coulomb_friction")
      torque(s * n + j, 0) = e.size * sign_of(v);
    else if (e.effect == "viscous_friction")
      torque(s * n + j, 0) = e.size * v;
    else if (e.effect == "stribeck_friction")
      torque(s * n + j, 0) = e.size * stribeck_fade(v, kSimStribeckVelocity) * sign_of(v);
    else if (e.effect == "rotor_inertia")
      torque(s * n + j, 0) = e.size * data.qdd(s, j);
    else if (e.effect == "torque_gain")
      torque(s * n + j, 0) = (1.0 / e.size - 1.0) * data.model_tau(s, j);
    else if (e.effect == "position_offset")
      torque.block(s * n, 0, n, 1) = -data.dtau_dq[static_cast<std::size_t>(s)].col(j) * e.size;
    else if (e.effect == "sensor_delay")
      torque.block(s * n, 0, n, 1) = data.model_tau_rate.row(s).transpose() * e.size;
    else
      return std::nullopt;
  }
  return joint_rms(conditioned_columns(data, e.effect, torque).col(0), n);
}

}  // namespace dyncc::diagnose
