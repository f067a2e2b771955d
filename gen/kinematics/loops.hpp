// Proving that declared loops close for every value of the coordinates.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "kinematics/kinematics.hpp"
#include "robot/description.hpp"

namespace dyncc::kin {

struct LoopCheck {
  std::string name;
  bool closed = false;                                 // proved: every component of the gap is identically zero
  bool proved = false;                                 // the verdict is a proof (the gap lies in the decidable class)
  std::array<double, 3> residual{};                    // gap at the sample point (point 2 - point 1, base frame)
  std::vector<std::pair<std::string, double>> sample;  // the sample coordinates
  std::string detail;
};

std::vector<LoopCheck> check_loops(const robot::RobotDescription& robot, const Kinematics& kin);

}  // namespace dyncc::kin
