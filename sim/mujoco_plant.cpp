// The MuJoCo plant: the arm as MuJoCo simulates it from the MJCF that `dyncc export` writes, with
// MuJoCo's own (soft) loop closure, joint friction and contact instead of dyncc's equations.
//
// It reads everything it needs from the MJCF itself (sim/ never links gen/):
//   * which joint carries which coordinate: the exporter puts one <motor> per coordinate, named
//     after it, on the joint that follows that coordinate alone, with gear = 1/scale
//     (joint = scale * q); the joint's rotor inertia, friction and limits sit on that joint too;
//   * how the other joints follow: the joint and fixed-tendon equalities (linear couplings, every
//     joint reads 0 at q = 0), solved here for reset(q) so MuJoCo starts on the constraint
//     manifold; the <connect> of the loop is redundant with them and is left to MuJoCo.
// What it adds before MuJoCo compiles the text: the time step, a hook sphere on the forearm, a
// massless welded payload body and, if asked for, the table.
#include <fmt/core.h>
#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "plant.hpp"

namespace dyncc::sim {
namespace {

namespace kraft = dyncc::generated::kraft_right;

// Names of what this file adds to the exported model (prefixed so they cannot clash with a link).
constexpr const char* kForearmBody = "forearm";  // the description's link carrying the hook
constexpr const char* kHookGeom = "sim_hook";
constexpr const char* kPayloadBody = "sim_payload";
constexpr const char* kTableGeom = "sim_table";
constexpr const char* kVirtualFile = "kraft.xml";

// The hook is a small sphere centred on kHookInForearm: small enough that the point where it
// touches is the hook point to within a few millimetres, large enough for MuJoCo's
// sphere-plane collision to be well defined.
constexpr double kHookRadius = 0.005;

// Contact: MuJoCo's soft contact, solref = (time constant, damping ratio). 5 ms critically damped
// is stiff (the static penetration under a load is about (1 - d) a0 tc^2 / d, tens of
// micrometres here) and still ten time steps long at the 2 kHz default, so semi-implicit Euler
// resolves it; MuJoCo's default 20 ms would let the hook sink visibly into the table and
// respond as a soft pad. solimp stays MuJoCo's default (0.9 0.95 0.001).
constexpr double kContactTimeConstant = 0.005;

// The loop closure (joint and tendon equalities, the <connect>): as stiff as MuJoCo's stability
// rule allows (time constant 2 time steps, what refsafe clamps to anyway) and an impedance close
// to 1, so the static violation (1 - d) a0 tc^2 / d stays far below 1e-6 rad. With the defaults
// (20 ms, d = 0.9..0.95) the parallelogram would sag by ~1e-3 rad under the forearm's weight.
constexpr std::array<double, 5> kEqualityImpedance{0.9999, 0.9999, 0.001, 0.5, 2.0};

// Joint Coulomb friction (frictionloss) is a soft constraint too: a joint held below the
// breakaway torque creeps at about (1 - d) a0 / (d b). Stiffer than the default so the creep is
// negligible (1e-6 rad/s order) while stiction still holds.
constexpr std::array<double, 5> kFrictionImpedance{0.999, 0.999, 0.001, 0.5, 2.0};

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// The VFS holds 2000 file slots of 1000-character names (about 2 MB), so it lives on the heap.
struct VfsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    delete vfs;  // NOLINT(cppcoreguidelines-owning-memory): paired with the new in load_model
  }
};

// Where row `index` of a MuJoCo array with `width` numbers per row starts.
std::ptrdiff_t offset(int index, int width) { return static_cast<std::ptrdiff_t>(index) * width; }

std::string vector_text(double x, double y, double z) { return fmt::format("{} {} {}", x, y, z); }

tinyxml2::XMLElement* find_body(tinyxml2::XMLElement* parent, const char* name) {
  for (tinyxml2::XMLElement* body = parent->FirstChildElement("body"); body != nullptr;
       body = body->NextSiblingElement("body")) {
    const char* body_name = body->Attribute("name");
    if (body_name != nullptr && std::strcmp(body_name, name) == 0) return body;
    if (tinyxml2::XMLElement* found = find_body(body, name)) return found;
  }
  return nullptr;
}

tinyxml2::XMLElement* child_or_new(tinyxml2::XMLElement* parent, const char* name) {
  tinyxml2::XMLElement* child = parent->FirstChildElement(name);
  if (child == nullptr) child = parent->InsertNewChildElement(name);
  return child;
}

// The exported MJCF with what the simulation adds, as text for MuJoCo.
std::string augmented_mjcf(const PlantSettings& settings, const std::string& mjcf_path) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(mjcf_path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::runtime_error("MuJoCo plant: cannot read " + mjcf_path + ": " + doc.ErrorStr());
  }
  tinyxml2::XMLElement* root = doc.RootElement();
  if (root == nullptr || std::strcmp(root->Name(), "mujoco") != 0) {
    throw std::runtime_error("MuJoCo plant: " + mjcf_path + " is not MJCF (no <mujoco> root)");
  }
  tinyxml2::XMLElement* worldbody = root->FirstChildElement("worldbody");
  tinyxml2::XMLElement* forearm = worldbody != nullptr ? find_body(worldbody, kForearmBody) : nullptr;
  if (forearm == nullptr) {
    throw std::runtime_error("MuJoCo plant: " + mjcf_path + " has no body \"" + kForearmBody + "\"");
  }

  // Integration: MuJoCo's semi-implicit Euler at the plant's rate (it treats joint damping
  // implicitly, and its soft constraints are designed around it; RK4 would gain little with
  // contacts and dry friction). The elliptic cone is the isotropic Coulomb cone |f_t| <= mu f_n,
  // the law the rigid plant uses; MuJoCo's default pyramid approximates it.
  tinyxml2::XMLElement* option = child_or_new(root, "option");
  option->SetAttribute("timestep", fmt::format("{}", 1.0 / settings.rate).c_str());
  option->SetAttribute("integrator", "Euler");
  option->SetAttribute("cone", "elliptic");

  // Contact only between the hook and the table: the exported link capsules have
  // contype = conaffinity = 0, and bit 2 here pairs the hook (contype) with the table
  // (conaffinity) and nothing else. Both geoms carry the same friction and solref, so MuJoCo's
  // mixing of the two (maximum friction, averaged solref) changes nothing.
  const std::string friction = fmt::format("{} 0.005 0.0001", settings.table.friction);
  const std::string solref = fmt::format("{} 1", kContactTimeConstant);
  tinyxml2::XMLElement* hook = forearm->InsertNewChildElement("geom");
  hook->SetAttribute("name", kHookGeom);
  hook->SetAttribute("type", "sphere");
  hook->SetAttribute("size", fmt::format("{}", kHookRadius).c_str());
  hook->SetAttribute("pos", vector_text(kHookInForearm[0], kHookInForearm[1], kHookInForearm[2]).c_str());
  hook->SetAttribute("contype", 2);
  hook->SetAttribute("conaffinity", 0);
  hook->SetAttribute("condim", 3);
  hook->SetAttribute("friction", friction.c_str());
  hook->SetAttribute("solref", solref.c_str());

  // The payload: welded to the forearm (no joint), its mass set at run time by
  // set_payload_attached. The compiler wants a positive placeholder mass; the plant zeroes it
  // right after loading (a welded body may have zero mass).
  const Vec3& at = settings.payload.position_in_forearm;
  tinyxml2::XMLElement* payload = forearm->InsertNewChildElement("body");
  payload->SetAttribute("name", kPayloadBody);
  payload->SetAttribute("pos", vector_text(at[0], at[1], at[2]).c_str());
  tinyxml2::XMLElement* inertial = payload->InsertNewChildElement("inertial");
  inertial->SetAttribute("pos", "0 0 0");
  inertial->SetAttribute("mass", 1.0);
  inertial->SetAttribute("diaginertia", "1e-4 1e-4 1e-4");

  // The table: a half-space (plane) whose surface is one hook radius below table.height, so the
  // sphere touches when the hook point reaches table.height, as the rigid plant's spring does.
  if (settings.table.present) {
    tinyxml2::XMLElement* table = worldbody->InsertNewChildElement("geom");
    table->SetAttribute("name", kTableGeom);
    table->SetAttribute("type", "plane");
    table->SetAttribute("size", "0 0 0.05");  // 0 0: infinite
    table->SetAttribute("pos", vector_text(0.0, 0.0, settings.table.height - kHookRadius).c_str());
    table->SetAttribute("contype", 0);
    table->SetAttribute("conaffinity", 2);
    table->SetAttribute("condim", 3);
    table->SetAttribute("friction", friction.c_str());
    table->SetAttribute("solref", solref.c_str());
  }

  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return {printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1)};
}

// Compiles MJCF text through MuJoCo's virtual file system (no temporary file to clean up).
ModelPtr load_model(const std::string& text, const std::string& mjcf_path) {
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);  // NOLINT(cppcoreguidelines-owning-memory)
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kVirtualFile, static_cast<int>(text.size())) != 0) {
    throw std::runtime_error("MuJoCo plant: cannot create the virtual MJCF file");
  }
  const int file = mj_findFileVFS(vfs.get(), kVirtualFile);
  std::memcpy(vfs->filedata[file], text.data(), text.size());
  std::array<char, 1000> error{};
  ModelPtr model(mj_loadXML(kVirtualFile, vfs.get(), error.data(), static_cast<int>(error.size())));
  mj_freeLastXML();  // MuJoCo keeps the parsed XML for mj_saveLastXML; nothing here needs it
  if (model == nullptr) throw std::runtime_error("MuJoCo cannot load " + mjcf_path + ": " + error.data());
  return model;
}

// A linear relation sum_j a_j (qpos_j - qpos0_j) = b among the joints, from an equality.
struct Relation {
  std::vector<double> a;
  double b = 0.0;
};

// The fixed tendon `tendon` as coefficients over the joints (its length minus length0).
void add_tendon(const mjModel* m, int tendon, double factor, std::vector<double>& a) {
  for (int w = m->tendon_adr[tendon]; w < m->tendon_adr[tendon] + m->tendon_num[tendon]; ++w) {
    if (m->wrap_type[w] != mjWRAP_JOINT) {
      throw std::runtime_error("MuJoCo plant: only fixed tendons can couple joints");
    }
    a[static_cast<std::size_t>(m->wrap_objid[w])] += factor * m->wrap_prm[w];
  }
}

std::vector<Relation> joint_relations(const mjModel* m) {
  std::vector<Relation> relations;
  const auto joints = static_cast<std::size_t>(m->njnt);
  for (int e = 0; e < m->neq; ++e) {
    const mjtNum* data = m->eq_data + offset(e, mjNEQDATA);
    const int type = m->eq_type[e];
    if (type != mjEQ_JOINT && type != mjEQ_TENDON) continue;  // connect/weld: redundant loop statements
    if (data[2] != 0.0 || data[3] != 0.0 || data[4] != 0.0) {
      throw std::runtime_error("MuJoCo plant: a nonlinear joint coupling cannot be solved for reset");
    }
    // MuJoCo: (x1 - x1_0) = data[0] + data[1] (x2 - x2_0), x2 absent when obj2id < 0.
    Relation r{std::vector<double>(joints, 0.0), data[0]};
    const int one = m->eq_obj1id[e], two = m->eq_obj2id[e];
    if (type == mjEQ_JOINT) {
      r.a[static_cast<std::size_t>(one)] += 1.0;
      if (two >= 0) r.a[static_cast<std::size_t>(two)] -= data[1];
    } else {
      add_tendon(m, one, 1.0, r.a);
      if (two >= 0) add_tendon(m, two, -data[1], r.a);
    }
    relations.push_back(std::move(r));
  }
  return relations;
}

// Solves the normal equations N x = v (k x k, row-major) by Gaussian elimination with partial
// pivoting; false if N is singular (a joint the couplings do not determine).
bool solve_in_place(std::vector<double>& n, std::vector<double>& v) {
  const std::size_t k = v.size();
  double largest = 0.0;
  for (const double x : n) largest = std::max(largest, std::abs(x));
  const double tiny = 1e-12 * std::max(largest, 1.0);
  for (std::size_t c = 0; c < k; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < k; ++r) {
      if (std::abs(n[r * k + c]) > std::abs(n[pivot * k + c])) pivot = r;
    }
    if (std::abs(n[pivot * k + c]) < tiny) return false;
    for (std::size_t j = 0; j < k; ++j) std::swap(n[c * k + j], n[pivot * k + j]);
    std::swap(v[c], v[pivot]);
    for (std::size_t r = 0; r < k; ++r) {
      if (r == c) continue;
      const double f = n[r * k + c] / n[c * k + c];
      for (std::size_t j = c; j < k; ++j) n[r * k + j] -= f * n[c * k + j];
      v[r] -= f * v[c];
    }
  }
  for (std::size_t c = 0; c < k; ++c) v[c] /= n[c * k + c];
  return true;
}

class MujocoPlant final : public Plant {
 public:
  MujocoPlant(const PlantSettings& settings, ModelPtr model)
      : settings_(settings), model_(std::move(model)), data_(mj_makeData(model_.get())) {
    mjModel* m = model_.get();
    if (data_ == nullptr) throw std::runtime_error("MuJoCo plant: cannot allocate mjData");
    for (int j = 0; j < m->njnt; ++j) {
      if (m->jnt_type[j] != mjJNT_HINGE && m->jnt_type[j] != mjJNT_SLIDE) {
        throw std::runtime_error("MuJoCo plant: only hinge and slide joints are supported");
      }
    }
    find_coordinate_joints();
    relations_ = joint_relations(m);
    hook_geom_ = mj_name2id(m, mjOBJ_GEOM, kHookGeom);
    table_geom_ = settings_.table.present ? mj_name2id(m, mjOBJ_GEOM, kTableGeom) : -1;
    payload_body_ = mj_name2id(m, mjOBJ_BODY, kPayloadBody);

    // The couplings must determine every other joint: checked once here (it does not depend on q).
    std::vector<double> qpos(static_cast<std::size_t>(m->nq));
    complete_positions(Joints{}, qpos);

    if (!settings_.joint_friction) {
      std::fill_n(m->dof_frictionloss, m->nv, 0.0);
      std::fill_n(m->dof_damping, m->nv, 0.0);
    }
    add_joint_effects();
    for (int e = 0; e < m->neq; ++e) {
      m->eq_solref[offset(e, mjNREF)] = 2.0 * m->opt.timestep;
      m->eq_solref[offset(e, mjNREF) + 1] = 1.0;
      std::copy(kEqualityImpedance.begin(), kEqualityImpedance.end(), m->eq_solimp + offset(e, mjNIMP));
    }
    for (int v = 0; v < m->nv; ++v) {
      m->dof_solref[offset(v, mjNREF)] = 2.0 * m->opt.timestep;
      m->dof_solref[offset(v, mjNREF) + 1] = 1.0;
      std::copy(kFrictionImpedance.begin(), kFrictionImpedance.end(), m->dof_solimp + offset(v, mjNIMP));
    }
    reset(Joints{});
  }

  MujocoPlant(const MujocoPlant&) = delete;
  MujocoPlant& operator=(const MujocoPlant&) = delete;
  MujocoPlant(MujocoPlant&&) = delete;
  MujocoPlant& operator=(MujocoPlant&&) = delete;
  ~MujocoPlant() override = default;  // the deleters free mjData, then mjModel

  void reset(const Joints& q) override {
    mjModel* m = model_.get();
    mjData* d = data_.get();
    mj_resetData(m, d);  // time 0, velocities, applied forces, warm start
    set_payload_mass(0.0);
    attached_ = false;
    std::vector<double> qpos(static_cast<std::size_t>(m->nq));
    complete_positions(q, qpos);
    std::copy(qpos.begin(), qpos.end(), d->qpos);
    elapsed_ = 0.0;
    steps_ = 0;
    mj_forward(m, d);
  }

  void advance(const Joints& tau, double duration) override {
    if (!(duration >= 0.0)) throw std::invalid_argument("MuJoCo plant: negative or NaN duration");
    mjModel* m = model_.get();
    mjData* d = data_.get();
    // The coordinate's torque on the joint that carries it: power tau qd = tau_joint qd_joint
    // with qd_joint = scale qd, so tau_joint = tau / scale = tau * gear. The equality constraints
    // carry it to the rest of the mechanism.
    for (std::size_t i = 0; i < kDof; ++i) d->qfrc_applied[dof_[i]] = tau[i] * gear_[i];
    // Whole steps to the cumulative target time: round(duration * rate) per call on average,
    // without the rounding of many short calls adding up.
    elapsed_ += duration;
    const auto target = static_cast<long long>(std::llround(elapsed_ * settings_.rate));
    for (; steps_ < target; ++steps_) {
      if (stribeck_) follow_stribeck();
      mj_step(m, d);
    }
    // MuJoCo resets the state silently when it diverges; a simulation must not carry on.
    if (d->warning[mjWARN_BADQACC].number > 0 || d->warning[mjWARN_BADQPOS].number > 0 ||
        d->warning[mjWARN_BADQVEL].number > 0) {
      throw std::runtime_error("MuJoCo plant: the simulation diverged (bad qpos/qvel/qacc)");
    }
    // mj_step leaves contacts and constraint forces of the state before its last integration;
    // one mj_forward makes contact() describe the state q() returns. It writes no warm start,
    // so the trajectory does not change.
    mj_forward(m, d);
  }

  void set_payload_attached(bool attached) override {
    set_payload_mass(attached ? settings_.payload.mass : 0.0);
    attached_ = attached;
    mj_forward(model_.get(), data_.get());
  }

  [[nodiscard]] Joints q() const override {
    Joints out{};
    for (std::size_t i = 0; i < kDof; ++i) {
      const int j = joint_[i];
      const int adr = model_->jnt_qposadr[j];
      out[i] = (data_->qpos[adr] - model_->qpos0[adr]) * gear_[i];
    }
    return out;
  }

  [[nodiscard]] Joints qd() const override {
    Joints out{};
    for (std::size_t i = 0; i < kDof; ++i) out[i] = data_->qvel[dof_[i]] * gear_[i];
    return out;
  }

  [[nodiscard]] ContactState contact() const override {
    ContactState state;
    if (table_geom_ < 0) return state;
    for (int c = 0; c < data_->ncon; ++c) {
      const mjContact& k = data_->contact[c];
      const bool ours =
          (k.geom1 == hook_geom_ && k.geom2 == table_geom_) || (k.geom1 == table_geom_ && k.geom2 == hook_geom_);
      if (!ours || k.exclude != 0) continue;  // excluded: within a margin gap, no force (none here)
      state.active = true;
      std::array<mjtNum, 6> force{};
      mj_contactForce(model_.get(), data_.get(), c, force.data());  // contact frame: [0] is the normal
      state.normal_force += std::max(0.0, force[0]);
    }
    return state;
  }

  [[nodiscard]] bool payload_attached() const override { return attached_; }
  [[nodiscard]] std::string name() const override { return "mujoco"; }

  [[nodiscard]] double joint_position(const std::string& joint) const {
    const int j = mj_name2id(model_.get(), mjOBJ_JOINT, joint.c_str());
    if (j < 0) throw std::invalid_argument("MuJoCo plant: no joint " + joint);
    const int adr = model_->jnt_qposadr[j];
    return data_->qpos[adr] - model_->qpos0[adr];
  }

  [[nodiscard]] Vec3 hook_position() const {
    const mjtNum* x = data_->geom_xpos + offset(hook_geom_, 3);
    return {x[0], x[1], x[2]};
  }

 private:
  // The exporter's motor for coordinate i is named after it and sits on the joint that follows
  // that coordinate alone, with gear 1/scale.
  void find_coordinate_joints() {
    const mjModel* m = model_.get();
    for (std::size_t i = 0; i < kDof; ++i) {
      const char* coordinate = kraft::kCoordinateNames[i];
      const int motor = mj_name2id(m, mjOBJ_ACTUATOR, coordinate);
      if (motor < 0 || m->actuator_trntype[motor] != mjTRN_JOINT) {
        throw std::runtime_error(fmt::format("MuJoCo plant: the MJCF has no motor \"{}\" on a joint", coordinate));
      }
      joint_[i] = m->actuator_trnid[offset(motor, 2)];
      dof_[i] = m->jnt_dofadr[joint_[i]];
      gear_[i] = m->actuator_gear[offset(motor, 6)];  // nu x 6; [0] for a joint
      if (gear_[i] == 0.0) throw std::runtime_error(fmt::format("MuJoCo plant: motor \"{}\" has gear 0", coordinate));
    }
  }

  // qpos for coordinates q: the coordinate joints at q / gear, the others from the couplings
  // (least squares, which is exact when they are consistent, as the exporter writes them).
  void complete_positions(const Joints& q, std::vector<double>& qpos) const {
    const mjModel* m = model_.get();
    const auto n = static_cast<std::size_t>(m->njnt);
    std::vector<double> y(n, 0.0);  // qpos - qpos0, per joint (all scalar joints)
    std::vector<bool> known(n, false);
    for (std::size_t i = 0; i < kDof; ++i) {
      const auto j = static_cast<std::size_t>(joint_[i]);
      y[j] = q[i] / gear_[i];
      known[j] = true;
    }
    std::vector<std::size_t> unknown;
    for (std::size_t j = 0; j < n; ++j) {
      if (!known[j]) unknown.push_back(j);
    }
    const std::size_t k = unknown.size();
    if (k > 0) {
      std::vector<double> normal(k * k, 0.0), rhs(k, 0.0);
      for (const Relation& r : relations_) {
        double b = r.b;
        for (std::size_t j = 0; j < n; ++j) {
          if (known[j]) b -= r.a[j] * y[j];
        }
        for (std::size_t u = 0; u < k; ++u) {
          rhs[u] += r.a[unknown[u]] * b;
          for (std::size_t v = 0; v < k; ++v) normal[u * k + v] += r.a[unknown[u]] * r.a[unknown[v]];
        }
      }
      if (!solve_in_place(normal, rhs)) {
        throw std::runtime_error("MuJoCo plant: the joint couplings do not determine every joint from the coordinates");
      }
      for (std::size_t u = 0; u < k; ++u) y[unknown[u]] = rhs[u];
      for (const Relation& r : relations_) {
        double residual = -r.b;
        for (std::size_t j = 0; j < n; ++j) residual += r.a[j] * y[j];
        if (std::abs(residual) > 1e-9)
          throw std::runtime_error("MuJoCo plant: the joint couplings contradict each other");
      }
    }
    for (std::size_t j = 0; j < n; ++j) {
      const int adr = m->jnt_qposadr[j];
      qpos[static_cast<std::size_t>(adr)] = m->qpos0[adr] + y[j];
    }
  }

  // The hidden joint effects on the joint that carries each coordinate (joint = q / gear, so a
  // coordinate torque f is f * gear on the joint and a coefficient of qd is one of gear^2 qd_joint):
  // extra Coulomb friction as frictionloss (MuJoCo's dry friction, a constraint that also holds the
  // joint at rest), extra viscous friction as damping, extra reflected inertia as armature.
  void add_joint_effects() {
    mjModel* m = model_.get();
    const JointEffects& e = settings_.effects;
    for (std::size_t i = 0; i < kDof; ++i) {
      const int v = dof_[i];
      const double g = gear_[i];
      m->dof_frictionloss[v] += e.coulomb[i] * std::abs(g);
      m->dof_damping[v] += e.viscous[i] * g * g;
      m->dof_armature[v] += e.rotor_inertia[i] * g * g;
      frictionloss_[i] = m->dof_frictionloss[v];
      stribeck_ = stribeck_ || e.stribeck[i] > 0.0;
    }
  }

  // Stribeck friction as dry friction whose level follows the speed: before each step the
  // frictionloss is the Coulomb level plus the excess at the joint's current speed (MuJoCo keeps
  // treating it as a constraint, so the joint still sticks below the breakaway torque).
  void follow_stribeck() {
    mjModel* m = model_.get();
    for (std::size_t i = 0; i < kDof; ++i) {
      const int v = dof_[i];
      const double speed = data_->qvel[v] * gear_[i];
      m->dof_frictionloss[v] =
          frictionloss_[i] + stribeck_excess(settings_.effects, static_cast<int>(i), speed) * std::abs(gear_[i]);
    }
  }

  // The payload as a solid sphere at its body origin. MuJoCo caches the subtree masses at compile
  // time (mj_comPos divides by them), so the payload body's and all its ancestors' are updated too.
  void set_payload_mass(double mass) {
    mjModel* m = model_.get();
    const int p = payload_body_;
    const double delta = mass - m->body_mass[p];
    m->body_mass[p] = mass;
    const double r = settings_.payload.radius;
    std::fill_n(m->body_inertia + offset(p, 3), 3, 0.4 * mass * r * r);
    for (int b = p;; b = m->body_parentid[b]) {
      m->body_subtreemass[b] += delta;
      if (b == 0) break;
    }
  }

  PlantSettings settings_;
  ModelPtr model_;
  DataPtr data_;
  std::array<int, kDof> joint_{};            // the joint that carries coordinate i alone
  std::array<int, kDof> dof_{};              // its degree of freedom
  std::array<double, kDof> gear_{};          // joint = q / gear
  std::array<double, kDof> frictionloss_{};  // the coordinate joints' Coulomb level (joint units)
  bool stribeck_ = false;                    // some joint's frictionloss follows its speed
  std::vector<Relation> relations_;
  int hook_geom_ = -1;
  int table_geom_ = -1;
  int payload_body_ = -1;
  bool attached_ = false;
  double elapsed_ = 0.0;
  long long steps_ = 0;
};

}  // namespace

std::unique_ptr<Plant> make_mujoco_plant(const PlantSettings& settings, const std::string& mjcf_path) {
  if (!(settings.rate >= 1.0)) throw std::invalid_argument("MuJoCo plant: the rate must be at least 1 step/s");
  if (!settings.effects.all_rigid()) {
    throw std::invalid_argument(
        "MuJoCo plant: its joints are rigid (the exported MJCF has one hinge per joint), so backlash and joint "
        "elasticity need the rigid plant (--plant dyncc)");
  }
  ModelPtr model = load_model(augmented_mjcf(settings, mjcf_path), mjcf_path);
  return std::make_unique<MujocoPlant>(settings, std::move(model));
}

namespace {
const MujocoPlant& as_mujoco(const Plant& plant) {
  const auto* mujoco = dynamic_cast<const MujocoPlant*>(&plant);
  if (mujoco == nullptr) throw std::invalid_argument("not a MuJoCo plant: " + plant.name());
  return *mujoco;
}
}  // namespace

double mujoco_joint_position(const Plant& plant, const std::string& joint) {
  return as_mujoco(plant).joint_position(joint);
}

Vec3 mujoco_hook_position(const Plant& plant) { return as_mujoco(plant).hook_position(); }

}  // namespace dyncc::sim
