#include "diagnose/long_rests.hpp"

#include <cstddef>

namespace dyncc::diagnose {

Eigen::VectorXd in_long_rests(const Dataset& d, const Eigen::VectorXd& away) {
  const Eigen::Index rows = d.rows(), n = d.n;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(rows * n);
  auto log_of = [&](Eigen::Index r) { return d.analysis_log[static_cast<std::size_t>(r)]; };
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index begin = 0; begin < rows;) {
      if (away[begin * n + j] > 0) {
        ++begin;
        continue;
      }
      Eigen::Index end = begin;
      while (end < rows && away[end * n + j] == 0 && log_of(end) == log_of(begin)) ++end;
      if (d.analysis_t[end - 1] - d.analysis_t[begin] + d.step >= kLongRest) {
        for (Eigen::Index r = begin; r < end; ++r) out[r * n + j] = 1;
      }
      begin = end;
    }
  }
  return out;
}

}  // namespace dyncc::diagnose
