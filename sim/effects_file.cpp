#include "effects_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

namespace dyncc::sim {
namespace {

using nlohmann::json;

// What a parameter is: one value per listed joint (per_joint effects), or a fixed count of values
// for an effect on the whole arm (1: a number, 3: a vector).
struct ParameterSpec {
  const char* name;
  bool required;
  double lower, upper;  // allowed range
  bool lower_open;      // lower itself excluded
  const char* unit;
  int count = 1;  // for effects on the whole arm
};

struct EffectSpec {
  const char* name;
  bool per_joint;
  std::vector<ParameterSpec> parameters;
};

// The effects and their parameters. The names are the diagnosis' (gen/diagnose/effects.cpp: fc, fv,
// fs, ia, gain, offset, width, stiffness, delay, mass) so a truth and a verdict read alike. The
// ranges only refuse what is not physical or cannot be simulated (a delay longer than the
// controller could survive, a payload the actuators cannot lift).
const std::vector<EffectSpec>& specs() {
  static const std::vector<EffectSpec> all = {
      {"coulomb_friction", true, {{"fc", true, 0, 5, false, "N m"}}},
      {"viscous_friction", true, {{"fv", true, 0, 5, false, "N m s/rad"}}},
      {"stribeck_friction", true, {{"fs", true, 0, 5, false, "N m"}, {"vs", false, 0, 10, true, "rad/s"}}},
      {"rotor_inertia", true, {{"ia", true, 0, 1, false, "kg m^2"}}},
      {"torque_gain", true, {{"gain", true, 0, 10, true, ""}}},
      {"position_offset", true, {{"offset", true, -0.5, 0.5, false, "rad"}}},
      {"backlash", true, {{"width", true, 0, 0.2, true, "rad"}}},
      {"joint_elasticity",
       true,
       {{"stiffness", true, 0, 1e6, true, "N m/rad"}, {"damping", false, 0, 1e3, false, "N m s/rad"}}},
      {"payload", false, {{"mass", true, 0, 3, false, "kg"}, {"position", false, -1, 1, false, "m", 3}}},
      {"sensor_delay", false, {{"delay", true, 0, 0.5, false, "s"}}},
      {"contact",
       false,
       {{"height", false, -1, 1, false, "m"},
        {"depth", false, 0, 0.2, true, "m"},
        {"friction", false, 0, 2, false, ""},
        {"stiffness", false, 0, 1e7, true, "N/m"},
        {"damping", false, 0, 1e5, false, "N s/m"}}},
  };
  return all;
}

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw std::invalid_argument(fmt::format("{}: {}: {}", file_, field, what));
  }

  double number(const json& value, const std::string& field, const ParameterSpec& p) const {
    if (!value.is_number()) fail(field, fmt::format("expected a number, got {}", value.dump()));
    const double x = value.get<double>();
    const bool below = p.lower_open ? x <= p.lower : x < p.lower;
    if (!std::isfinite(x) || below || x > p.upper) {
      fail(field, fmt::format("{} is outside {}{}, {}]{}", value.dump(), p.lower_open ? "(" : "[", p.lower, p.upper,
                              *p.unit != 0 ? fmt::format(" {}", p.unit) : ""));
    }
    return x;
  }

  // The joints an effect acts on (0-based), from "joints": [1, 3].
  std::vector<int> joints(const json& entry, const std::string& at) const {
    const std::string field = at + ".joints";
    if (!entry.contains("joints")) fail(field, "missing (the joints it acts on, numbered from 1, e.g. [2])");
    const json& list = entry["joints"];
    if (!list.is_array() || list.empty()) fail(field, "expected a non-empty array of joint numbers, e.g. [2]");
    std::vector<int> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json& j = list[i];
      const std::string where = fmt::format("{}[{}]", field, i);
      if (!j.is_number_integer() || j.get<long long>() < 1 || j.get<long long>() > kDof) {
        fail(where, fmt::format("{} is not a joint of the Kraft arm (1..{})", j.dump(), kDof));
      }
      const int k = static_cast<int>(j.get<long long>()) - 1;
      for (const int seen : out) {
        if (seen == k) fail(where, fmt::format("joint {} is listed twice", k + 1));
      }
      out.push_back(k);
    }
    return out;
  }

  // name -> values (one per listed joint, or spec.count for an effect on the arm).
  std::map<std::string, std::vector<double>> parameters(const json& entry, const std::string& at,
                                                        const EffectSpec& spec, std::size_t joints) const {
    const std::string field = at + ".parameters";
    if (!entry.contains("parameters")) fail(field, fmt::format("missing (the parameters of {})", spec.name));
    const json& given = entry["parameters"];
    if (!given.is_object()) fail(field, "expected an object of named parameters");
    std::string known;
    for (const ParameterSpec& p : spec.parameters) known += fmt::format("{}{}", known.empty() ? "" : ", ", p.name);
    for (const auto& item : given.items()) {
      bool ok = false;
      for (const ParameterSpec& p : spec.parameters) ok = ok || item.key() == p.name;
      if (!ok) fail(field + "." + item.key(), fmt::format("{} has no such parameter (it has {})", spec.name, known));
    }
    std::map<std::string, std::vector<double>> out;
    for (const ParameterSpec& p : spec.parameters) {
      const std::string name = field + "." + p.name;
      if (!given.contains(p.name)) {
        if (p.required) fail(name, "missing");
        continue;
      }
      const json& value = given[p.name];
      const std::size_t count = spec.per_joint ? joints : static_cast<std::size_t>(p.count);
      std::vector<double>& values = out[p.name];
      if (count == 1 && !spec.per_joint) {
        values.push_back(number(value, name, p));
        continue;
      }
      if (!value.is_array() || value.size() != count) {
        fail(name, spec.per_joint ? fmt::format("expected an array of {} number(s), one per listed joint", count)
                                  : fmt::format("expected an array of {} numbers", count));
      }
      for (std::size_t i = 0; i < count; ++i) values.push_back(number(value[i], fmt::format("{}[{}]", name, i), p));
    }
    return out;
  }

 private:
  std::string file_;
};

json parse(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path.string() + ": cannot open the effects file");
  try {
    return json::parse(in);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(fmt::format("{}: malformed JSON: {}", path.string(), e.what()));
  }
}

// One parsed entry into the effects: per-joint values onto their joints, arm values as they are.
void apply(HiddenEffects& out, const std::string& effect, const std::vector<int>& joints,
           const std::map<std::string, std::vector<double>>& p) {
  auto value = [&p](const char* name, std::size_t i, double otherwise) {
    const auto it = p.find(name);
    return it == p.end() ? otherwise : it->second[i];
  };
  JointEffects& j = out.joints;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const auto k = static_cast<std::size_t>(joints[i]);
    if (effect == "coulomb_friction") j.coulomb[k] = value("fc", i, 0);
    if (effect == "viscous_friction") j.viscous[k] = value("fv", i, 0);
    if (effect == "stribeck_friction") {
      j.stribeck[k] = value("fs", i, 0);
      j.stribeck_velocity[k] = value("vs", i, j.stribeck_velocity[k]);
    }
    if (effect == "rotor_inertia") j.rotor_inertia[k] = value("ia", i, 0);
    if (effect == "torque_gain") out.torque_gain[k] = value("gain", i, 1);
    if (effect == "position_offset") out.position_offset[k] = value("offset", i, 0);
    if (effect == "backlash") j.transmission[k].width = value("width", i, 0);
    if (effect == "joint_elasticity") {
      j.transmission[k].stiffness = value("stiffness", i, 0);
      j.transmission[k].damping = value("damping", i, 0);
    }
  }
  if (effect == "payload") {
    out.payload = value("mass", 0, 0);
    for (std::size_t r = 0; r < 3; ++r) out.payload_position[r] = value("position", r, kHookInForearm[r]);
  }
  if (effect == "sensor_delay") out.sensor_delay = value("delay", 0, 0);
  if (effect == "contact") {
    out.contact.present = true;
    if (p.contains("height")) out.contact.height = value("height", 0, 0);
    if (p.contains("depth")) out.contact.depth = value("depth", 0, 0);
    out.contact.friction = value("friction", 0, out.contact.friction);
    if (p.contains("stiffness")) out.contact.stiffness = value("stiffness", 0, 0);
    if (p.contains("damping")) out.contact.damping = value("damping", 0, 0);
  }
}

}  // namespace

bool HiddenEffects::has(const std::string& effect) const {
  for (const Listed& l : listed) {
    if (l.effect == effect) return true;
  }
  return false;
}

std::vector<std::string> effect_names() {
  std::vector<std::string> out;
  for (const EffectSpec& s : specs()) out.emplace_back(s.name);
  return out;
}

HiddenEffects read_effects(const std::filesystem::path& path) {
  const Reader reader(path.string());
  const json doc = parse(path);
  if (!doc.is_object()) reader.fail("(top level)", "expected an object {\"effects\": [...]}");
  for (const auto& item : doc.items()) {
    if (item.key() != "effects") reader.fail(item.key(), "unknown field (the file has only \"effects\")");
  }
  if (!doc.contains("effects") || !doc["effects"].is_array()) {
    reader.fail("effects", "missing or not an array (write {\"effects\": []} for none)");
  }
  std::string known;
  for (const std::string& name : effect_names()) known += fmt::format("{}{}", known.empty() ? "" : ", ", name);
  HiddenEffects out;
  std::set<std::string> taken;  // "effect" for an arm effect, "effect/joint" for a joint's
  const json& list = doc["effects"];
  for (std::size_t e = 0; e < list.size(); ++e) {
    const std::string at = fmt::format("effects[{}]", e);
    const json& entry = list[e];
    if (!entry.is_object()) reader.fail(at, R"(expected an object {"effect": ..., "parameters": {...}})");
    for (const auto& item : entry.items()) {
      if (item.key() != "effect" && item.key() != "joints" && item.key() != "parameters") {
        reader.fail(at + "." + item.key(), "unknown field (an effect has effect, joints, parameters)");
      }
    }
    if (!entry.contains("effect") || !entry["effect"].is_string()) reader.fail(at + ".effect", "missing or not a name");
    const std::string name = entry["effect"].get<std::string>();
    const EffectSpec* spec = nullptr;
    for (const EffectSpec& s : specs()) spec = name == s.name ? &s : spec;
    if (spec == nullptr)
      reader.fail(at + ".effect", fmt::format("unknown effect '{}' (expected one of {})", name, known));
    std::vector<int> joints;
    if (spec->per_joint) {
      joints = reader.joints(entry, at);
    } else if (entry.contains("joints")) {
      reader.fail(at + ".joints", fmt::format("{} acts on the whole arm: leave out joints", name));
    }
    for (const int k : joints) {
      if (!taken.insert(fmt::format("{}/{}", name, k)).second) {
        reader.fail(at + ".joints", fmt::format("{} on joint {} is already given by an earlier entry", name, k + 1));
      }
    }
    if (!spec->per_joint && !taken.insert(name).second) {
      reader.fail(at + ".effect", fmt::format("{} is already given by an earlier entry", name));
    }
    const auto parameters = reader.parameters(entry, at, *spec, joints.size());
    if (parameters.contains("height") && parameters.contains("depth")) {
      reader.fail(at + ".parameters", "give the table's height or its depth under the reference, not both");
    }
    apply(out, name, joints, parameters);
    out.listed.push_back({name, e});
  }
  return out;
}

void require_playable(const HiddenEffects& effects, PlantKind plant, const std::string& file) {
  if (plant != PlantKind::mujoco) return;
  for (const HiddenEffects::Listed& l : effects.listed) {
    const std::string at = fmt::format("{}: effects[{}]", file, l.index);
    if (l.effect == "backlash" || l.effect == "joint_elasticity") {
      throw std::invalid_argument(fmt::format(
          "{}: {} is not possible on the MuJoCo plant: its joints are rigid (one hinge per joint in the exported "
          "MJCF, no motor body apart from the link); use --plant dyncc",
          at, l.effect));
    }
    if (l.effect == "contact" && (effects.contact.stiffness || effects.contact.damping)) {
      throw std::invalid_argument(fmt::format(
          "{}.parameters: contact stiffness and damping set the rigid plant's penalty contact; the MuJoCo plant uses "
          "its own soft contact (solref 5 ms, critically damped): leave them out or use --plant dyncc",
          at));
    }
  }
}

}  // namespace dyncc::sim
