#include "excite_reference.hpp"

#include <algorithm>
#include <vector>

#include "fourier_excitation.hpp"
#include "joint_spline.hpp"
#include "plant.hpp"

namespace dyncc::sim {
namespace {

double lowest_hook(const std::function<TrajectoryPoint(double)>& at, double duration) {
  double lowest = 1e9;
  const auto samples = static_cast<long>(duration * 100);  // every 10 ms: far finer than the swings
  for (long i = 0; i <= samples; ++i) {
    lowest = std::min(lowest, forearm_point(at(static_cast<double>(i) / 100).q, kHookInForearm)[2]);
  }
  return lowest;
}

}  // namespace

ExciteReference excite_reference(const ExciteSettings& settings) {
  ExciteReference out;
  if (settings.trajectory == Trajectory::fourier) {
    const FourierExcitation fourier(settings.seed, settings.excitation_scale);
    out.at = [fourier](double t) { return fourier.at(t); };
    out.lowest_hook = lowest_hook(out.at, settings.duration);
    out.table_height = out.lowest_hook + kDefaultTableDepth;
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
  out.lowest_hook = lowest_hook(out.at, settings.duration);
  out.table_height = Table{}.height;  // the task presses on the paper's table
  return out;
}

}  // namespace dyncc::sim
