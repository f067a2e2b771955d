// placeholder: the MuJoCo plant is being written in this issue.
#include <stdexcept>

#include "plant.hpp"

namespace dyncc::sim {
std::unique_ptr<Plant> make_mujoco_plant(const PlantSettings& /*settings*/, const std::string& /*mjcf_path*/) {
  throw std::runtime_error("the MuJoCo plant is not built yet");
}
}  // namespace dyncc::sim
