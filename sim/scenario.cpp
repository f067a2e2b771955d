#include "scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "dyncc/runtime/position_estimator.hpp"
#include "dyncc/runtime/slotine_li_controller.hpp"
#include "operator.hpp"
#include "plant.hpp"
#include "potentiometers.hpp"

namespace dyncc::sim {
namespace {

namespace gen = dyncc::generated::kraft_right;
using Controller = runtime::SlotineLiController<Kraft, double>;
using Estimator = runtime::PositionEstimator<kDof, double>;

// The operator's hand on the master: it carries the master's weight and pulls it towards the
// script like a spring-damper (stiff enough to follow, soft enough to feel the reflected force).
constexpr Joints kHandStiffness{15.0, 25.0, 25.0};  // N m / rad
constexpr Joints kHandDamping{2.0, 4.0, 4.0};       // N m s / rad
constexpr int kHandUpdatesPerPeriod = 10;           // the hand reacts faster than the 81 Hz loop

// Adaptation gains Gamma^-1 by what a parameter multiplies in Y: gravity (first moments M*),
// inertia (second moments), friction. Chosen so the loaded arm re-converges in a few seconds at
// lambda = pi rad/s without exciting the 81 Hz loop.
double adaptation_gain(const char* name) {
  if (name[0] == 'M') return 0.03;
  if (name[0] == 'F') return 0.02;
  return 0.01;
}

Controller::Settings controller_settings(const ScenarioSettings& s) {
  Controller::Settings c;
  c.lambda = 3.14159265358979;  // the paper's 1/2 Hz bandwidth (ERRATA 8)
  c.feedback = runtime::Feedback::lambda_H;
  c.period = 1.0 / s.control_rate;
  c.simplified = s.simplified;
  c.mass_matrix_margin = 1e-3;
  // A generous box around the initial estimate (a 1 kg payload moves the first moments by less
  // than half of it), friction never negative: what keeps noise and contact from running away.
  c.bounded = true;
  for (int b = 0; b < kParameters; ++b) {
    const char* name = Kraft::parameter_names[b];
    const double p0 = Kraft::initial_estimate[b], span = std::fabs(p0) + 0.5;
    c.gamma_inverse[b] = adaptation_gain(name);
    c.lower[b] = name[0] == 'F' ? 0.0 : p0 - span;
    c.upper[b] = p0 + span;
  }
  return c;
}

Joints clamp(const Joints& tau, const Joints& limit) {
  Joints out{};
  for (int k = 0; k < kDof; ++k) out[k] = std::clamp(tau[k], -limit[k], limit[k]);
  return out;
}

std::unique_ptr<Plant> make_plant(const ScenarioSettings& s, const PlantSettings& p) {
  if (s.plant == PlantKind::mujoco) return make_mujoco_plant(p, s.mjcf);
  return make_rigid_plant(p);
}

}  // namespace

std::vector<std::string> scenario_names() {
  return {"paper-0.5kg", "paper-1kg", "paper-simplified", "paper-contact", "paper-unloaded"};
}

ScenarioSettings scenario_settings(const std::string& name) {
  ScenarioSettings s;
  s.name = name;
  if (name == "paper-0.5kg") {
    s.payload = 0.5;
  } else if (name == "paper-1kg") {
    s.payload = 1.0;
  } else if (name == "paper-simplified") {
    s.payload = 0.5;
    s.simplified = true;
  } else if (name == "paper-contact") {
    s.payload = 0.5;
    s.freeze_in_contact = true;
  } else if (name == "paper-unloaded") {
    s.payload = 0.0;  // the same task without a payload: the paper's reference run
  } else {
    std::string known;
    for (const auto& n : scenario_names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown scenario '" + name + "' (expected one of " + known + ")");
  }
  return s;
}

Run simulate(const ScenarioSettings& settings, const std::function<void(double)>& progress) {
  const TaskScript script = TaskScript::paper();
  std::optional<RecordedMaster> recorded;
  if (!settings.master_csv.empty()) recorded = RecordedMaster::load(settings.master_csv);
  const double duration =
      settings.duration > 0 ? settings.duration : (recorded ? recorded->duration() : script.duration());

  PlantSettings slave_settings;
  slave_settings.payload.mass = settings.payload;
  slave_settings.rate = settings.plant_rate;
  std::unique_ptr<Plant> slave = make_plant(settings, slave_settings);
  PlantSettings master_settings;
  master_settings.table.present = false;
  master_settings.rate = settings.plant_rate;
  std::unique_ptr<Plant> master = make_rigid_plant(master_settings);  // the left arm, in the operator's hand
  const Joints start = recorded ? recorded->at(0.0).q : script.at(0.0).q;
  slave->reset(start);
  master->reset(start);

  Parameters initial{};
  for (int b = 0; b < kParameters; ++b) initial[b] = Kraft::initial_estimate[b];
  Controller controller(controller_settings(settings), initial);
  const double period = 1.0 / settings.control_rate;
  Estimator slave_estimator(period, settings.estimator_bandwidth),
      master_estimator(period, settings.estimator_bandwidth);
  Potentiometers slave_pots(settings.quantum, settings.noise, settings.seed);
  Potentiometers master_pots(settings.quantum, settings.noise, settings.seed + 1000);
  const Parameters master_parameters = true_parameters({});

  Run run;
  run.settings = settings;
  const auto periods = static_cast<long>(std::floor(duration * settings.control_rate));
  run.samples.reserve(static_cast<std::size_t>(periods) + 1);
  double resting = 0;  // s the payload has been on the table since the put-down began
  for (long i = 0; i <= periods; ++i) {
    const double t = static_cast<double>(i) * period;
    // Sensors, then the estimators (the only source of velocity and acceleration).
    slave_estimator.update(slave_pots.read(slave->q()));
    master_estimator.update(master_pots.read(master->q()));
    const ContactState contact = slave->contact();

    // Payload events: taken on the hook as the lift starts (the hook is on it then), left on the
    // table once it has rested there (in total, contact may chatter) after the put-down began.
    if (settings.payload > 0 && run.attach_time < 0 && t >= script.pick_up) {
      const double height = forearm_point(slave->q(), kHookInForearm)[2];
      if (height < slave_settings.table.height + 0.01) {
        slave->set_payload_attached(true);
        run.attach_time = t;
      }
    }
    if (t >= script.put_down && contact.active) resting += period;
    if (slave->payload_attached() && resting >= script.release_after) {
      slave->set_payload_attached(false);
      run.release_time = t;
    }

    controller.set_adaptation(settings.adaptation && !(settings.freeze_in_contact && contact.active));
    const auto step =
        controller.step(slave_estimator.position(), slave_estimator.velocity(), master_estimator.position(),
                        master_estimator.velocity(), master_estimator.acceleration());
    const Joints tau = clamp(step.tau, settings.torque_limit);

    Sample sample;
    sample.t = t;
    sample.master = master->q();
    sample.slave = slave->q();
    sample.s = step.eps;
    sample.tau = tau;
    sample.estimate = controller.estimate();
    sample.contact = contact.active;
    sample.contact_force = contact.normal_force;
    sample.payload = slave->payload_attached();
    sample.adapting = controller.adaptation();
    run.samples.push_back(sample);
    if (i == periods) break;

    // The master feels the slave's feedback with the sign reversed: +lambda H^ eps.
    MassMatrix h{};
    gen::mass_matrix<double>(slave_estimator.position().data(), controller.estimate().data(), h.data());
    Joints reflected{};
    for (int r = 0; r < kDof; ++r) {
      for (int c = 0; c < kDof; ++c) reflected[r] += controller.settings().lambda * h[r * kDof + c] * step.eps[c];
    }

    const double sub = period / kHandUpdatesPerPeriod;
    for (int k = 0; k < kHandUpdatesPerPeriod; ++k) {
      const double tk = t + k * sub;
      if (recorded) {
        master->reset(recorded->at(tk + sub).q);  // replayed: the master goes where the recording went
      } else {
        const TrajectoryPoint hand = script.at(tk);
        const Joints qm = master->q(), vm = master->qd();
        Joints weight{};
        gen::gravity_torque<double>(qm.data(), master_parameters.data(), weight.data());
        Joints tau_master{};
        for (int j = 0; j < kDof; ++j) {
          tau_master[j] = weight[j] + kHandStiffness[j] * (hand.q[j] - qm[j]) + kHandDamping[j] * (hand.qd[j] - vm[j]) +
                          reflected[j];
        }
        master->advance(tau_master, sub);
      }
      slave->advance(tau, sub);
    }
    if (progress) progress(static_cast<double>(i) / static_cast<double>(periods));
  }
  if (progress) progress(1.0);
  return run;
}

void write_csv(const Run& run, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write the log");
  out << "t";
  for (const char* group : {"master_q", "slave_q", "s", "tau"}) {
    for (int k = 1; k <= kDof; ++k) out << ',' << group << k;
  }
  for (int b = 0; b < kParameters; ++b) out << ",p_" << Kraft::parameter_names[b];
  out << ",contact,contact_force,payload,adapting\n";
  out.precision(9);
  for (const Sample& s : run.samples) {
    out << s.t;
    for (const Joints* group : {&s.master, &s.slave, &s.s, &s.tau}) {
      for (const double v : *group) out << ',' << v;
    }
    for (const double v : s.estimate) out << ',' << v;
    out << ',' << (s.contact ? 1 : 0) << ',' << s.contact_force << ',' << (s.payload ? 1 : 0) << ','
        << (s.adapting ? 1 : 0) << '\n';
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write the log");
}

}  // namespace dyncc::sim
