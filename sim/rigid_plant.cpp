// The rigid plant: the generated Kraft model with the true parameters, integrated by classic RK4.
// Joint friction and the table contact are the two non-smooth effects; both are regularised over
// a small velocity scale so that RK4 at >= 1 kHz stays accurate (the time constants they
// introduce, H / (f_c / v_s), stay above ten integration steps).
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

class RigidPlant final : public Plant {
 public:
  explicit RigidPlant(const PlantSettings& settings) : settings_(settings), unloaded_(rigid_part(true_parameters({}))) {
    Payload carried = settings.payload;
    loaded_ = rigid_part(true_parameters(carried));
    const Parameters nominal = true_parameters({});
    for (int k = 0; k < kDof; ++k) {
      const std::string joint = std::to_string(k + 1);
      coulomb_[k] = settings.joint_friction ? nominal[base_parameter_index(("FC" + joint).c_str())] : 0.0;
      viscous_[k] = settings.joint_friction ? nominal[base_parameter_index(("FV" + joint).c_str())] : 0.0;
    }
  }

  void reset(const Joints& q) override {
    q_ = q;
    qd_ = Joints{};
    attached_ = false;
    contact_ = contact_force(q_, qd_).state;
  }

  void advance(const Joints& tau, double duration) override {
    const int steps = std::max(1, static_cast<int>(std::lround(duration * settings_.rate)));
    const double dt = duration / steps;
    for (int i = 0; i < steps; ++i) rk4(tau, dt);
    contact_ = contact_force(q_, qd_).state;
  }

  void set_payload_attached(bool attached) override { attached_ = attached; }
  [[nodiscard]] Joints q() const override { return q_; }
  [[nodiscard]] Joints qd() const override { return qd_; }
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

  [[nodiscard]] Joints acceleration(const Joints& q, const Joints& qd, const Joints& tau) const {
    const Parameters& p = attached_ ? loaded_ : unloaded_;
    MassMatrix h{};
    gen::mass_matrix<double>(q.data(), p.data(), h.data());
    const Joints zero{};
    Joints bias{};  // C qd + g
    gen::inverse_dynamics<double>(q.data(), qd.data(), zero.data(), p.data(), bias.data());
    const Contact contact = contact_force(q, qd);
    Joints rhs{};
    for (int k = 0; k < kDof; ++k) {
      const double friction = coulomb_[k] * std::tanh(qd[k] / kFrictionVelocityScale) + viscous_[k] * qd[k];
      rhs[k] = tau[k] - bias[k] - friction + contact.generalized[k];
    }
    Joints qdd{};
    runtime::solve_positive_definite<double, kDof>(h, rhs, qdd);  // H of a real arm is always definite
    return qdd;
  }

  void rk4(const Joints& tau, double dt) {
    auto along = [](const Joints& x, const Joints& dx, double s) {
      Joints y{};
      for (int k = 0; k < kDof; ++k) y[k] = x[k] + s * dx[k];
      return y;
    };
    const Joints a1 = acceleration(q_, qd_, tau);
    const Joints q2 = along(q_, qd_, dt / 2), v2 = along(qd_, a1, dt / 2);
    const Joints a2 = acceleration(q2, v2, tau);
    const Joints q3 = along(q_, v2, dt / 2), v3 = along(qd_, a2, dt / 2);
    const Joints a3 = acceleration(q3, v3, tau);
    const Joints q4 = along(q_, v3, dt), v4 = along(qd_, a3, dt);
    const Joints a4 = acceleration(q4, v4, tau);
    for (int k = 0; k < kDof; ++k) {
      q_[k] += dt / 6 * (qd_[k] + 2 * v2[k] + 2 * v3[k] + v4[k]);
      qd_[k] += dt / 6 * (a1[k] + 2 * a2[k] + 2 * a3[k] + a4[k]);
    }
  }

  PlantSettings settings_;
  Parameters unloaded_, loaded_{};
  Joints coulomb_{}, viscous_{};
  Joints q_{}, qd_{};
  bool attached_ = false;
  ContactState contact_;
};

}  // namespace

std::unique_ptr<Plant> make_rigid_plant(const PlantSettings& settings) {
  return std::make_unique<RigidPlant>(settings);
}

}  // namespace dyncc::sim
