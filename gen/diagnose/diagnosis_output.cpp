#include "diagnose/diagnosis_output.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "diagnose/selection.hpp"

namespace dyncc::diagnose {
namespace {

// The held-out blocks that hold rows, as [first, last] analysis rows.
std::vector<std::pair<Eigen::Index, Eigen::Index>> heldout_blocks(const Folds& folds) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> out;
  for (int f = 0; f < kFolds; ++f) {
    if (folds.end_of(f) > folds.begin_of(f)) out.emplace_back(folds.begin_of(f), folds.end_of(f) - 1);
  }
  return out;
}

nlohmann::json vector_json(const Eigen::VectorXd& v) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i]);
  return out;
}

nlohmann::json parameters_json(const std::vector<FittedParameter>& fitted) {
  nlohmann::json parameters = nlohmann::json::array();
  for (const FittedParameter& p : fitted) {
    nlohmann::json one{{"name", p.name}, {"value", p.value}, {"error", p.error}};
    // An unbounded end is null (JSON has no infinity).
    auto end = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
    if (!std::isnan(p.low)) one["interval95"] = {end(p.low), end(p.high)};
    parameters.push_back(std::move(one));
  }
  return parameters;
}

std::string parameter_text(const FittedParameter& p) {
  const std::string interval = std::isnan(p.low) ? std::string() : fmt::format("  [{:.5g}, {:.5g}]", p.low, p.high);
  return fmt::format("{} = {:.5g} +- {:.2g}{}", p.name, p.value, p.error, interval);
}

nlohmann::json effect_json(const RankedEffect& r) {
  const nlohmann::json parameters = parameters_json(r.parameters);
  nlohmann::json out{{"effect", r.effect},
                     {"joints", r.joints},
                     {"parameters", parameters},
                     {"heldout_rms_before", vector_json(r.before)},
                     {"heldout_rms_after", vector_json(r.after)},
                     {"shrink", r.shrink},
                     {"shrink_interval", {r.shrink_low, r.shrink_high}},
                     {"accepted", r.accepted},
                     {"plausible", r.plausible}};
  if (!r.profile_name.empty()) out[r.profile_name] = r.profile;
  if (r.shrink_away_from_zero) out["shrink_away_from_zero_velocity"] = *r.shrink_away_from_zero;
  if (!r.alternatives.empty()) {
    nlohmann::json alternatives = nlohmann::json::array();
    for (const AlternativeFit& a : r.alternatives) {
      alternatives.push_back({{"effect", a.effect},
                              {"parameters", parameters_json(a.parameters)},
                              {"selection_shrink", a.selection_shrink},
                              {"named_selection_shrink", a.named_selection_shrink},
                              {"plausible", a.plausible}});
    }
    out["alternatives"] = std::move(alternatives);
  }
  return out;
}

std::string joints_text(const std::vector<int>& joints) {
  return joints.empty() ? std::string("-") : fmt::format("{}", fmt::join(joints, ","));
}

}  // namespace

nlohmann::json diagnosis_json(const Dataset& data, const Diagnosis& d) {
  nlohmann::json audit = nlohmann::json::array();
  for (std::size_t l = 0; l < data.audits.size(); ++l) {
    const Audit& a = data.audits[l];
    nlohmann::json joints = nlohmann::json::array();
    for (const JointAudit& j : a.joints) {
      joints.push_back(
          {{"quantum", j.quantum}, {"position_noise", j.position_noise}, {"torque_noise", j.torque_noise}});
    }
    audit.push_back({{"log", data.logs[l]},
                     {"rate_hz", a.rate},
                     {"jitter", a.jitter},
                     {"largest_gap", a.largest_gap},
                     {"samples", a.samples},
                     {"duration_s", a.duration},
                     {"joints", joints}});
  }
  nlohmann::json windows = nlohmann::json::array();
  for (const Window& w : d.gap.windows) {
    windows.push_back({{"log", data.logs[static_cast<std::size_t>(w.log)]},
                       {"start", w.start},
                       {"end", w.end},
                       {"rms_ratio", w.rms_ratio}});
  }
  nlohmann::json blocks = nlohmann::json::array();
  for (const auto& [first, last] : heldout_blocks(d.folds)) {
    blocks.push_back({{"log", data.logs[static_cast<std::size_t>(data.analysis_log[static_cast<std::size_t>(first)])]},
                      {"start", data.analysis_t[first]},
                      {"end", data.analysis_t[last]},
                      {"rows", last - first + 1}});
  }
  nlohmann::json regimes = nlohmann::json::object();
  for (const Regime& r : d.gap.regimes)
    regimes[r.name] = {{"rms", vector_json(r.rms)}, {"share", vector_json(r.share)}};
  nlohmann::json ranking = nlohmann::json::array();
  for (const RankedEffect& r : d.ranking) ranking.push_back(effect_json(r));
  nlohmann::json selected = nlohmann::json::array();
  for (const RankedEffect& r : d.selected) selected.push_back(effect_json(r));
  nlohmann::json verdict = {{"effect", d.verdict.effect},
                            {"joints", d.verdict.joints},
                            {"confidence", d.verdict.confidence}};
  if (const std::string why = why_not_named(d); !why.empty()) verdict["why"] = why;
  return {{"verdict", verdict},
          {"ranking", ranking},
          {"selected", selected},
          {"inertial_parameters", effect_json(d.within_model)},
          {"gap",
           {{"torque_rms", vector_json(d.gap.torque_rms)},
            {"heldout_rms", vector_json(d.gap.residual_rms)},
            {"percent_of_torque_rms", vector_json(d.gap.percent)},
            {"noise_floor", vector_json(d.gap.noise_floor)},
            {"sign_floor", vector_json(d.gap.sign_floor)},
            {"position_noise_floor", vector_json(d.gap.position_floor)},
            {"heldout_rms_after_selected", vector_json(d.final_after)},
            {"windows", windows},
            {"regimes", regimes}}},
          {"audit", audit},
          {"filter", {{"cutoff_hz", data.cutoff}, {"row_spacing_s", data.step}, {"rows", data.rows()}}},
          {"heldout_blocks", {{"even", d.folds == Folds::even(data.rows())}, {"blocks", blocks}}},
          {"torque", data.held_torque ? "held command" : "at its time stamp"}};
}

namespace {

// The flagged windows of the residual joined where they touch (within half a second, one log):
// the bursts of residual, each with its largest ratio to the usual residual.
std::vector<Window> bursts_of(std::vector<Window> windows) {
  constexpr double kJoined = 0.5;  // s
  std::sort(windows.begin(), windows.end(),
            [](const Window& a, const Window& b) { return std::pair(a.log, a.start) < std::pair(b.log, b.start); });
  std::vector<Window> bursts;
  for (const Window& w : windows) {
    if (!bursts.empty() && bursts.back().log == w.log && w.start - bursts.back().end < kJoined) {
      bursts.back().end = std::max(bursts.back().end, w.end);
      bursts.back().rms_ratio = std::max(bursts.back().rms_ratio, w.rms_ratio);
    } else {
      bursts.push_back(w);
    }
  }
  return bursts;
}

// Why a `none` verdict names nothing: no joint's gap is above its floors and material (set_verdict); and the first
// step's best candidate where it removes part of that gap significantly held out all the same (blind seed 853 case 9:
// a 10.4 g load beside an offset, each 5 % or less, below the friction sign's floor on every joint, while a load's
// columns removed 46 % [10, 83] %, its fit implausible).
std::string why_none(const Diagnosis& d) {
  std::string out = fmt::format(
      "no joint's held-out gap is both above its floors (the torque's noise, what the positions' noise moves "
      "the model by, the model's friction sign at reversals) and material ({:.1f} % of its torque RMS)",
      100 * kMaterial);
  if (d.ranking.empty()) return out;
  // Only a candidate that would have been an effect by what it removes (kAcceptShrink, its
  // interval above zero, and for a friction where the joints move too) but was not by what it
  // reads: one that removes less, or only how a friction turns over, is what such a gap is made of.
  const RankedEffect& best = d.ranking.front();
  const bool removes_enough = best.shrink >= kAcceptShrink && best.shrink_low > 0 &&
                              (!best.shrink_away_from_zero || *best.shrink_away_from_zero >= kAcceptShrink);
  if (!removes_enough) return out;
  out += fmt::format(
      "; yet {} removes {:.1f} % of it held out (95 % interval [{:.1f}, {:.1f}] %), not named because {}: an effect "
      "below the floors may be there",
      best.effect, 100 * best.shrink, 100 * best.shrink_low, 100 * best.shrink_high,
      best.plausible ? "it carries nothing material of its own on any joint" : "its fit is implausible");
  return out;
}

std::string why_unknown(const Diagnosis& d) {
  std::string out = "a gap above its floors that no effect of the library removes held out";
  if (!d.ranking.empty()) {
    const RankedEffect& best = d.ranking.front();
    out += fmt::format("; the best candidate, {}, removes {:.1f} % (95 % interval [{:.1f}, {:.1f}] %{})", best.effect,
                       100 * best.shrink, 100 * best.shrink_low, 100 * best.shrink_high,
                       best.plausible ? "" : ", an implausible fit");
  }
  // A burst is an event: ten times the usual residual or more, in one or two places only.
  constexpr double kEventRatio = 10.0;
  const std::vector<Window> bursts = bursts_of(d.gap.windows);
  const bool events =
      !bursts.empty() && bursts.size() <= 2 &&
      std::all_of(bursts.begin(), bursts.end(), [](const Window& w) { return w.rms_ratio >= kEventRatio; });
  if (events) {
    const bool one = bursts.size() == 1;
    std::vector<std::string> where;
    where.reserve(bursts.size());
    for (const Window& w : bursts) {
      where.push_back(
          fmt::format("{:.1f}-{:.1f} s of log {}, {:.0f}x the usual residual", w.start, w.end, w.log + 1, w.rms_ratio));
    }
    out += fmt::format(
        "; the residual's {} ({}) {} too rare to test on blocks held out in time: a fit on the blocks "
        "without {} has nothing to learn {} from; look at the log there (a touch, a knock, a glitch of "
        "a sensor)",
        one ? "burst" : "two bursts", fmt::join(where, "; "), one ? "is an event" : "are events", one ? "it" : "them",
        one ? "it" : "them");
  }
  return out;
}

}  // namespace

std::string why_not_named(const Diagnosis& d) {
  if (d.verdict.effect == "unknown") return why_unknown(d);
  if (d.verdict.effect == "none") return why_none(d);
  return {};
}

std::string diagnosis_text(const Dataset& data, const Diagnosis& d) {
  std::string out;
  for (std::size_t l = 0; l < data.audits.size(); ++l) {
    const Audit& a = data.audits[l];
    out += fmt::format("log {}: {} samples, {:.1f} s at {:.1f} Hz (jitter {:.1f} %, largest gap {:.1f}x)\n",
                       data.logs[l], a.samples, a.duration, a.rate, 100 * a.jitter, a.largest_gap);
    for (std::size_t j = 0; j < a.joints.size(); ++j) {
      const JointAudit& ja = a.joints[j];
      out += fmt::format("  joint {}: quantum {}, position noise {:.2e}, torque noise {:.2e}\n", j + 1,
                         ja.quantum > 0 ? fmt::format("{:.3e}", ja.quantum) : std::string("none"), ja.position_noise,
                         ja.torque_noise);
    }
  }
  if (data.held_torque) out += "  torque: a command held over each period (read at the period's middle)\n";
  out += fmt::format("\nheld-out gap of the nominal model (zero-phase filter {:.2f} Hz):\n", data.cutoff);
  for (Eigen::Index j = 0; j < data.n; ++j) {
    out += fmt::format(
        "  joint {}: {:.4g} N m RMS = {:.1f} % of the torque RMS (noise floor {:.2g}, positions' noise {:.2g}, "
        "friction sign at reversals {:.2g})\n",
        j + 1, d.gap.residual_rms[j], d.gap.percent[j], d.gap.noise_floor[j], d.gap.position_floor[j],
        d.gap.sign_floor[j]);
  }
  for (const Window& w : d.gap.windows) {
    out += fmt::format("  window {:.1f}-{:.1f} s of log {}: {:.1f}x the usual residual\n", w.start, w.end, w.log + 1,
                       w.rms_ratio);
  }
  if (d.folds != Folds::even(data.rows())) {
    out += "  held out in blocks moved so that no one block holds the residual's bursts:";
    for (const auto& [first, last] : heldout_blocks(d.folds)) {
      out += fmt::format(" {:.1f}-{:.1f} s", data.analysis_t[first], data.analysis_t[last]);
    }
    out += "\n";
  }
  out +=
      fmt::format("\nwithin the model (re-identified base parameters): shrink {:.1f} %\n", 100 * d.within_model.shrink);
  out += "\ncandidates (first step, held-out):\n";
  for (const RankedEffect& r : d.ranking) {
    const std::string away = r.shrink_away_from_zero
                                 ? fmt::format("  (away from zero velocity {:.1f} %)", 100 * *r.shrink_away_from_zero)
                                 : std::string();
    out += fmt::format("  {:<20} shrink {:6.1f} % [{:6.1f}, {:6.1f}]  joints {}{}{}\n", r.effect, 100 * r.shrink,
                       100 * r.shrink_low, 100 * r.shrink_high, joints_text(r.joints),
                       r.plausible ? "" : "  (implausible fit)", away);
  }
  out += d.selected.empty() ? "\nselected:\n  nothing\n"
                            : "\nselected (+- one standard error: the folds' spread and how far slow and fast "
                              "motion disagree; in brackets the 95 % interval, Student's t over the folds):\n";
  for (const RankedEffect& r : d.selected) {
    out += fmt::format("  {} on joints {}: shrink {:.1f} %{}\n", r.effect, joints_text(r.joints), 100 * r.shrink,
                       r.plausible ? "" : " (implausible as the joint fit reads it)");
    for (const FittedParameter& p : r.parameters) out += fmt::format("    {}\n", parameter_text(p));
    for (const AlternativeFit& a : r.alternatives) {
      out += fmt::format(
          "    or {} in its place (all selected effects then remove {:.1f} % held out, {:.1f} % as named; "
          "+- the folds' spread){}:\n",
          a.effect, 100 * a.selection_shrink, 100 * a.named_selection_shrink, a.plausible ? "" : ", implausible fit");
      for (const FittedParameter& p : a.parameters) out += fmt::format("      {}\n", parameter_text(p));
      if (a.parameters.empty()) out += "      (no joint where its own columns carry a material part)\n";
    }
  }
  out += fmt::format("\nverdict: {} (joints {}, confidence {:.2f})\n", d.verdict.effect, joints_text(d.verdict.joints),
                     d.verdict.confidence);
  if (const std::string why = why_not_named(d); !why.empty()) out += fmt::format("  why: {}\n", why);
  return out;
}

}  // namespace dyncc::diagnose
