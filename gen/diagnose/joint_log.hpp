// A log of a real (or simulated) arm, as the diagnosis reads it: CSV with a header, `t` (s, may be
// non-uniform), `q1..qn` (measured positions, the description's coordinate order), `tau1..taun`
// (applied joint torques), optionally `qd1..qdn` and `qdd1..qddn`; other columns are ignored.
// Foreign logs are renamed onto these names with a column map (`--map their=ours,...`).
#pragma once

#include <Eigen/Dense>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace dyncc::diagnose {

struct JointLog {
  std::string path;
  Eigen::VectorXd t;                   // N, strictly increasing
  Eigen::MatrixXd q, tau;              // N x n
  std::optional<Eigen::MatrixXd> qd;   // N x n, when logged
  std::optional<Eigen::MatrixXd> qdd;  // N x n, when logged
  [[nodiscard]] Eigen::Index samples() const { return t.size(); }
  [[nodiscard]] Eigen::Index joints() const { return q.cols(); }
};

/// A malformed or inconsistent log; `what()` is "file:line:column: error: ..." (exit code 2).
class LogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Column renames: their header name -> ours ("time" -> "t", "pos_1" -> "q1").
using ColumnMap = std::map<std::string, std::string>;

/// Parses "a=b,c=d"; throws LogError naming the entry for malformed text.
ColumnMap parse_column_map(const std::string& text);

inline constexpr Eigen::Index kMinimumSamples = 50;

/// Reads and checks a log for an arm with `joints` coordinates: every required column present
/// (and no q/tau columns beyond `joints`), every value a finite number, time strictly
/// increasing, at least kMinimumSamples rows.
JointLog read_joint_log(const std::string& path, Eigen::Index joints, const ColumnMap& renames = {});

}  // namespace dyncc::diagnose
