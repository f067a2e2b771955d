// The rigid plant: the generated Kraft model with the true parameters, integrated by classic RK4.
// Joint friction and the table contact are the two non-smooth effects; both are regularised over
// a small velocity scale so that RK4 at >= 1 kHz stays accurate (the time constants they
// introduce, H / (f_c / v_s), stay above ten integration steps).
//
// Hidden joint effects (sim/joint_effects.hpp) enter where they act on a real arm: extra friction
// with the description's, extra reflected inertia on the diagonal of H, and a transmission that is
// not rigid as a motor body of its own (its reflected rotor inertia, taken out of the links'
// parameters) coupled to the link through the dead band and spring of transmission_torque.
#include <algorithm>
#include <cmath>
#include <string>

#include "dyncc/runtime/small_matrix.hpp"
#include "plant.hpp"

namespace dyncc::sim {
namespace {

namespace gen = dyncc::generated::kraft_right;

constexpr double kFrictionVelocityScale = 0.01;  // rad/s over which Coulomb friction turns over
constexpr double kSlipVelocityScale = 0.005;     // m/s, the same for the tangential contact force

// Links (q, qd) and motors (m, md); a motor's entries are used only where the transmission is not
// rigid (elsewhere motor and link are one body).
struct State {
  Joints q{}, qd{}, m{}, md{};
};

State along(const State& x, const State& dx, double s) {
  State y;
  for (int k = 0; k < kDof; ++k) {
    y.q[k] = x.q[k] + s * dx.q[k];
    y.qd[k] = x.qd[k] + s * dx.qd[k];
    y.m[k] = x.m[k] + s * dx.m[k];
    y.md[k] = x.md[k] + s * dx.md[k];
  }
  return y;
}

class RigidPlant final : public Plant {
 public:
  explicit RigidPlant(const PlantSettings& settings) : settings_(settings) {
    const JointEffects& e = settings.effects;
    for (int k = 0; k < kDof; ++k) apart_[k] = !e.transmission[k].rigid();
    unloaded_ = rigid_part(true_parameters({}, apart_));
    loaded_ = rigid_part(true_parameters(settings.payload, apart_));
    const Parameters nominal = true_parameters({});
    const Joints rotor = rotor_inertias();
    for (int k = 0; k < kDof; ++k) {
      const std::string joint = std::to_string(k + 1);
      const bool own = settings.joint_friction;
      coulomb_[k] = (own ? nominal[base_parameter_index(("FC" + joint).c_str())] : 0.0) + e.coulomb[k];
      viscous_[k] = (own ? nominal[base_parameter_index(("FV" + joint).c_str())] : 0.0) + e.viscous[k];
      // The extra reflected inertia sits with the rotor: on the motor body where there is one.
      motor_inertia_[k] = apart_[k] ? rotor[k] + e.rotor_inertia[k] : 0.0;
      link_inertia_[k] = apart_[k] ? 0.0 : e.rotor_inertia[k];
    }
  }

  void reset(const Joints& q) override {
    x_ = State{};
    x_.q = q;
    attached_ = false;
    Joints weight{};
    gen::gravity_torque<double>(q.data(), unloaded_.data(), weight.data());
    for (int k = 0; k < kDof; ++k) {
      x_.m[k] = apart_[k] ? q[k] + transmission_deflection(settings_.effects.transmission[k], weight[k]) : q[k];
    }
    contact_ = contact_force(x_.q, x_.qd).state;
  }

  void advance(const Joints& tau, double duration) override {
    const int steps = std::max(1, static_cast<int>(std::lround(duration * settings_.rate)));
    const double dt = duration / steps;
    for (int i = 0; i < steps; ++i) rk4(tau, dt);
    contact_ = contact_force(x_.q, x_.qd).state;
  }

  void set_payload_attached(bool attached) override { attached_ = attached; }
  [[nodiscard]] Joints q() const override { return x_.q; }
  [[nodiscard]] Joints qd() const override { return x_.qd; }
  [[nodiscard]] Joints sensor_q() const override {
    Joints out{};
    for (int k = 0; k < kDof; ++k) out[k] = apart_[k] ? x_.m[k] : x_.q[k];
    return out;
  }
  [[nodiscard]] ContactState contact() const override { return contact_; }
  [[nodiscard]] bool payload_attached() const override { return attached_; }
  [[nodiscard]] std::string name() const override { return "dyncc"; }

 private:
  // The rigid-body part of the base parameters: friction is modelled here, regularised.
  static Parameters rigid_part(Parameters p) {
    for (const char* name : {"FC1", "FV1", "FC2", "FV2", "FC3", "FV3"}) p[base_parameter_index(name)] = 0.0;
    return p;
  }

  struct Contact {
    ContactState state;
    Joints generalized{};  // J^T F
  };

  // Unilateral spring-damper normal to the table, regularised Coulomb friction along it.
  [[nodiscard]] Contact contact_force(const Joints& q, const Joints& qd) const {
    Contact out;
    if (!settings_.table.present) return out;
    const Vec3 p = forearm_point(q, kHookInForearm);
    const double depth = settings_.table.height - p[2];
    if (depth <= 0.0) return out;
    const std::array<double, 9> j = forearm_point_jacobian(q, kHookInForearm);
    Vec3 v{};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < kDof; ++c) v[r] += j[r * 3 + c] * qd[c];
    }
    const double normal = std::max(0.0, settings_.table.stiffness * depth - settings_.table.damping * v[2]);
    const double slip = std::sqrt(v[0] * v[0] + v[1] * v[1] + kSlipVelocityScale * kSlipVelocityScale);
    const Vec3 force{-settings_.table.friction * normal * v[0] / slip, -settings_.table.friction * normal * v[1] / slip,
                     normal};
    out.state = {normal > 0.0, normal};
    for (int c = 0; c < kDof; ++c) {
      for (int r = 0; r < 3; ++r) out.generalized[c] += j[r * 3 + c] * force[r];
    }
    return out;
  }

  // Joint friction: the description's Coulomb and viscous terms plus the hidden extra ones, the
  // Stribeck excess raising the Coulomb level near rest.
  [[nodiscard]] double friction(int k, double velocity) const {
    const double level = coulomb_[k] + stribeck_excess(settings_.effects, k, velocity);
    return level * std::tanh(velocity / kFrictionVelocityScale) + viscous_[k] * velocity;
  }

  // The rates of the state under the applied joint torque tau (on the motor where there is one).
  [[nodiscard]] State rates(const State& x, const Joints& tau) const {
    const Parameters& p = attached_ ? loaded_ : unloaded_;
    MassMatrix h{};
    gen::mass_matrix<double>(x.q.data(), p.data(), h.data());
    for (int k = 0; k < kDof; ++k) h[k * kDof + k] += link_inertia_[k];
    const Joints zero{};
    Joints bias{};  // C qd + g
    gen::inverse_dynamics<double>(x.q.data(), x.qd.data(), zero.data(), p.data(), bias.data());
    const Contact contact = contact_force(x.q, x.qd);
    State dx;
    dx.q = x.qd;
    dx.m = x.md;
    Joints rhs{};
    for (int k = 0; k < kDof; ++k) {
      double drive = tau[k];
      if (apart_[k]) {  // the link gets what the transmission passes; the motor keeps the rest
        drive = transmission_torque(settings_.effects.transmission[k], motor_inertia_[k], x.m[k] - x.q[k],
                                    x.md[k] - x.qd[k]);
        dx.md[k] = (tau[k] - drive) / motor_inertia_[k];
      }
      rhs[k] = drive - bias[k] - friction(k, x.qd[k]) + contact.generalized[k];
    }
    runtime::solve_positive_definite<double, kDof>(h, rhs, dx.qd);  // H of a real arm is always definite
    return dx;
  }

  void rk4(const Joints& tau, double dt) {
    const State k1 = rates(x_, tau);
    const State k2 = rates(along(x_, k1, dt / 2), tau);
    const State k3 = rates(along(x_, k2, dt / 2), tau);
    const State k4 = rates(along(x_, k3, dt), tau);
    auto step = [dt](double& x, double r1, double r2, double r3, double r4) {
      x += dt / 6 * (r1 + 2 * r2 + 2 * r3 + r4);
    };
    for (int k = 0; k < kDof; ++k) {
      step(x_.q[k], k1.q[k], k2.q[k], k3.q[k], k4.q[k]);
      step(x_.qd[k], k1.qd[k], k2.qd[k], k3.qd[k], k4.qd[k]);
      step(x_.m[k], k1.m[k], k2.m[k], k3.m[k], k4.m[k]);
      step(x_.md[k], k1.md[k], k2.md[k], k3.md[k], k4.md[k]);
    }
  }

  PlantSettings settings_;
  std::array<bool, kDof> apart_{};  // a motor body of its own (non-rigid transmission)
  Parameters unloaded_{}, loaded_{};
  Joints coulomb_{}, viscous_{};
  Joints motor_inertia_{};  // kg m^2, the motor bodies
  Joints link_inertia_{};   // kg m^2, extra reflected inertia on H's diagonal (rigid transmissions)
  State x_;
  bool attached_ = false;
  ContactState contact_;
};

}  // namespace

std::unique_ptr<Plant> make_rigid_plant(const PlantSettings& settings) {
  return std::make_unique<RigidPlant>(settings);
}

}  // namespace dyncc::sim
