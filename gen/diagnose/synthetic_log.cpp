#include "diagnose/synthetic_log.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>

#include "diagnose/contact.hpp"
#include "diagnose/effects.hpp"
#include "diagnose/signals.hpp"

namespace dyncc::diagnose {
namespace {

constexpr double kStribeckVelocity = 0.1;
constexpr double kDiagnosisCutoff =
    4.0;  // Hz, the diagnosis' low-pass at the bench's rates  // rad/s: the injected static excess fades over this
constexpr int kHarmonics = 4;
constexpr double kBaseFrequency = 0.1;  // Hz

// Per joint: a Fourier series with random phases and amplitudes falling with the harmonic, as in
// identification experiments (the period 1 / kBaseFrequency).
class Excitation {
 public:
  Excitation(Eigen::Index n, double amplitude, unsigned seed) : n_(n) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> phase(0.0, 2 * std::numbers::pi), size(0.5, 1.0);
    for (Eigen::Index j = 0; j < n; ++j) {
      for (int k = 1; k <= kHarmonics; ++k) {
        waves_.push_back({amplitude * 0.45 * size(random) / k, phase(random),
                          2 * std::numbers::pi * kBaseFrequency * k * (1.0 + 0.07 * static_cast<double>(j))});
      }
    }
  }
  void at(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) const {
    q = qd = qdd = Eigen::VectorXd::Zero(n_);
    for (Eigen::Index j = 0; j < n_; ++j) {
      for (int k = 0; k < kHarmonics; ++k) {
        const Wave& w = waves_[static_cast<std::size_t>(j * kHarmonics + k)];
        const double s = std::sin(w.omega * t + w.phase), c = std::cos(w.omega * t + w.phase);
        q[j] += w.amplitude * s;
        qd[j] += w.amplitude * w.omega * c;
        qdd[j] -= w.amplitude * w.omega * w.omega * s;
      }
    }
  }

 private:
  struct Wave {
    double amplitude, phase, omega;
  };
  Eigen::Index n_;
  std::vector<Wave> waves_;
};

double sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

// The standard parameters with a payload: a point mass 5 cm along x of the payload link.
Eigen::VectorXd with_payload(const pipeline::Derivation& d, Eigen::VectorXd standard, double mass) {
  const int link = payload_link(d);
  const double x = 0.05;
  const std::array<double, 10> delta{mass, mass * x, 0, 0, 0, 0, 0, mass * x * x, 0, mass * x * x};
  for (std::size_t k = 0; k < 10; ++k) {
    const int index = d.model.params.of_link[static_cast<std::size_t>(link)][k];
    if (index >= 0) standard[index] += delta[k];
  }
  return standard;
}

// A surface the arm's payload link touches: a point of that link (off the diagnosis' grid of
// candidate points) pushed up by a spring while it is below the surface, with the peak force as
// the effect's size. The height is the 25 % quantile of the point's height over the motion.
struct Surface {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double height = 0, depth = 1;  // m: surface, and the deepest the point goes below it
  // The payload link's geometry, compiled once: compiling it at every sample was most of a
  // contact log's generation time.
  std::shared_ptr<const ContactGeometry> geometry;
};

struct Sample {
  Eigen::VectorXd logged_q, logged_tau, clean_tau;
  Eigen::VectorXd logged_qd, logged_qdd;  // the rates of the logged positions
  Eigen::VectorXd transmitted;            // what a transmission between motor and link carries
};

// What the link itself needs (its rigid bodies with the load, less the push of a table): the
// torque a transmission between motor and link carries. The drive's friction acts on the motor
// side, as in Spong's elastic joint. `rigid` is the model's evaluation at the link's state.
Eigen::VectorXd link_torque(const pipeline::Derivation& d, const std::vector<Injection>& effects,
                            const dyn::Evaluation& rigid, const Eigen::VectorXd& q, const Surface& surface) {
  Eigen::VectorXd tau = rigid.tau - rigid.friction;
  for (const Injection& e : effects) {
    if (e.effect != "contact") continue;
    const ContactGeometry::Basis b = surface.geometry ? surface.geometry->at(q) : ContactGeometry(d).at(q);
    const double below = surface.height - ContactGeometry::height(b, surface.point);
    if (below > 0) tau += e.size * below / surface.depth * ContactGeometry::lever(b, surface.point);
  }
  return tau;
}

// The same at time t of the excitation.
Eigen::VectorXd link_torque(const pipeline::Derivation& d, const std::vector<Injection>& effects, const Excitation& ex,
                            const Eigen::VectorXd& loaded, const Surface& surface, double t) {
  Eigen::VectorXd q, qd, qdd;
  ex.at(t, q, qd, qdd);
  return link_torque(d, effects, d.numeric->evaluate({q, qd, qd, qdd}, loaded, false), q, surface);
}

// How far an elastic joint's motor is ahead of its link (empty when no joint is elastic).
Eigen::VectorXd deflection(const std::vector<Injection>& effects, const Eigen::VectorXd& transmitted) {
  Eigen::VectorXd out;
  for (const Injection& e : effects) {
    if (e.effect != "joint_elasticity") continue;
    if (out.size() == 0) out = Eigen::VectorXd::Zero(transmitted.size());
    const auto j = static_cast<Eigen::Index>(e.joint);
    if (e.effect == "joint_elasticity") out[j] += transmitted[j] / e.size;
  }
  return out;
}

// A dead band of width b leaves the link b/2 behind the motor on the side the carried torque
// pushes. When that torque turns over, the motor crosses the band in kCrossing seconds (a smooth
// half-cosine from the turn): the motor's extra speed on the way is what the drive's friction sees.
// What is not simulated: the link runs free while the motor crosses (it follows its trajectory).
constexpr double kCrossing = 0.05;  // s

struct DeadBand {
  Eigen::VectorXd shift, rate, acceleration;  // of the motor against the link
};

// `now` is the carried torque at t; `carried` gives it at earlier times (only with a backlash).
DeadBand dead_band(const std::vector<Injection>& effects, const Eigen::VectorXd& now,
                   const std::function<Eigen::VectorXd(double)>& carried, double t) {
  DeadBand out{Eigen::VectorXd::Zero(now.size()), Eigen::VectorXd::Zero(now.size()), Eigen::VectorXd::Zero(now.size())};
  std::optional<Eigen::VectorXd> before;
  for (const Injection& e : effects) {
    if (e.effect != "backlash") continue;
    if (!before) before = carried(t - kCrossing);
    const auto j = static_cast<Eigen::Index>(e.joint);
    const double to = sign(now[j]), from = sign((*before)[j]), half = 0.5 * e.size;
    if (to == from || to == 0 || from == 0) {
      out.shift[j] += half * to;
      continue;
    }
    double lo = t - kCrossing, hi = t;  // the turn: the carried torque has sign `from` at lo, `to` at hi
    for (int k = 0; k < 30; ++k) {
      const double mid = 0.5 * (lo + hi);
      (sign(carried(mid)[j]) == from ? lo : hi) = mid;
    }
    const double phase = std::numbers::pi * (t - hi) / kCrossing, swing = half * (to - from);
    out.shift[j] += half * from + swing * 0.5 * (1 - std::cos(phase));
    out.rate[j] += swing * 0.5 * std::sin(phase) * std::numbers::pi / kCrossing;
    out.acceleration[j] += swing * 0.5 * std::cos(phase) * std::pow(std::numbers::pi / kCrossing, 2);
  }
  return out;
}

constexpr double kRateStep = 1e-3;  // s: a spring's deflection rate by central differences

// The model's evaluations that a sample at time t needs: at the link's state with the nominal
// parameters (the clean torque) and with the sample's own (the rigid torque the link needs), and
// with a spring, the latter kRateStep before and after.
struct SampleModel {
  dyn::Evaluation clean, rigid, earlier, later;
};

bool elastic(const std::vector<Injection>& effects) {
  return std::any_of(effects.begin(), effects.end(), [](const Injection& e) { return e.effect == "joint_elasticity"; });
}

// The SampleModels of samples at `times`, sample k with the parameters *params[k], computed
// together (NumericModel's batch evaluation: the same numbers as one by one).
std::vector<SampleModel> sample_models(const pipeline::Derivation& d, const std::vector<Injection>& effects,
                                       const Excitation& ex, const Eigen::VectorXd& nominal,
                                       const std::vector<double>& times,
                                       const std::vector<const Eigen::VectorXd*>& params) {
  const dyn::NumericModel& model = *d.numeric;
  auto state_at = [&](double t) {
    dyn::State s;
    ex.at(t, s.q, s.qd, s.a);
    s.v = s.qd;
    return s;
  };
  std::vector<dyn::State> at;
  at.reserve(times.size());
  for (const double t : times) at.push_back(state_at(t));
  std::vector<SampleModel> out(times.size());
  const std::vector<dyn::Evaluation> clean = model.evaluate(at, nominal, false);
  for (std::size_t k = 0; k < times.size(); ++k) out[k].clean = clean[k];
  // The rigid torque with the samples' own parameters (the clean evaluation where they are the
  // nominal ones), and a spring's neighbours, one batch per parameter set.
  std::vector<const Eigen::VectorXd*> groups;
  for (const Eigen::VectorXd* p : params) {
    if (std::find(groups.begin(), groups.end(), p) == groups.end()) groups.push_back(p);
  }
  const bool spring = elastic(effects);
  for (const Eigen::VectorXd* group : groups) {
    const bool clean_is_rigid = group == &nominal;
    std::vector<std::size_t> which;
    std::vector<dyn::State> states;
    for (std::size_t k = 0; k < times.size(); ++k) {
      if (params[k] != group) continue;
      which.push_back(k);
      if (!clean_is_rigid) states.push_back(at[k]);
      if (spring) {
        states.push_back(state_at(times[k] - kRateStep));
        states.push_back(state_at(times[k] + kRateStep));
      }
    }
    const std::vector<dyn::Evaluation> e = model.evaluate(states, *group, false);
    std::size_t next = 0;
    for (const std::size_t k : which) {
      out[k].rigid = clean_is_rigid ? out[k].clean : e[next++];
      if (spring) {
        out[k].earlier = e[next++];
        out[k].later = e[next++];
      }
    }
  }
  return out;
}

Sample sample(const pipeline::Derivation& d, const std::vector<Injection>& effects, const Excitation& ex,
              const Eigen::VectorXd& loaded, const Surface& surface, double t, const SampleModel& m) {
  Eigen::VectorXd q, qd, qdd;
  ex.at(t, q, qd, qdd);
  const dyn::NumericModel& model = *d.numeric;
  Sample s;
  s.clean_tau = m.clean.tau;
  s.transmitted = link_torque(d, effects, m.rigid, q, surface);
  s.logged_q = q;
  s.logged_qd = qd;
  s.logged_qdd = qdd;
  for (const Injection& e : effects) {  // read late
    if (e.effect == "sensor_delay") ex.at(t - e.size, s.logged_q, s.logged_qd, s.logged_qdd);
  }
  // The position is read on the motor side of a transmission that is not rigid: a spring of
  // stiffness k deflects by the torque it carries over k, and the motor turns at the link's rate
  // plus the spring's, which the drive's friction sees; likewise across a dead band (dead_band).
  const Eigen::VectorXd bent = deflection(effects, s.transmitted);
  Eigen::VectorXd motor = qd;
  if (bent.size() > 0) {
    constexpr double h = kRateStep;
    Eigen::VectorXd q_later, q_earlier, unused_rate, unused_acceleration;
    ex.at(t + h, q_later, unused_rate, unused_acceleration);
    ex.at(t - h, q_earlier, unused_rate, unused_acceleration);
    const Eigen::VectorXd later = deflection(effects, link_torque(d, effects, m.later, q_later, surface)),
                          earlier = deflection(effects, link_torque(d, effects, m.earlier, q_earlier, surface));
    s.logged_q += bent;
    s.logged_qd += (later - earlier) / (2 * h);
    s.logged_qdd += (later - 2 * bent + earlier) / (h * h);
    motor += (later - earlier) / (2 * h);
  }
  const DeadBand band = dead_band(
      effects, s.transmitted, [&](double at) { return link_torque(d, effects, ex, loaded, surface, at); }, t);
  s.logged_q += band.shift;
  s.logged_qd += band.rate;
  s.logged_qdd += band.acceleration;
  motor += band.rate;
  s.logged_tau = s.transmitted + model.friction({q, motor, motor, qdd}, loaded);
  for (const Injection& e : effects) {
    const auto j = static_cast<Eigen::Index>(e.joint);
    if (e.effect == "coulomb_friction") s.logged_tau[j] += e.size * sign(motor[j]);
    if (e.effect == "viscous_friction") s.logged_tau[j] += e.size * motor[j];
    if (e.effect == "stribeck_friction") {
      s.logged_tau[j] += e.size * std::exp(-std::pow(motor[j] / kStribeckVelocity, 2)) * sign(motor[j]);
    }
    if (e.effect == "rotor_inertia") s.logged_tau[j] += e.size * qdd[j];
    if (e.effect == "position_offset") s.logged_q[j] += e.size;
  }
  for (const Injection& e : effects) {  // the logged command: the motor gives gain * it
    if (e.effect == "torque_gain") s.logged_tau[e.joint] /= e.size;
  }
  return s;
}

bool carried(const SyntheticOptions& o, double t) { return t >= o.payload_on && t < o.payload_off; }

// What both the sizing and the writing start from: the trajectory and the true parameters.
struct Scene {
  Scene(const pipeline::Derivation& d, const std::vector<Injection>& effects, const SyntheticOptions& o)
      : n(static_cast<Eigen::Index>(d.robot.coordinates.size())),
        excitation(n, o.amplitude, o.seed),
        nominal(d.numeric->nominal_standard_values()) {
    double payload = 0;
    for (const Injection& e : effects) payload += e.effect == "payload" ? e.size : 0.0;
    loaded = with_payload(d, nominal, payload);
    const bool touches =
        std::any_of(effects.begin(), effects.end(), [](const Injection& e) { return e.effect == "contact"; });
    auto geometry = std::make_shared<const ContactGeometry>(d);
    if (touches && geometry->valid()) {
      surface = place_surface(*geometry, o);
      surface.geometry = std::move(geometry);
    }
  }
  Surface place_surface(const ContactGeometry& geometry, const SyntheticOptions& o) const {
    const int samples = 2000;
    std::vector<ContactGeometry::Basis> bases;
    Eigen::VectorXd origin(samples);
    for (int i = 0; i < samples; ++i) {
      Eigen::VectorXd q, qd, qdd;
      excitation.at(o.duration * i / samples, q, qd, qdd);
      bases.push_back(geometry.at(q));
      origin[i] = bases.back().height[0];
    }
    const double scale = ContactGeometry::scale(origin);
    Surface s;
    s.point = Eigen::Vector3d(0.8 * scale, 0.0, 0.2 * scale);
    std::vector<double> heights;
    heights.reserve(bases.size());
    for (const auto& b : bases) heights.push_back(ContactGeometry::height(b, s.point));
    std::sort(heights.begin(), heights.end());
    s.height = heights[heights.size() / 4];
    s.depth = std::max(1e-6, s.height - heights.front());
    return s;
  }
  Eigen::Index n;
  Excitation excitation;
  Eigen::VectorXd nominal, loaded;
  Surface surface;
};

// The samples at `times` (with the load where it is carried), their model evaluations made
// together (sample_models).
std::vector<Sample> samples_at(const pipeline::Derivation& d, const std::vector<Injection>& effects, const Scene& scene,
                               const SyntheticOptions& o, const std::vector<double>& times) {
  std::vector<const Eigen::VectorXd*> params;
  params.reserve(times.size());
  for (const double t : times) params.push_back(carried(o, t) ? &scene.loaded : &scene.nominal);
  const std::vector<SampleModel> models = sample_models(d, effects, scene.excitation, scene.nominal, times, params);
  std::vector<Sample> out;
  out.reserve(times.size());
  for (std::size_t k = 0; k < times.size(); ++k) {
    out.push_back(sample(d, effects, scene.excitation, *params[k], scene.surface, times[k], models[k]));
  }
  return out;
}

constexpr std::size_t kSamplesPerBatch = 512;

}  // namespace

std::vector<std::string> injectable_effects() {
  return {"coulomb_friction", "viscous_friction", "stribeck_friction", "payload",
          "torque_gain",      "sensor_delay",     "position_offset",   "rotor_inertia",
          "contact",          "joint_elasticity", "backlash"};
}

bool acts_on_one_joint(const std::string& effect) {
  return effect != "payload" && effect != "sensor_delay" && effect != "contact" && effect != "none";
}

EffectSize effect_size(const pipeline::Derivation& d, const std::vector<Injection>& effects,
                       const SyntheticOptions& o) {
  const Scene scene(d, effects, o);
  const Eigen::Index n = scene.n;
  const Eigen::VectorXd& nominal = scene.nominal;
  // As the diagnosis sees them: through its zero-phase low-pass (a Stribeck pulse at a reversal
  // and a Coulomb step lose different shares of their RMS to it). Every 20 ms, or ten times
  // across a dead band's crossing, which a coarser grid samples as a spike or misses.
  const bool crossing =
      std::any_of(effects.begin(), effects.end(), [](const Injection& e) { return e.effect == "backlash"; });
  const int samples = crossing ? static_cast<int>(10 * o.duration / kCrossing) : 2000;
  Eigen::MatrixXd clean(samples, n), change(samples, n), transmitted(samples, n);
  for (int first = 0; first < samples; first += static_cast<int>(kSamplesPerBatch)) {
    std::vector<double> times;
    for (int i = first; i < std::min(samples, first + static_cast<int>(kSamplesPerBatch)); ++i) {
      times.push_back(o.duration * i / samples);
    }
    const std::vector<Sample> batch = samples_at(d, effects, scene, o, times);
    // What the diagnosis sees: logged torque minus the model at the logged positions and their rates.
    std::vector<dyn::State> logged;
    logged.reserve(batch.size());
    for (const Sample& s : batch) logged.push_back({s.logged_q, s.logged_qd, s.logged_qd, s.logged_qdd});
    const std::vector<dyn::Evaluation> model_at_logged = d.numeric->evaluate(logged, nominal, false);
    for (std::size_t k = 0; k < batch.size(); ++k) {
      const Eigen::Index i = first + static_cast<Eigen::Index>(k);
      clean.row(i) = batch[k].clean_tau.transpose();
      transmitted.row(i) = batch[k].transmitted.transpose();
      change.row(i) = (batch[k].logged_tau - model_at_logged[k].tau).transpose();
    }
  }
  const double rate = samples / o.duration, cutoff = std::min(rate / 8, kDiagnosisCutoff);
  EffectSize out{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), minority_sign_share(transmitted)};
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::VectorXd c = zero_phase_lowpass(clean.col(j), cutoff, rate);
    const Eigen::VectorXd e = zero_phase_lowpass(change.col(j), cutoff, rate);
    out.clean_rms[j] = std::sqrt(c.squaredNorm() / samples);
    out.effect_rms[j] = std::sqrt(e.squaredNorm() / samples);
  }
  return out;
}

void write_synthetic_log(const pipeline::Derivation& d, const std::vector<Injection>& effects,
                         const SyntheticOptions& o, const std::filesystem::path& path) {
  const Scene scene(d, effects, o);
  const Eigen::Index n = scene.n;
  std::mt19937 random(o.seed + 7919);
  std::normal_distribution<double> noise(0.0, o.torque_noise);
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << "t";
  for (Eigen::Index j = 1; j <= n; ++j) out << ",q" << j;
  for (Eigen::Index j = 1; j <= n; ++j) out << ",tau" << j;
  out << "\n";
  out.precision(10);
  const auto samples = static_cast<long>(o.duration * o.rate);
  for (long first = 0; first < samples; first += static_cast<long>(kSamplesPerBatch)) {
    std::vector<double> times;
    for (long i = first; i < std::min(samples, first + static_cast<long>(kSamplesPerBatch)); ++i) {
      times.push_back(static_cast<double>(i) / o.rate);
    }
    const std::vector<Sample> batch = samples_at(d, effects, scene, o, times);
    for (std::size_t k = 0; k < batch.size(); ++k) {
      const Sample& s = batch[k];
      out << times[k];
      for (Eigen::Index j = 0; j < n; ++j) {
        out << ',' << (o.quantum > 0 ? o.quantum * std::round(s.logged_q[j] / o.quantum) : s.logged_q[j]);
      }
      for (Eigen::Index j = 0; j < n; ++j) out << ',' << s.logged_tau[j] + noise(random);
      out << "\n";
    }
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace dyncc::diagnose
