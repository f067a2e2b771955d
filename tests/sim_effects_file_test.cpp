// The effects file of `dyncc-sim excite` (sim/effects_file.cpp): every effect and parameter lands
// where the plants and the interface read it, defaults apply where a parameter is left out, and
// which plant can play what.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "effects_file.hpp"
#include "temp_path.hpp"

namespace dyncc::sim {
namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  auto path = dyncc::test::temp_path(name);
  std::ofstream(path) << text;
  return path;
}

TEST(EffectsFile, ReadsEveryEffectOntoItsJoints) {
  const auto path = write("every.json", R"({"effects": [
    {"effect": "coulomb_friction", "joints": [2], "parameters": {"fc": [0.1]}},
    {"effect": "viscous_friction", "joints": [1, 3], "parameters": {"fv": [0.02, 0.03]}},
    {"effect": "stribeck_friction", "joints": [3], "parameters": {"fs": [0.05], "vs": [0.2]}},
    {"effect": "stribeck_friction", "joints": [1], "parameters": {"fs": [0.04]}},
    {"effect": "rotor_inertia", "joints": [1], "parameters": {"ia": [0.01]}},
    {"effect": "torque_gain", "joints": [2], "parameters": {"gain": [1.1]}},
    {"effect": "position_offset", "joints": [3], "parameters": {"offset": [-0.02]}},
    {"effect": "backlash", "joints": [1], "parameters": {"width": [0.01]}},
    {"effect": "joint_elasticity", "joints": [1, 2], "parameters": {"stiffness": [80, 90], "damping": [0.5, 0]}},
    {"effect": "payload", "parameters": {"mass": 0.5, "position": [0.35, 0.01, 0]}},
    {"effect": "sensor_delay", "parameters": {"delay": 0.01}},
    {"effect": "contact", "parameters": {"height": -0.3, "friction": 0.4}}
  ]})");
  const HiddenEffects e = read_effects(path);
  const JointEffects& j = e.joints;
  EXPECT_EQ(j.coulomb, (Joints{0, 0.1, 0}));
  EXPECT_EQ(j.viscous, (Joints{0.02, 0, 0.03}));
  EXPECT_EQ(j.stribeck, (Joints{0.04, 0, 0.05}));
  EXPECT_EQ(j.stribeck_velocity, (Joints{0.1, 0.1, 0.2})) << "vs defaults to 0.1 rad/s";
  EXPECT_EQ(j.rotor_inertia, (Joints{0.01, 0, 0}));
  EXPECT_EQ(e.torque_gain, (Joints{1, 1.1, 1}));
  EXPECT_EQ(e.position_offset, (Joints{0, 0, -0.02}));
  EXPECT_EQ(j.transmission[0].width, 0.01);
  EXPECT_EQ(j.transmission[0].stiffness, 80) << "backlash and a spring on one joint: the spring holds the teeth";
  EXPECT_EQ(j.transmission[1].damping, 0);
  EXPECT_TRUE(j.transmission[2].rigid());
  EXPECT_EQ(e.payload, 0.5);
  EXPECT_EQ(e.payload_position, (Vec3{0.35, 0.01, 0}));
  EXPECT_EQ(e.sensor_delay, 0.01);
  EXPECT_TRUE(e.contact.present);
  EXPECT_EQ(e.contact.height, -0.3);
  EXPECT_EQ(e.contact.friction, 0.4);
  EXPECT_FALSE(e.contact.stiffness.has_value());
  EXPECT_EQ(e.listed.size(), 12U);
  EXPECT_TRUE(e.has("contact"));
  EXPECT_FALSE(e.has("none"));
}

TEST(EffectsFile, AnEmptyListIsTheDescriptionsArm) {
  const HiddenEffects e = read_effects(write("empty.json", R"({"effects": []})"));
  EXPECT_TRUE(e.listed.empty());
  EXPECT_TRUE(e.joints.all_rigid());
  EXPECT_EQ(e.payload, 0.0);
  EXPECT_FALSE(e.contact.present);
}

TEST(EffectsFile, RefusesRepeatsAndMisplacedFields) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"effects": [{"effect": "coulomb_friction", "joints": [1], "parameters": {"fc": [0.1]}},
                       {"effect": "coulomb_friction", "joints": [1], "parameters": {"fc": [0.2]}}]})",
       "effects[1].joints: coulomb_friction on joint 1 is already given"},
      {R"({"effects": [{"effect": "payload", "joints": [3], "parameters": {"mass": 1}}]})",
       "effects[0].joints: payload acts on the whole arm"},
      {R"({"effects": [{"effect": "torque_gain", "parameters": {"gain": [1.1]}}]})", "effects[0].joints: missing"},
      {R"({"effects": [{"effect": "torque_gain", "joints": [1, 1], "parameters": {"gain": [1, 1]}}]})",
       "effects[0].joints[1]: joint 1 is listed twice"},
      {R"({"effects": [{"effect": "sensor_delay", "parameters": {"delay": "10 ms"}}]})",
       "effects[0].parameters.delay: expected a number"},
      {R"({"effects": [{"effect": "contact", "parameter": {}}]})", "effects[0].parameter: unknown field"},
      {R"([1, 2])", "(top level): expected an object"},
      {R"({"effects": [{"effect": "contact", "parameters": {"height": -0.3, "depth": 0.01}}]})",
       "effects[0].parameters: give the table's height or its depth"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      read_effects(write("bad.json", text));
      ADD_FAILURE() << "accepted " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
  }
}

TEST(EffectsFile, TheMujocoPlantPlaysRigidJointsAndItsOwnContactOnly) {
  const auto contact =
      write("contact.json", R"({"effects": [{"effect": "contact", "parameters": {"stiffness": 1e4}}]})");
  const HiddenEffects e = read_effects(contact);
  EXPECT_NO_THROW(require_playable(e, PlantKind::dyncc, "contact.json"));
  EXPECT_THROW(require_playable(e, PlantKind::mujoco, "contact.json"), std::invalid_argument);
  const HiddenEffects spring = read_effects(
      write("spring.json",
            R"({"effects": [{"effect": "joint_elasticity", "joints": [2], "parameters": {"stiffness": [50]}}]})"));
  EXPECT_THROW(require_playable(spring, PlantKind::mujoco, "spring.json"), std::invalid_argument);
  EXPECT_NO_THROW(require_playable(spring, PlantKind::dyncc, "spring.json"));
}

}  // namespace
}  // namespace dyncc::sim
