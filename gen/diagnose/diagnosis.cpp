#include "diagnose/diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "diagnose/crossval.hpp"

namespace dyncc::diagnose {
namespace {

constexpr double kAcceptShrink = 0.05;  // an effect must remove 5 % of the weighted held-out error
constexpr double kMaterial = 0.015;     // ... and explain at least 1.5 % of some joint's torque RMS
constexpr double kJointShrink = 0.10;   // ... and 10 % on a joint to count as acting there
constexpr double kStudent95 = 2.776;    // t quantile, 4 degrees of freedom (5 folds)
constexpr double kNoiseFactor = 3.0;    // residual above this many noise floors is structure
constexpr int kMaxEffects = 3;
constexpr double kSupersetResidual = 0.05;  // span test: a column set that reproduces another's

struct Candidate {
  const Effect* effect = nullptr;
  CrossValidation cv;
  double shrink = 0, low = 0, high = 0;
  Eigen::VectorXd after;
  double explained = 0;   // sum over joints of (before^2 - after^2) / torque_rms^2
  double material = 0;    // largest per-joint explained RMS / torque RMS
  bool plausible = true;  // its fitted parameters make physical sense
};

// Weighted squared error over samples [begin, end): joints count relative to their torque.
double score(const Eigen::VectorXd& stacked, const Eigen::VectorXd& weight, Eigen::Index n, Eigen::Index begin,
             Eigen::Index end) {
  double sum = 0;
  for (Eigen::Index s = begin; s < end; ++s) {
    for (Eigen::Index j = 0; j < n; ++j) sum += weight[j] * weight[j] * stacked[s * n + j] * stacked[s * n + j];
  }
  return sum;
}

Candidate evaluate(const Effect& effect, const Eigen::MatrixXd& accepted, const Eigen::VectorXd& r0,
                   const Eigen::VectorXd& baseline, const Eigen::VectorXd& weight, Eigen::Index n) {
  Candidate c;
  c.effect = &effect;
  Eigen::MatrixXd e(r0.size(), accepted.cols() + effect.columns.cols());
  e << accepted, effect.columns;
  c.cv = cross_validate(r0, e, n, weight);
  const Eigen::Index samples = r0.size() / n;
  c.shrink = 1.0 - score(c.cv.heldout, weight, n, 0, samples) / score(baseline, weight, n, 0, samples);
  std::vector<double> folds;
  Eigen::Index begin = 0;
  for (const Eigen::Index end : c.cv.fold_end) {
    const double before = score(baseline, weight, n, begin, end);
    folds.push_back(before > 0 ? 1.0 - score(c.cv.heldout, weight, n, begin, end) / before : 0.0);
    begin = end;
  }
  const double mean = std::accumulate(folds.begin(), folds.end(), 0.0) / static_cast<double>(folds.size());
  double var = 0;
  for (const double f : folds) var += (f - mean) * (f - mean);
  const double half =
      kStudent95 * std::sqrt(var / static_cast<double>(folds.size() - 1) / static_cast<double>(folds.size()));
  c.low = c.shrink - half;
  c.high = c.shrink + half;
  c.after = joint_rms(c.cv.heldout, n);
  return c;
}

void measure(Candidate& c, const Eigen::VectorXd& before, const Eigen::VectorXd& torque_rms) {
  c.explained = 0;
  c.material = 0;
  for (Eigen::Index j = 0; j < before.size(); ++j) {
    const double gain = before[j] * before[j] - c.after[j] * c.after[j];
    const double scale = std::max(torque_rms[j], 1e-12);
    c.explained += gain / (scale * scale);
    c.material = std::max(c.material, std::sqrt(std::max(0.0, gain)) / scale);
  }
}

// Whether the columns of `inner` lie (nearly) in the span of `outer`: then `outer` is the same
// explanation with more freedom, not an alternative.
bool spans(const Eigen::MatrixXd& outer, const Eigen::MatrixXd& inner) {
  if (outer.cols() == 0) return false;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(outer);
  const Eigen::MatrixXd fit = outer * qr.solve(inner);
  return (inner - fit).norm() <= kSupersetResidual * inner.norm();
}

double physical(Reading reading, double theta) {
  switch (reading) {
    case Reading::reciprocal: return theta != 0 ? 1.0 / theta : 0.0;
    case Reading::gain: return 1.0 / (1.0 + theta);
    case Reading::as_is: break;
  }
  return theta;
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

// A contact's point of action in the link frame, from its force and moments (c = M / F), and the
// surface height of its profile point.
void add_contact_point(RankedEffect& r) {
  auto find = [&](const std::string& name) {
    for (const FittedParameter& p : r.parameters) {
      if (p.name == name) return p;
    }
    return FittedParameter{};
  };
  const FittedParameter force = find("force");
  if (force.value == 0) return;
  for (const char axis : {'x', 'y', 'z'}) {
    const FittedParameter moment = find(std::string("moment_") + axis);
    const double value = moment.value / force.value;
    const double error = std::hypot(moment.error, value * force.error) / std::abs(force.value);
    r.parameters.push_back({std::string("point_") + axis, value, error});
  }
  r.parameters.push_back({"surface_height", r.profile, 0.0});
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
  const bool per_joint = std::all_of(e.joint_of.begin(), e.joint_of.end(), [](int j) { return j >= 0; });
  if (per_joint) {
    r.joints = own_joints(c, offset, torque_rms);
  } else {
    for (Eigen::Index j = 0; j < before.size(); ++j) {
      if (before[j] > 0 && 1.0 - c.after[j] / before[j] >= kJointShrink) r.joints.push_back(static_cast<int>(j) + 1);
    }
  }
  for (Eigen::Index k = 0; k < e.columns.cols(); ++k) {
    const int joint = e.joint_of[static_cast<std::size_t>(k)];
    if (joint >= 0 && std::find(r.joints.begin(), r.joints.end(), joint + 1) == r.joints.end()) continue;
    const double theta = c.cv.theta[offset + k], error = c.cv.theta_error[offset + k];
    const double value = physical(e.reading[static_cast<std::size_t>(k)], theta);
    // First-order propagation of the fold spread through the reading.
    const double derivative =
        std::abs(physical(e.reading[static_cast<std::size_t>(k)], theta + 1e-6 * (1 + std::abs(theta))) - value) /
        (1e-6 * (1 + std::abs(theta)));
    r.parameters.push_back({e.parameters[static_cast<std::size_t>(k)], value, derivative * error});
  }
  if (e.family == "contact") add_contact_point(r);
  return r;
}

// Physical sense of a fit: friction coefficients, a static friction excess, a payload's mass and
// a contact's force and stiffness (a surface only pushes) are not negative (beyond twice their
// error). A fit that needs them negative is the effect's columns soaking up something else (e.g.
// a Stribeck "excess" below Coulomb sharpening a mis-estimated sign near zero velocity).
bool plausible(const RankedEffect& r) {
  for (const FittedParameter& p : r.parameters) {
    const bool non_negative = p.name.rfind("fc", 0) == 0 || p.name.rfind("fv", 0) == 0 || p.name.rfind("fs", 0) == 0 ||
                              p.name == "mass" || p.name.rfind("ia", 0) == 0 || p.name == "force" ||
                              p.name == "stiffness";
    if (non_negative && p.value < -2.0 * p.error) return false;
  }
  return true;
}

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

Gap locate(const Dataset& d, const Eigen::VectorXd& r) {
  Gap g;
  const Eigen::Index n = d.n, samples = d.rows();
  g.residual_rms = joint_rms(r, n);
  g.torque_rms = (d.analysis_tau.array().square().colwise().mean()).sqrt().transpose();
  g.percent = 100.0 * g.residual_rms.cwiseQuotient(g.torque_rms.cwiseMax(1e-12));
  g.noise_floor = Eigen::VectorXd::Zero(n);
  for (std::size_t l = 0; l < d.audits.size(); ++l) {
    const Audit& a = d.audits[l];
    const double band = std::sqrt(std::min(1.0, 2.0 * d.cutoff / a.rate));
    for (Eigen::Index j = 0; j < n; ++j) {
      g.noise_floor[j] = std::max(g.noise_floor[j], a.joints[static_cast<std::size_t>(j)].torque_noise * band);
    }
  }
  // Time windows of about 2 s (at least 10 rows), flagged at twice the median window RMS.
  const auto length = std::max<Eigen::Index>(10, static_cast<Eigen::Index>(2.0 / d.step));
  std::vector<std::pair<Eigen::Index, double>> windows;
  for (Eigen::Index begin = 0; begin + length <= samples; begin += length) {
    double sum = 0;
    for (Eigen::Index s = begin; s < begin + length; ++s) {
      for (Eigen::Index j = 0; j < n; ++j) sum += std::pow(r[s * n + j] / std::max(g.torque_rms[j], 1e-12), 2);
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
      sum[static_cast<std::size_t>(k)] += r[s * n + j] * r[s * n + j];
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

}  // namespace

Diagnosis diagnose(const Dataset& d, const pipeline::Derivation& derivation) {
  Diagnosis out;
  const Eigen::Index n = d.n;
  const Eigen::VectorXd r0 = d.residual;
  out.gap = locate(d, r0);
  const Eigen::VectorXd weight =
      out.gap.torque_rms.cwiseMax(1e-3 * out.gap.torque_rms.maxCoeff() + 1e-12).cwiseInverse();
  const std::vector<Effect> effects = candidate_effects(d, derivation);

  Eigen::MatrixXd accepted(r0.size(), 0);
  Eigen::VectorXd baseline = r0;  // held-out residual of the model so far
  std::vector<std::string> taken;
  for (int step = 0; step < kMaxEffects; ++step) {
    // Every remaining candidate on top of what is accepted; the best profile point per effect.
    std::map<std::string, Candidate> best;
    const Eigen::VectorXd before = joint_rms(baseline, n);
    for (const Effect& e : effects) {
      if (std::find(taken.begin(), taken.end(), e.family) != taken.end()) continue;
      Candidate c = evaluate(e, accepted, r0, baseline, weight, n);
      c.plausible = plausible(describe(c, before, accepted.cols(), out.gap.torque_rms));
      auto it = best.find(e.name);
      const bool better = it == best.end() || (c.plausible && !it->second.plausible) ||
                          (c.plausible == it->second.plausible && c.shrink > it->second.shrink);
      if (better) best[e.name] = std::move(c);
    }
    if (best.empty()) break;
    std::vector<const Candidate*> order;
    order.reserve(best.size());
    for (const auto& [name, c] : best) order.push_back(&c);
    std::sort(order.begin(), order.end(), [](const Candidate* a, const Candidate* b) { return a->shrink > b->shrink; });
    for (auto& [name, c] : best) measure(c, before, out.gap.torque_rms);
    if (step == 0) {
      for (const Candidate* c : order) {
        out.ranking.push_back(describe(*c, before, accepted.cols(), out.gap.torque_rms));
        out.ranking.back().plausible = c->plausible;
      }
      out.within_model = describe(best.at("inertial_parameters"), before, 0, out.gap.torque_rms);
    }
    // Parsimony among equal explanations: two candidates are equal when what one explains beyond
    // the other is immaterial (below kMaterial of the torque RMS); of equals, the fewest columns
    // win, and equals whose columns do not contain the chosen ones are alternatives ("A or B").
    std::stable_partition(order.begin(), order.end(), [](const Candidate* c) { return c->plausible; });
    const Candidate* top = order.front();
    auto equal = [&](const Candidate* c) {
      return c->explained >= top->explained - kMaterial * kMaterial ||
             c->shrink >= top->shrink - 0.5 * (top->high - top->low);
    };
    const Candidate* chosen = top;
    for (const Candidate* c : order) {
      if (c->plausible && equal(c) && c->effect->columns.cols() < chosen->effect->columns.cols()) chosen = c;
    }
    if (!(chosen->plausible && chosen->shrink >= kAcceptShrink && chosen->low > 0.0 && chosen->material >= kMaterial)) {
      break;
    }
    RankedEffect r = describe(*chosen, before, accepted.cols(), out.gap.torque_rms);
    if (r.joints.empty()) break;  // explains nothing material on any joint of its own
    r.accepted = true;
    for (const Candidate* c : order) {
      if (c == chosen || !c->plausible || !equal(c)) continue;
      if (spans(c->effect->columns, chosen->effect->columns)) continue;  // a superset: the same explanation
      if (c->effect->columns.cols() > 2 * chosen->effect->columns.cols()) continue;
      r.effect += " or " + c->effect->name;
    }
    out.selected.push_back(r);
    taken.push_back(chosen->effect->family);
    if (chosen->effect->family == "stribeck_friction") taken.emplace_back("coulomb_friction");
    Eigen::MatrixXd grown(r0.size(), accepted.cols() + chosen->effect->columns.cols());
    grown << accepted, chosen->effect->columns;
    accepted = grown;
    baseline = chosen->cv.heldout;
  }
  out.final_after = joint_rms(baseline, n);

  if (out.selected.empty()) {
    // Structure left: a joint whose gap is material and above the noise floor.
    auto structured_on = [&](Eigen::Index j) {
      return out.gap.residual_rms[j] > kNoiseFactor * out.gap.noise_floor[j] &&
             out.gap.residual_rms[j] > kMaterial * out.gap.torque_rms[j];
    };
    for (Eigen::Index j = 0; j < n; ++j) {
      if (structured_on(j)) out.verdict.joints.push_back(static_cast<int>(j) + 1);
    }
    const bool structured = !out.verdict.joints.empty();
    out.verdict.effect = structured ? "unknown" : "none";
    out.verdict.confidence = structured ? 0.5 : 0.9;
  } else {
    const RankedEffect& first = out.selected.front();
    out.verdict.effect = first.effect;
    out.verdict.joints = first.joints;
    const double se = std::max(1e-9, (first.shrink_high - first.shrink_low) / (2 * kStudent95));
    out.verdict.confidence = normal_cdf(first.shrink / se);
  }
  return out;
}

}  // namespace dyncc::diagnose
