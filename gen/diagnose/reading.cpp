// What a candidate's fit reads as: the joints where it acts, its parameters in physical units
// with their 95 % intervals (a contact's point, a friction coefficient), and which joints of a
// per-joint effect read plausibly.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "diagnose/plausibility.hpp"
#include "diagnose/regime_error.hpp"
#include "diagnose/selection.hpp"

namespace dyncc::diagnose {
namespace {

constexpr double kJointShrink = 0.10;  // ... and 10 % on a joint to count as acting there

}  // namespace

double physical(Reading reading, double theta) {
  switch (reading) {
    case Reading::reciprocal: return theta != 0 ? 1.0 / theta : 0.0;
    case Reading::gain: return 1.0 / (1.0 + theta);
    case Reading::as_is: break;
  }
  return theta;
}

// Whether an effect has one column set per joint (friction, gain, offset, ...).
bool per_joint(const Effect& e) {
  return !e.joint_of.empty() && std::all_of(e.joint_of.begin(), e.joint_of.end(), [](int j) { return j >= 0; });
}

// Whether an effect shows as the measured positions being off the link's (an offset, a spring, a
// dead band): its column of joint j has rows on every joint whose torque that position moves.
bool shifts_positions(const Effect& e) {
  return e.family == "position_offset" || e.family == "joint_elasticity" || e.family == "backlash";
}

// For an effect with one column set per joint (friction, gain, offset, ...), the joints whose
// own columns carry a material, significant part of the fit: where the effect IS, rather than
// where its fit happens to lower the residual (an offset of joint 2 changes joint 3's torque too).
std::vector<int> own_joints(const Candidate& c, Eigen::Index offset, const Eigen::VectorXd& torque_rms) {
  const Effect& e = *c.effect;
  const Eigen::Index n = torque_rms.size(), rows = e.columns.rows() / n;
  std::vector<int> joints;
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd part = Eigen::VectorXd::Zero(e.columns.rows());
    bool significant = false;
    for (Eigen::Index k = 0; k < e.columns.cols(); ++k) {
      if (e.joint_of[static_cast<std::size_t>(k)] != j) continue;
      const double theta = c.cv.theta[offset + k];
      part += e.columns.col(k) * theta;
      significant = significant || std::abs(theta) > 2.0 * c.cv.theta_error[offset + k];
    }
    double largest = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      double sum = 0;
      for (Eigen::Index s = 0; s < rows; ++s) sum += part[s * n + i] * part[s * n + i];
      largest = std::max(largest, std::sqrt(sum / static_cast<double>(rows)) / std::max(torque_rms[i], 1e-12));
    }
    if (significant && largest >= kMaterial) joints.push_back(static_cast<int>(j) + 1);
  }
  return joints;
}

namespace {

// The 95 % interval of a fitted column's coefficient `theta` (half-width `half`, Student's t over
// the folds) read as its physical value: the reading is monotonic on each side of its pole (a
// compliance of 0, a gain column of -1), so the ends map to the ends; an interval that reaches
// the pole is unbounded on that side (a spring the folds cannot tell from rigid).
std::pair<double, double> read_interval(Reading reading, double theta, double half) {
  const double pole = reading == Reading::gain ? -1.0 : 0.0;
  const double a = theta - half, b = theta + half;
  const double inf = std::numeric_limits<double>::infinity();
  if (reading != Reading::as_is && a <= pole && pole <= b) {
    // The side of the value runs from the nearer end to infinity (the reading falls on both
    // sides of the pole: 1/theta and 1/(1 + theta) decrease).
    return theta > pole ? std::pair{physical(reading, b), inf} : std::pair{-inf, physical(reading, a)};
  }
  const double x = physical(reading, a), y = physical(reading, b);
  return {std::min(x, y), std::max(x, y)};
}

// A derived value's 95 % interval, symmetric to first order (a point from a force and moments).
FittedParameter symmetric_interval(FittedParameter p) {
  std::tie(p.low, p.high) = read_interval(Reading::as_is, p.value, student95(kFolds - 1) * p.error);
  return p;
}

// A point of action in the link frame from a total and its first moments (c = M / F): a
// contact's from its force and moments, a load's from its mass and m c.
void add_point(RankedEffect& r, const std::string& total, const std::string& moment_prefix) {
  auto find = [&](const std::string& name) {
    for (const FittedParameter& p : r.parameters) {
      if (p.name == name) return p;
    }
    return FittedParameter{};
  };
  const FittedParameter whole = find(total);
  if (whole.value == 0) return;
  for (const char axis : {'x', 'y', 'z'}) {
    const FittedParameter moment = find(moment_prefix + axis);
    const double value = moment.value / whole.value;
    const double error = std::hypot(moment.error, value * whole.error) / std::abs(whole.value);
    r.parameters.push_back(symmetric_interval({std::string("point_") + axis, value, error}));
  }
}

// A contact's friction coefficient: its friction over its normal force, from the pair (offset or
// spring) that the fit knows better.
void add_friction_coefficient(RankedEffect& r) {
  std::map<std::string, FittedParameter> p;
  for (const FittedParameter& x : r.parameters) p[x.name] = x;
  auto known = [&](const std::string& name) { return std::abs(p[name].value) / (p[name].error + 1e-300); };
  const bool spring = known("stiffness") > known("force");
  const FittedParameter normal = p[spring ? "stiffness" : "force"];
  const FittedParameter friction = p[spring ? "friction_stiffness" : "friction_force"];
  if (normal.value == 0) return;
  const double mu = friction.value / normal.value;
  r.parameters.push_back(symmetric_interval(
      {"friction_coefficient", mu, std::hypot(friction.error, mu * normal.error) / std::abs(normal.value)}));
}

// A held contact's point is the gate's (the search's resolution, not a fit).
void add_held_point(RankedEffect& r, const ContactPoint& at) {
  for (int axis = 0; axis < 3; ++axis) {
    r.parameters.push_back({std::string("point_") + static_cast<char>('x' + axis), at.point[axis], 0.0});
  }
}

}  // namespace

// A pressed contact's push at its fitted surface (the point at rest there): the push at the
// mean depth of the rows in contact less the spring's share of it, with its error over the
// folds; nothing for any other effect. A spring contact pushes from its surface on, so a push
// there clearly below zero is a surface placed too high; a penalty contact with a damper lets go
// before the point leaves the surface, which reads the same (ContactRows::effect).
std::optional<FittedParameter> surface_push(const Candidate& c, Eigen::Index offset) {
  const Effect& e = *c.effect;
  if (e.family != "contact" || e.columns.cols() != 8) return std::nullopt;
  const auto depth =
      std::find_if(e.shape.begin(), e.shape.end(), [](const ShapeValue& v) { return v.name == "mean_depth"; });
  if (depth == e.shape.end()) return std::nullopt;
  const Eigen::MatrixXd folds = c.cv.theta_folds.row(offset) - depth->value * c.cv.theta_folds.row(offset + 4);
  return symmetric_interval(
      {"surface_push", c.cv.theta[offset] - depth->value * c.cv.theta[offset + 4], jackknife_error(folds)[0]});
}

RankedEffect describe(const Candidate& c, const Eigen::VectorXd& before, Eigen::Index offset,
                      const Eigen::VectorXd& torque_rms) {
  RankedEffect r;
  const Effect& e = *c.effect;
  r.effect = e.name;
  r.family = e.family;
  r.before = before;
  r.after = c.after;
  r.shrink = c.shrink;
  r.shrink_low = c.low;
  r.shrink_high = c.high;
  r.columns = static_cast<std::size_t>(e.columns.cols());
  r.profile_name = e.profile_name;
  r.profile = e.profile;
  if (per_joint(e)) {
    r.joints = own_joints(c, offset, torque_rms);
  } else {
    for (Eigen::Index j = 0; j < before.size(); ++j) {
      if (before[j] > 0 && 1.0 - c.after[j] / before[j] >= kJointShrink) r.joints.push_back(static_cast<int>(j) + 1);
    }
  }
  for (Eigen::Index k = 0; k < e.columns.cols(); ++k) {
    const int joint = e.joint_of[static_cast<std::size_t>(k)];
    if (joint >= 0 && std::find(r.joints.begin(), r.joints.end(), joint + 1) == r.joints.end()) continue;
    const double scale = c.applied_scale.size() > 0 ? c.applied_scale[offset + k] : 1.0;
    const Eigen::VectorXd& read = c.read_theta.size() > 0 ? c.read_theta : c.cv.theta;
    const Eigen::VectorXd& spread = c.read_error.size() > 0 ? c.read_error : c.cv.theta_error;
    const double theta = scale * read[offset + k];
    const double error = scale * (c.systematic.size() > 0 ? std::hypot(spread[offset + k], c.systematic[offset + k])
                                                          : spread[offset + k]);
    const Reading reading = e.reading[static_cast<std::size_t>(k)];
    const double value = physical(reading, theta);
    // First-order propagation of the error through the reading.
    const double derivative =
        std::abs(physical(reading, theta + 1e-6 * (1 + std::abs(theta))) - value) / (1e-6 * (1 + std::abs(theta)));
    FittedParameter p{e.parameters[static_cast<std::size_t>(k)], value, derivative * error};
    std::tie(p.low, p.high) = read_interval(reading, theta, student95(kFolds - 1) * error);
    r.parameters.push_back(p);
  }
  if (e.family == "contact") {
    const ContactPoint at = ContactPoint::of(e);
    if (at.held) {
      add_held_point(r, at);
    } else {
      add_point(r, "force", "moment_");
      add_friction_coefficient(r);
      if (const auto push = surface_push(c, offset)) r.parameters.push_back(*push);
    }
    r.parameters.push_back({"surface_height", r.profile, 0.0});
  }
  if (e.family == "payload") add_point(r, "mass", "m");
  for (const ShapeValue& v : e.shape) r.parameters.push_back({v.name, v.value, v.resolution});
  return r;
}

// The joints (0-based) of a per-joint candidate's own joints whose fitted parameters all make
// physical sense.
std::vector<int> plausible_joints(const Effect& e, const RankedEffect& r, const pipeline::Derivation& derivation,
                                  const Gap& gap) {
  std::vector<int> out;
  for (const int joint : r.joints) {
    bool fine = true;
    for (std::size_t k = 0; k < e.parameters.size(); ++k) {
      if (e.joint_of[k] != joint - 1) continue;
      for (const FittedParameter& p : r.parameters) {
        if (p.name == e.parameters[k] && !plausible_parameter(p, derivation, gap)) fine = false;
      }
    }
    if (fine) out.push_back(joint - 1);
  }
  return out;
}

}  // namespace dyncc::diagnose
