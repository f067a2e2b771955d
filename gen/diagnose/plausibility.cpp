#include "diagnose/plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace dyncc::diagnose {
namespace {

constexpr double kFarthestPoint = 2.0;  // m: a payload or contact point farther from its link is implausible

// The joint (0-based) of a per-joint parameter named prefix + number ("fc2", "stiffness3"), or -1.
int joint_of_parameter(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0 || name.size() <= prefix.size()) return -1;
  return std::atoi(name.c_str() + prefix.size()) - 1;
}

}  // namespace

bool plausible_parameter(const FittedParameter& p, const pipeline::Derivation& derivation, const Gap& gap) {
  const Eigen::VectorXd& torque_rms = gap.torque_rms;
  const Eigen::VectorXd nominal = derivation.numeric->nominal_standard_values();
  const auto& params = derivation.model.params;
  auto described = [&](const std::string& name, const char* prefix, const std::vector<int>& of) {
    const int joint = joint_of_parameter(name, prefix);
    if (joint < 0 || joint >= static_cast<int>(of.size())) return 0.0;
    const int index = of[static_cast<std::size_t>(joint)];
    return index >= 0 ? nominal[index] : 0.0;
  };
  // A contact's friction is judged by its coefficient, friction per unit of push (and its
  // spring's share): a frictionless table's fit reads a mean friction force of a few mN either
  // side of zero beside a push of tenths of a newton (blind seed 433 case 19: -2.2 +- 0.7 mN
  // beside 0.47 N, a coefficient of -0.009 +- 0.011).
  const bool non_negative = p.name.rfind("fc", 0) == 0 || p.name.rfind("fv", 0) == 0 || p.name.rfind("fs", 0) == 0 ||
                            p.name == "mass" || p.name.rfind("ia", 0) == 0 || p.name == "force" ||
                            p.name.rfind("stiffness", 0) == 0 || p.name.rfind("width", 0) == 0 || p.name == "damping" ||
                            p.name == "friction_coefficient" || p.name == "friction_stiffness";
  const double total = p.value + described(p.name, "fc", params.coulomb_of) +
                       described(p.name, "fv", params.viscous_of) + described(p.name, "ia", params.rotor_of);
  if (non_negative && total < -2.0 * p.error) return false;
  // A drive whose torque is off by more than a factor of two is a wrong description, not a gain.
  if (p.name.rfind("gain", 0) == 0 && (p.value < 0.5 || p.value > 2.0)) return false;
  // A transmission that gives way by more than twice kLargestDeflection RMS under its joint's
  // torque, or a dead band wider than four times it (0.1 and 0.2 rad: twice what the bench
  // draws), is a loose joint or a wrong description (the TX40's wrist read as springs of 2-10
  // N m/rad, 0.3-0.6 rad under its torque, soaking up what the rotor inertias lack).
  const int spring = joint_of_parameter(p.name, "stiffness"), band = joint_of_parameter(p.name, "width");
  if (spring >= 0 && spring < torque_rms.size() &&
      torque_rms[spring] > 2.0 * kLargestDeflection * (p.value + 2.0 * p.error)) {
    return false;
  }
  if (band >= 0 && band < torque_rms.size() && p.value - 2.0 * p.error > 4.0 * kLargestDeflection) return false;
  // ... and one that moves the positions by less than the sensor resolves (the larger of its
  // quantum and noise) is a model mismatch that happens to look like a shift: a spring's RMS
  // deflection under the joint's torque must be two of those steps (a smooth shift of a step or
  // so is what quantisation and an estimator's lag make of any mismatch: effect-free
  // closed-loop Kraft logs at 200 Hz, 1.5 mrad potentiometer steps, were read as springs of
  // 270-333 N m/rad giving way 0.9-1.6 mrad, and beside a rotor inertia one took 11 % of it); a
  // dead band jumps by its full width at each turn and half of it must be one step (a 0.64 mrad
  // band on 0.2 mrad steps is read within 1 %).
  if (spring >= 0 && spring < torque_rms.size() &&
      torque_rms[spring] < 2.0 * gap.position_resolution[spring] * std::max(p.value, 1e-12)) {
    return false;
  }
  if (band >= 0 && band < torque_rms.size() && 0.5 * p.value < gap.position_resolution[band]) return false;
  return true;
}

bool plausible(const RankedEffect& r, const pipeline::Derivation& derivation, const Gap& gap) {
  for (const FittedParameter& p : r.parameters) {
    if (!plausible_parameter(p, derivation, gap)) return false;
  }
  // A held contact (its push alone, no moments) pushes beyond twice its error: a push within
  // it of zero is no contact.
  const bool held =
      r.family == "contact" && std::none_of(r.parameters.begin(), r.parameters.end(),
                                            [](const FittedParameter& p) { return p.name.rfind("moment_", 0) == 0; });
  if (held && std::any_of(r.parameters.begin(), r.parameters.end(),
                          [](const FittedParameter& p) { return p.name == "force" && p.value <= 2.0 * p.error; })) {
    return false;
  }
  // A load or a contact is on the link, not metres away: a first moment with next to no mass (a
  // payload of 0.1 g at 46 m on a Kraft log whose forearm was read 0.05 rad off) is the columns
  // mimicking another effect.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  for (const FittedParameter& p : r.parameters) {
    if (p.name.size() == 7 && p.name.rfind("point_", 0) == 0) point[p.name[6] - 'x'] = p.value;
  }
  return point.norm() <= kFarthestPoint;
}

}  // namespace dyncc::diagnose
