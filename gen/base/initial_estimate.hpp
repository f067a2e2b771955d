// The description's `initial_estimate:` (values of the user's groupings, e.g. the paper's
// p0..p20) mapped onto the identifiable base parameters, as a controller's first estimate.
//
// The mapping is exact and unique even when the grouping is redundant (the paper's is): the
// torque Y_user * p_user equals Y_base * (to_base * p_user) for every state, and the redundant
// directions of p_user do not change it. Parameters outside the groupings that the estimate
// does not give (friction, say) take their nominal values, and are listed.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "base/grouping_check.hpp"

namespace dyncc::base {

struct InitialEstimate {
  Eigen::VectorXd base_values;                   // parallel to BaseParameterSet::list
  std::vector<std::string> from_nominal_values;  // user-side names the estimate did not give
};

/// Needs a complete grouping check (check.complete) and robot.initial_estimate non-empty.
InitialEstimate map_initial_estimate(const robot::RobotDescription& robot, const GroupingCheck& check);

}  // namespace dyncc::base
