#include "diagnose/effects.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "diagnose/payload.hpp"
#include "diagnose/shifted_positions.hpp"
#include "diagnose/signals.hpp"
#include "diagnose/torque_noise.hpp"

namespace dyncc::diagnose {
namespace {

constexpr double kStribeckScales[] = {0.02, 0.03, 0.045, 0.065, 0.1, 0.15, 0.22, 0.33, 0.5};  // rad/s, geometric
constexpr double kTorqueSignScale = 0.01;  // N m, smoothed sign of the torque (backlash)
// The smallest Stribeck velocity scale the data resolves on each joint. A static excess over the
// scale vs lasts about 2 vs / |qdd| around a reversal; once that is shorter than the filter's time
// scale, 1 / (2 pi cutoff), the excess is smeared into the same shape as any other mismatch at
// reversals (where the velocity estimate crosses zero a little early or late), so it is not
// evidence of a Stribeck effect. |qdd| is its median where the joint is slow.
Eigen::VectorXd resolved_stribeck_scale(const Dataset& d) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(d.n);
  for (Eigen::Index j = 0; j < d.n; ++j) {
    const double typical = d.qd.col(j).cwiseAbs().mean();
    std::vector<double> slow;
    for (Eigen::Index s = 0; s < d.samples(); ++s) {
      if (std::abs(d.qd(s, j)) < 0.1 * typical) slow.push_back(std::abs(d.qdd(s, j)));
    }
    if (slow.empty()) continue;
    std::nth_element(slow.begin(), slow.begin() + static_cast<std::ptrdiff_t>(slow.size() / 2), slow.end());
    out[j] = 0.5 * slow[slow.size() / 2] / (2 * std::numbers::pi * d.cutoff);
  }
  return out;
}

// One column per joint, nonzero only in that joint's rows: value(s, j).
template <typename F>
Effect per_joint(const Dataset& d, const std::string& name, const std::string& prefix, Reading reading, F value) {
  Effect e;
  e.name = name;
  e.family = name;
  e.columns = Eigen::MatrixXd::Zero(d.samples() * d.n, d.n);
  for (Eigen::Index j = 0; j < d.n; ++j) {
    for (Eigen::Index s = 0; s < d.samples(); ++s) e.columns(s * d.n + j, j) = value(s, j);
    e.parameters.push_back(fmt::format("{}{}", prefix, j + 1));
    e.joint_of.push_back(static_cast<int>(j));
    e.reading.push_back(reading);
  }
  return e;
}

}  // namespace

bool sharp_in_time(std::string_view effect) { return effect == "coulomb_friction" || effect == "stribeck_friction"; }

Eigen::MatrixXd conditioned_columns(const Dataset& d, std::string_view effect, const Eigen::MatrixXd& stacked) {
  return sharp_in_time(effect) ? d.condition(d.prefilter(stacked)) : d.condition(stacked);
}

int payload_link(const pipeline::Derivation& derivation) {
  const auto& links = derivation.robot.links;
  const Eigen::VectorXd nominal = derivation.numeric->nominal_standard_values();
  int best = -1, best_depth = -1;
  double best_mass = -1;
  for (std::size_t l = 0; l < links.size(); ++l) {
    bool leaf = true;
    for (const auto& other : links) leaf = leaf && other.parent != static_cast<int>(l);
    if (!leaf) continue;
    int depth = 0;
    for (int p = static_cast<int>(l); p >= 0; p = links[static_cast<std::size_t>(p)].parent) ++depth;
    const int m = derivation.model.params.of_link[l][0];
    const double mass = m >= 0 ? nominal[m] : 0.0;
    if (depth > best_depth || (depth == best_depth && mass > best_mass)) {
      best = static_cast<int>(l);
      best_depth = depth;
      best_mass = mass;
    }
  }
  return best;
}

std::vector<Effect> candidate_effects(const Dataset& d, const pipeline::Derivation& derivation,
                                      const Eigen::VectorXd& rests) {
  std::vector<Effect> out;
  const Eigen::Index rows = d.samples() * d.n;

  const Eigen::VectorXd scale = friction_sign_velocity(d);
  auto sign = [&](Eigen::Index s, Eigen::Index j) { return smooth_sign(d.qd(s, j), scale[j]); };
  out.push_back(per_joint(d, "coulomb_friction", "fc", Reading::as_is, sign));
  out.push_back(per_joint(d, "viscous_friction", "fv", Reading::as_is,
                          [&](Eigen::Index s, Eigen::Index j) { return d.qd(s, j); }));
  // Stribeck: Coulomb plus a static excess that fades with speed; with its Coulomb column it is a
  // superset of coulomb_friction, so it wins only when the fading is in the data.
  const Eigen::VectorXd resolved = resolved_stribeck_scale(d);
  for (const double vs : kStribeckScales) {
    if ((resolved.array() > vs).all()) continue;  // no joint resolves this scale
    Effect e = per_joint(d, "stribeck_friction", "fc", Reading::as_is, sign);
    const Effect excess = per_joint(d, "stribeck_friction", "fs", Reading::as_is, [&](Eigen::Index s, Eigen::Index j) {
      return vs >= resolved[j] ? stribeck_fade(d.qd(s, j), vs) * sign(s, j) : 0.0;
    });
    Eigen::MatrixXd both(rows, 2 * d.n);
    both << e.columns, excess.columns;
    e.columns = both;
    e.parameters.insert(e.parameters.end(), excess.parameters.begin(), excess.parameters.end());
    e.joint_of.insert(e.joint_of.end(), excess.joint_of.begin(), excess.joint_of.end());
    e.reading.insert(e.reading.end(), excess.reading.begin(), excess.reading.end());
    e.profile_name = "velocity_scale";
    e.profile = vs;
    out.push_back(e);
  }
  out.push_back(
      per_joint(d, "rotor_inertia", "ia", Reading::as_is, [&](Eigen::Index s, Eigen::Index j) { return d.qdd(s, j); }));
  // Measured torque = nominal / gain: residual = (1/gain - 1) tau_model.
  out.push_back(per_joint(d, "torque_gain", "gain", Reading::gain,
                          [&](Eigen::Index s, Eigen::Index j) { return d.model_tau(s, j); }));
  const std::size_t delay_at = out.size();
  {  // Positions measured late by `delay`: the torque leads the model by delay * d tau_model/dt.
    Effect e;
    e.name = e.family = "sensor_delay";
    e.columns.resize(rows, 1);
    for (Eigen::Index s = 0; s < d.samples(); ++s) {
      for (Eigen::Index i = 0; i < d.n; ++i) e.columns(s * d.n + i, 0) = d.model_tau_rate(s, i);
    }
    e.parameters = {"delay"};
    e.joint_of = {-1};
    e.reading = {Reading::as_is};
    out.push_back(e);
  }
  {  // Within the model's structure: every rigid-body base parameter re-identified.
    Effect e;
    e.name = e.family = "inertial_parameters";
    e.columns = d.base_rigid;
    e.parameters = d.base_rigid_names;
    e.joint_of.assign(d.base_rigid_names.size(), -1);
    e.reading.assign(d.base_rigid_names.size(), Reading::as_is);
    out.push_back(e);
  }
  // Into the analysis rows, through the filter's two passes as the logged torque (dataset.hpp).
  for (Effect& e : out) e.columns = conditioned_columns(d, e.name, e.columns);
  fit_delay_column(d, out[delay_at]);  // a secant where the delay is large
  // Effects that shift the measured positions off the link's, by theta_j w_j(t) (conditioned as
  // they are made: the columns are re-linearised at a first fit).
  const ModelSensitivity sensitivity = model_sensitivity(d, derivation);
  auto shifted = [&](const std::string& name, const std::string& prefix, Reading reading, auto w) {
    Effect e = per_joint(d, name, prefix, reading, [](Eigen::Index, Eigen::Index) { return 0.0; });
    Eigen::MatrixXd raw(d.samples(), d.n);
    for (Eigen::Index s = 0; s < d.samples(); ++s) {
      for (Eigen::Index j = 0; j < d.n; ++j) raw(s, j) = w(s, j);
    }
    fit_shift_columns(d, derivation, sensitivity, filtered_shift(d, raw), e);
    out.push_back(std::move(e));
  };
  shifted("position_offset", "offset", Reading::as_is, [](Eigen::Index, Eigen::Index) { return 1.0; });
  // Read on the motor side of a spring: the link lags the motor by the torque it carries over the
  // stiffness.
  const Eigen::MatrixXd& carried = sensitivity.transmitted;
  shifted("joint_elasticity", "stiffness", Reading::reciprocal,
          [&](Eigen::Index s, Eigen::Index j) { return carried(s, j); });
  out.back().torque_noise = std::make_shared<const NoiseDraws>(carried_torque_noise(d, sensitivity));
  // Backlash of width b: the link sits b/2 behind the motor on the side that torque pushes (on a
  // joint where it turns over: elsewhere it is an offset, the simpler explanation).
  const Eigen::VectorXd turning = minority_sign_share(carried);
  shifted("backlash", "width", Reading::as_is, [&](Eigen::Index s, Eigen::Index j) {
    return turning[j] >= kBacklashTurnOver ? 0.5 * std::tanh(carried(s, j) / kTorqueSignScale) : 0.0;
  });
  // Conditioned as they are made (a load's point is fitted).
  PayloadPlacer(d, derivation, rests).add_effects(d.residual, Eigen::MatrixXd(), out);
  return out;
}

}  // namespace dyncc::diagnose
