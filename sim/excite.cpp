#include "excite.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "dyncc/runtime/position_estimator.hpp"
#include "dyncc/runtime/slotine_li_controller.hpp"
#include "excite_reference.hpp"
#include "joint_sensors.hpp"
#include "plant.hpp"

namespace dyncc::sim {
namespace {

using Controller = runtime::SlotineLiController<Kraft, double>;
using Estimator = runtime::PositionEstimator<kDof, double>;

void check(const ExciteSettings& s) {
  if (!(s.rate >= 81.0 && s.rate <= 1000.0)) throw std::invalid_argument("excite: the rate must be 81..1000 Hz");
  if (!(s.duration > 0.0)) throw std::invalid_argument("excite: the duration must be positive");
  if (!(s.quantum >= 0.0) || !(s.noise >= 0.0)) throw std::invalid_argument("excite: quantum and noise must be >= 0");
}

PlantSettings plant_settings(const ExciteSettings& s, const ExciteReference& reference) {
  PlantSettings p;
  // Whole integration steps per control period: every torque change falls on a step.
  p.rate = s.rate * std::ceil(s.plant_rate / s.rate - 1e-9);
  p.payload.mass = s.effects.payload;
  p.payload.position_in_forearm = s.effects.payload_position;
  p.effects = s.effects.joints;
  const ContactEffect& c = s.effects.contact;
  p.table.present = c.present;
  p.table.height = c.height ? *c.height : (c.depth ? reference.low_hook + *c.depth : reference.table_height);
  p.table.friction = c.friction;
  p.table.stiffness = c.stiffness.value_or(p.table.stiffness);
  p.table.damping = c.damping.value_or(p.table.damping);
  return p;
}

std::unique_ptr<Plant> make_plant(const ExciteSettings& s, const PlantSettings& p) {
  if (s.plant == PlantKind::mujoco) return make_mujoco_plant(p, s.mjcf);
  return make_rigid_plant(p);
}

// Starts the arm at rest where its sensors read `target`: the link moved until the sensor side
// (behind a transmission's deflection under the arm's weight) plus the offset is there.
void start_at(Plant& plant, const Joints& target, const Joints& offset) {
  Joints link{};
  for (int k = 0; k < kDof; ++k) link[k] = target[k] - offset[k];
  for (int iteration = 0; iteration < 8; ++iteration) {
    plant.reset(link);
    const Joints seen = plant.sensor_q();
    for (int k = 0; k < kDof; ++k) link[k] -= seen[k] + offset[k] - target[k];
  }
  plant.reset(link);
}

Controller::Settings controller_settings(const ExciteSettings& s) {
  Controller::Settings c;
  c.lambda = s.lambda;
  c.feedback = runtime::Feedback::lambda_H;  // K_D = lambda H^: PD gains lambda^2, 2 lambda on H^
  c.period = 1.0 / s.rate;
  return c;
}

double rms(const std::vector<double>& v) {
  double sum = 0;
  for (const double x : v) sum += x * x;
  return v.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(v.size()));
}

}  // namespace

ExciteRun excite(const ExciteSettings& settings, const std::function<void(double)>& progress) {
  check(settings);
  const HiddenEffects& e = settings.effects;
  require_playable(e, settings.plant, "the effects");
  const ExciteReference reference = excite_reference(settings);
  const PlantSettings ps = plant_settings(settings, reference);
  std::unique_ptr<Plant> plant = make_plant(settings, ps);
  start_at(*plant, reference.at(0.0).q, e.position_offset);

  const double period = 1.0 / settings.rate;
  const auto substeps = static_cast<int>(std::lround(ps.rate / settings.rate));
  const double sub = period / substeps;
  JointSensors sensors(e.sensor_delay, e.position_offset,
                       Potentiometers(settings.quantum, settings.noise, settings.seed));
  sensors.record(0.0, plant->sensor_q());
  Estimator estimator(period, settings.estimator_bandwidth);
  Parameters nominal{};
  std::copy_n(Kraft::nominal_parameters, kParameters, nominal.begin());
  Controller controller(controller_settings(settings), nominal);
  controller.set_adaptation(false);

  ExciteRun run;
  run.settings = settings;
  run.table_height = ps.table.height;
  run.low_hook = reference.low_hook;
  const auto rows = static_cast<long>(std::lround(settings.duration * settings.rate));
  run.samples.reserve(static_cast<std::size_t>(rows));
  for (long i = 0; i < rows; ++i) {
    const double t = static_cast<double>(i) * period;
    const bool on = e.payload > 0 && t >= reference.attach && (reference.release < 0 || t < reference.release);
    if (on != plant->payload_attached()) plant->set_payload_attached(on);

    const Joints measured = sensors.read(t);
    estimator.update(measured);
    const TrajectoryPoint d = reference.at(t);
    const auto step =
        controller.step(estimator.position(), estimator.velocity(), d.q, d.qd, d.qdd);  // adaptation is off
    ExciteSample sample;
    sample.t = t;
    sample.measured = measured;
    for (int k = 0; k < kDof; ++k)
      sample.tau[k] = std::clamp(step.tau[k], -settings.torque_limit[k], settings.torque_limit[k]);
    sample.desired = d.q;
    sample.link = plant->q();
    sample.sensor = plant->sensor_q();
    sample.payload = plant->payload_attached();

    // The actuators give gain times the command (torque_gain), held over the period.
    Joints applied{};
    for (int k = 0; k < kDof; ++k) applied[k] = e.torque_gain[k] * sample.tau[k];
    for (int s = 1; s <= substeps; ++s) {
      plant->advance(applied, sub);
      sensors.record(t + s * sub, plant->sensor_q());
      const ContactState contact = plant->contact();
      sample.contact = sample.contact || contact.active;
      sample.contact_force += contact.normal_force / substeps;
    }
    run.samples.push_back(sample);
    if (progress) progress(static_cast<double>(i + 1) / static_cast<double>(rows));
  }
  return run;
}

void write_excite_log(const ExciteRun& run, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write the log");
  out << "t,q1,q2,q3,tau1,tau2,tau3\n";
  out.precision(10);
  for (const ExciteSample& s : run.samples) {
    out << s.t;
    for (const double q : s.measured) out << ',' << q + 0.0;  // + 0.0: a reading of -0 is written as 0
    for (const double tau : s.tau) out << ',' << tau;
    out << '\n';
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write the log");
}

std::string excite_summary(const ExciteRun& run) {
  const ExciteSettings& s = run.settings;
  std::string effects;
  for (const HiddenEffects::Listed& l : s.effects.listed) effects += (effects.empty() ? "" : ", ") + l.effect;
  std::array<std::vector<double>, kDof> error, torque;
  std::size_t contact = 0;
  double force = 0;
  for (const ExciteSample& x : run.samples) {
    for (int k = 0; k < kDof; ++k) {
      error[k].push_back(x.measured[k] - x.desired[k]);
      torque[k].push_back(x.tau[k]);
    }
    contact += x.contact ? 1 : 0;
    force = std::max(force, x.contact_force);
  }
  std::string out =
      fmt::format("{} rows at {} Hz ({} s), plant {}, trajectory {}, effects: {}\n", run.samples.size(), s.rate,
                  s.duration, s.plant == PlantKind::mujoco ? "mujoco" : "dyncc",
                  s.trajectory == Trajectory::teleop ? "teleop" : "fourier", effects.empty() ? "none" : effects);
  out += "joint   tracking RMS (rad)   torque RMS (N m)\n";
  for (int k = 0; k < kDof; ++k)
    out += fmt::format("q{}      {:>18.5f}   {:>16.4f}\n", k + 1, rms(error[k]), rms(torque[k]));
  if (s.effects.contact.present) {
    out += fmt::format(
        "table at z = {:.4f} m, {:.1f} mm above the reference's low hook point: the hook touches it in {:.1f} % of "
        "the rows (largest mean force over a period {:.2f} N)\n",
        run.table_height, 1e3 * (run.table_height - run.low_hook),
        100.0 * static_cast<double>(contact) / static_cast<double>(run.samples.size()), force);
  }
  if (s.effects.payload > 0) {
    double on = -1, off = -1;
    for (const ExciteSample& x : run.samples) {
      if (x.payload && on < 0) on = x.t;
      if (!x.payload && on >= 0 && off < 0) off = x.t;
    }
    if (on < 0) {
      out += "the payload is never on the hook\n";
    } else {
      out += fmt::format("payload {} kg on the hook from {:.3f} s to {}\n", s.effects.payload, on,
                         off < 0 ? std::string("the end") : fmt::format("{:.3f} s", off));
    }
  }
  return out;
}

}  // namespace dyncc::sim
