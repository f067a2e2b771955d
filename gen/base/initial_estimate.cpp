#include "base/initial_estimate.hpp"

#include <algorithm>
#include <map>
#include <unordered_map>

#include "sym/evaluate.hpp"
#include "sym/parse.hpp"

namespace dyncc::base {

InitialEstimate map_initial_estimate(const robot::RobotDescription& robot, const GroupingCheck& check) {
  const std::map<std::string, double> nominal_map = robot.nominal_values();
  const std::unordered_map<std::string, double> nominal(nominal_map.begin(), nominal_map.end());
  InitialEstimate result;
  Eigen::VectorXd user(static_cast<Eigen::Index>(check.names.size()));
  for (std::size_t i = 0; i < check.names.size(); ++i) {
    const std::string& name = check.description_names[i];
    const auto given = std::find_if(robot.initial_estimate.begin(), robot.initial_estimate.end(),
                                    [&](const robot::EstimateEntry& e) { return e.name == name; });
    if (given != robot.initial_estimate.end()) {
      user(static_cast<Eigen::Index>(i)) = given->value;
    } else {
      // The friction entry as written: a parameter (its nominal value) or a number.
      user(static_cast<Eigen::Index>(i)) = sym::evaluate(sym::parse_or_throw(name), nominal);
      result.from_nominal_values.push_back(name);
    }
  }
  result.base_values = check.to_base * user;
  return result;
}

}  // namespace dyncc::base
