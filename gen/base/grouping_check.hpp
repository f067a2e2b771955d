// Checking a user's own parameter grouping (the description's `base_parameters:`, e.g. the
// paper's p0..p14) against the identifiable space found by find_base_parameters().
//
// Each user parameter must be a linear combination of the standard parameters. The grouping
// must reach every identifiable combination (else: an error naming what is missing). It may be
// redundant, as the paper's is: then the directions that do not change the torque are named, as
// "p0, p3, p4, p5, p7 enter only as p0 + p3 + p4, p5 - p3, p7 - p4". Friction parameters the
// grouping does not mention are added as they are.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "base/base_parameters.hpp"

namespace dyncc::base {

struct GroupingCheck {
  std::vector<std::string> names;                   // the user's names, then any friction parameters added
  std::vector<std::string> description_names;       // parallel: the grouping's name, or the friction
                                                    // entry as written (fc1, or a number)
  Eigen::MatrixXd rows;                             // user parameter = rows * standard parameters
  Eigen::MatrixXd to_base;                          // base = to_base * user values (valid when complete)
  bool complete = false;                            // spans the identifiable space
  std::vector<std::string> errors;                  // one per problem, readable
  std::vector<std::string> warnings;                // redundancy, parts without effect, additions
  std::vector<std::string> redundant_directions;    // e.g. "p3 - p0 - p4" (null space of to_base)
  std::vector<std::string> effective_combinations;  // e.g. "p0 + p3 + p4"
  std::vector<std::string> involved;                // parameters that enter only in combination
};

GroupingCheck check_grouping(const robot::RobotDescription& robot, const dyn::DynamicModel& model,
                             const BaseParameterSet& base);

}  // namespace dyncc::base
