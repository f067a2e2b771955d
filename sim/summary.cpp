#include "summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "operator.hpp"

namespace dyncc::sim {
namespace {

constexpr double kSettleWindow = 1.0;  // s: trailing window of the settling test
constexpr double kSettleFactor = 1.5;  // settled when the trailing RMS is within this of the unloaded level

const Sample* at_time(const Run& run, double t) {
  for (const Sample& s : run.samples) {
    if (s.t >= t) return &s;
  }
  return run.samples.empty() ? nullptr : &run.samples.back();
}

}  // namespace

double rms(const Run& run, int joint, double from, double to) {
  double sum = 0;
  int count = 0;
  for (const Sample& s : run.samples) {
    if (s.t < from || s.t >= to) continue;
    sum += s.s[static_cast<std::size_t>(joint)] * s.s[static_cast<std::size_t>(joint)];
    ++count;
  }
  return count > 0 ? std::sqrt(sum / count) : std::nan("");
}

Summary summarize(const Run& run) {
  const TaskScript script = TaskScript::paper();
  Summary out;
  out.scenario = run.settings.name;
  out.plant = run.settings.plant == PlantKind::mujoco ? "mujoco" : "dyncc";
  out.adaptation = run.settings.adaptation;
  out.payload = run.settings.payload;
  if (run.samples.empty()) return out;
  const double end = run.samples.back().t + 1e-9;
  for (const Sample& s : run.samples) {
    if (s.contact) {
      out.first_contact = s.t;
      break;
    }
  }
  // Lift-off: after the pick-up, the first time the hook has been off the table for 0.25 s.
  if (run.attach_time >= 0) {
    double clear_since = -1;
    for (const Sample& s : run.samples) {
      if (s.t < run.attach_time) continue;
      if (s.contact) {
        clear_since = -1;
        continue;
      }
      if (clear_since < 0) clear_since = s.t;
      if (s.t - clear_since >= 0.25) {
        out.lift_off = clear_since;
        break;
      }
    }
  }
  const double reach_end = out.first_contact > 0 ? out.first_contact : script.pick_up;
  const double hold_start = std::max(out.lift_off, script.lift_end) + 1.0;
  const double after_start = (run.release_time > 0 ? run.release_time : script.put_down + 3.0) + 1.0;
  for (int k = 0; k < kDof; ++k) {
    out.rms_before[k] = rms(run, k, 1.0, reach_end);
    out.rms_holding[k] = rms(run, k, hold_start, script.put_down);
    out.rms_after[k] = rms(run, k, after_start, end);
  }
  if (out.lift_off > 0) out.lift_delay = out.lift_off - script.pick_up;

  // Settling after lift-off: the trailing RMS of (s2, s3) back within kSettleFactor of its level
  // before the reach ended, searched until the first sweep has gone on for a while.
  if (out.lift_off > 0) {
    const double level = std::hypot(out.rms_before[1], out.rms_before[2]);
    const auto& seg = script.segments();
    double search_end = end;
    for (const auto& s : seg) {
      if (s.sweep_joint >= 0) {
        search_end = s.start;
        break;
      }
    }
    constexpr double kStep = 0.05;  // s between settling tests
    const int steps = static_cast<int>((search_end - out.lift_off - kSettleWindow) / kStep);
    for (int i = 0; i <= steps; ++i) {
      const double t = out.lift_off + kSettleWindow + i * kStep;
      const double window = std::hypot(rms(run, 1, t - kSettleWindow, t), rms(run, 2, t - kSettleWindow, t));
      if (window <= kSettleFactor * level) {
        out.reconvergence = t - kSettleWindow - out.lift_off;
        break;
      }
    }
  }
  // Drift of the first moments (the gravity parameters M*) over the press: from the first contact
  // to the operator's lift start, relative to their true values.
  if (out.first_contact > 0) {
    const Parameters& a = at_time(run, out.first_contact)->estimate;
    const Parameters& b = at_time(run, script.pick_up)->estimate;
    const Parameters truth = true_parameters({});
    double change = 0, size = 0;
    for (int k = 0; k < kParameters; ++k) {
      if (Kraft::parameter_names[k][0] != 'M') continue;
      change += (b[k] - a[k]) * (b[k] - a[k]);
      size += truth[k] * truth[k];
    }
    out.press_drift = std::sqrt(change / size);
  }
  out.final_estimate = run.samples.back().estimate;
  return out;
}

std::string summary_table(const std::vector<Summary>& rows) {
  std::string out = fmt::format("{:<17} {:<6} {:<8} {:>5} | {:^26} | {:^26} | {:^26} | {:>7} {:>7} {:>9}\n", "scenario",
                                "plant", "mode", "kg", "RMS s1 s2 s3 before", "RMS s1 s2 s3 holding",
                                "RMS s1 s2 s3 after", "lift", "settle", "drift");
  out += fmt::format("{:<17} {:<6} {:<8} {:>5} | {:^26} | {:^26} | {:^26} | {:>7} {:>7} {:>9}\n", "", "", "", "",
                     "(rad/s)", "(rad/s)", "(rad/s)", "delay s", "s", "in press");
  auto triple = [](const Joints& v) { return fmt::format("{:8.4f} {:8.4f} {:8.4f}", v[0], v[1], v[2]); };
  auto seconds = [](double v) { return v < 0 ? std::string("never") : fmt::format("{:.2f}", v); };
  for (const Summary& s : rows) {
    out += fmt::format("{:<17} {:<6} {:<8} {:>5.2f} | {} | {} | {} | {:>7} {:>7} {:>8.1f}%\n", s.scenario, s.plant,
                       s.adaptation ? "adaptive" : "fixed", s.payload, triple(s.rms_before), triple(s.rms_holding),
                       triple(s.rms_after), seconds(s.lift_delay), seconds(s.reconvergence), 100.0 * s.press_drift);
  }
  return out;
}

std::string estimate_table(const std::vector<Summary>& rows) {
  std::string out = fmt::format("{:<6} {:>10}", "p^", "initial");
  for (const Summary& s : rows)
    out += fmt::format(" {:>14}", fmt::format("{}/{}", s.scenario.substr(6), s.plant.substr(0, 2)));
  out += "\n";
  for (int b = 0; b < kParameters; ++b) {
    out += fmt::format("{:<6} {:>10.4f}", Kraft::parameter_names[b], Kraft::initial_estimate[b]);
    for (const Summary& s : rows) out += fmt::format(" {:>14.4f}", s.final_estimate[b]);
    out += "\n";
  }
  return out;
}

}  // namespace dyncc::sim
