#include "excite_reference.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "fourier_excitation.hpp"
#include "joint_spline.hpp"
#include "plant.hpp"

namespace dyncc::sim {
namespace {

double lowest_hook(const std::function<TrajectoryPoint(double)>& at, double from, double to) {
  double lowest = 1e9;
  const auto first = static_cast<long>(std::ceil(from * 100)), last = static_cast<long>(to * 100);
  for (long i = first; i <= last; ++i) {  // every 10 ms: far finer than the swings
    lowest = std::min(lowest, forearm_point(at(static_cast<double>(i) / 100).q, kHookInForearm)[2]);
  }
  return lowest;
}

// The height the Fourier run's hook reaches in kTouchedPeriods of its base periods at least: the
// kTouchedPeriods-th lowest of the periods' lowest points (all of the run's lowest where it is
// shorter). The joints' frequencies differ by a few per cent, so the hook's path does not repeat:
// a table just above its single lowest point was touched in one burst of a 60 s log (10 of the 14
// wrong verdicts on the bench's Fourier contacts, blind seeds up to 647), which no test on held-out
// data can tell from an outlier.
double low_fourier_hook(const std::function<TrajectoryPoint(double)>& at, double duration) {
  const double period = 1.0 / FourierExcitation::kBaseFrequency;
  std::vector<double> lows;
  for (double start = 0; start + period <= duration + 1e-9; start += period) {
    lows.push_back(lowest_hook(at, start, start + period));
  }
  if (static_cast<int>(lows.size()) < kTouchedPeriods) return lowest_hook(at, 0, duration);
  std::nth_element(lows.begin(), lows.begin() + (kTouchedPeriods - 1), lows.end());
  return lows[kTouchedPeriods - 1];
}

}  // namespace

ExciteReference excite_reference(const ExciteSettings& settings) {
  ExciteReference out;
  if (settings.trajectory == Trajectory::fourier) {
    const FourierExcitation fourier(settings.seed, settings.excitation_scale);
    out.at = [fourier](double t) { return fourier.at(t); };
    out.low_hook = low_fourier_hook(out.at, settings.duration);
    out.table_height = out.low_hook + kDefaultTableDepth;
    return out;
  }
  // The operator's run: the scenario with this payload (its master feels the payload through the
  // force reflection, so a loaded master moves differently), simulated no longer than needed.
  const double payload = settings.effects.payload;
  ScenarioSettings task = scenario_settings(payload > 0 ? "paper-0.5kg" : "paper-unloaded");
  task.payload = payload;
  task.seed = settings.seed;
  task.duration = std::min(settings.duration, TaskScript::paper().duration());
  const Run run = simulate(task);
  std::vector<double> t;
  std::vector<Joints> q;
  for (const Sample& s : run.samples) {
    t.push_back(s.t);
    q.push_back(s.master);
  }
  const JointSpline master(std::move(t), std::move(q));
  out.at = [master](double time) { return master.at(time); };
  out.attach = run.attach_time >= 0 ? run.attach_time : settings.duration;  // never picked up: never on
  out.release = run.release_time;
  out.low_hook = lowest_hook(out.at, 0, settings.duration);
  out.table_height = Table{}.height;  // the task presses on the paper's table
  return out;
}

}  // namespace dyncc::sim
