#include "diagnose/joint_log.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>

namespace dyncc::diagnose {
namespace {

struct Cell {
  std::string text;
  int column = 1;  // 1-based character column where the cell starts
};

std::vector<Cell> split(const std::string& line) {
  std::vector<Cell> cells;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    std::string text = line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    // Tolerate spaces and a trailing carriage return around a cell (Windows logs, "1, 2").
    const auto first = text.find_first_not_of(" \t\r");
    const auto last = text.find_last_not_of(" \t\r");
    text = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
    cells.push_back({text, static_cast<int>(begin) + 1 + static_cast<int>(first == std::string::npos ? 0 : first)});
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return cells;
}

[[noreturn]] void fail(const std::string& path, int line, int column, const std::string& what) {
  throw LogError(fmt::format("{}:{}:{}: error: {}", path, line, column, what));
}

}  // namespace

ColumnMap parse_column_map(const std::string& text) {
  ColumnMap out;
  if (text.empty()) return out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = text.find(',', begin);
    const std::string entry = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    const std::size_t equals = entry.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == entry.size()) {
      throw LogError(fmt::format("--map: '{}': expected THEIR_NAME=OUR_NAME (e.g. time=t,pos_1=q1)", entry));
    }
    out[entry.substr(0, equals)] = entry.substr(equals + 1);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return out;
}

JointLog read_joint_log(const std::string& path, Eigen::Index joints, const ColumnMap& renames) {
  std::ifstream in(path);
  if (!in) throw LogError(fmt::format("{}: error: cannot open the log", path));
  std::string line;
  if (!std::getline(in, line)) fail(path, 1, 1, "empty file: expected a header with t, q1.., tau1..");
  std::vector<Cell> header = split(line);
  std::map<std::string, std::size_t> index;
  for (std::size_t c = 0; c < header.size(); ++c) {
    const auto renamed = renames.find(header[c].text);
    const std::string name = renamed == renames.end() ? header[c].text : renamed->second;
    if (!index.emplace(name, c).second) fail(path, 1, header[c].column, fmt::format("column '{}' appears twice", name));
  }
  // Required columns, and none beyond the robot's joint count (a log of another arm).
  auto require = [&](const std::string& name, const std::string& what) {
    const auto it = index.find(name);
    if (it == index.end()) fail(path, 1, 1, fmt::format("missing column '{}' ({})", name, what));
    return it->second;
  };
  const std::size_t t_column = require("t", "time in seconds");
  std::vector<std::size_t> q_columns, tau_columns, qd_columns, qdd_columns;
  for (Eigen::Index k = 1; k <= joints; ++k) {
    q_columns.push_back(require(fmt::format("q{}", k), fmt::format("position of joint {}", k)));
    tau_columns.push_back(require(fmt::format("tau{}", k), fmt::format("torque of joint {}", k)));
    if (index.contains(fmt::format("qd{}", k))) qd_columns.push_back(index[fmt::format("qd{}", k)]);
    if (index.contains(fmt::format("qdd{}", k))) qdd_columns.push_back(index[fmt::format("qdd{}", k)]);
  }
  for (const char* prefix : {"q", "tau"}) {
    const std::string extra = fmt::format("{}{}", prefix, joints + 1);
    if (index.contains(extra)) {
      fail(path, 1, header[index[extra]].column,
           fmt::format("column '{}': the log has more joints than the description's {}", extra, joints));
    }
  }
  for (const auto* group : {&qd_columns, &qdd_columns}) {
    if (!group->empty() && static_cast<Eigen::Index>(group->size()) != joints) {
      fail(path, 1, 1,
           fmt::format("optional {} columns are given for some joints only ({} of {})",
                       group == &qd_columns ? "qd" : "qdd", group->size(), joints));
    }
  }

  std::vector<double> values;  // row-major, header order
  const std::size_t width = header.size();
  std::vector<bool> used(width, false);  // the columns the diagnosis reads (others may hold text)
  used[t_column] = true;
  for (const auto* group : {&q_columns, &tau_columns, &qd_columns, &qdd_columns}) {
    for (const std::size_t c : *group) used[c] = true;
  }
  int line_number = 1;
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<Cell> cells = split(line);
    if (cells.size() < width) {
      fail(path, line_number, static_cast<int>(line.size()) + 1,
           fmt::format("{} fields, the header has {}", cells.size(), width));
    }
    for (std::size_t c = 0; c < width; ++c) {
      const Cell& cell = cells[c];
      double v = 0;
      const char* end = cell.text.data() + cell.text.size();
      const auto [ptr, error] = std::from_chars(cell.text.data(), end, v);
      if (used[c] && (error != std::errc() || ptr != end || !std::isfinite(v))) {
        fail(path, line_number, cell.column,
             fmt::format("column '{}': expected a finite number, got '{}'", header[c].text, cell.text));
      }
      values.push_back(used[c] ? v : 0.0);
    }
    if (rows > 0 && values[rows * width + t_column] <= values[(rows - 1) * width + t_column]) {
      fail(path, line_number, cells[t_column].column,
           fmt::format("column '{}': time must increase ({} after {})", header[t_column].text,
                       values[rows * width + t_column], values[(rows - 1) * width + t_column]));
    }
    ++rows;
  }
  if (static_cast<Eigen::Index>(rows) < kMinimumSamples) {
    fail(path, line_number, 1, fmt::format("{} samples; the diagnosis needs at least {}", rows, kMinimumSamples));
  }
  JointLog log;
  log.path = path;
  const auto n = static_cast<Eigen::Index>(rows);
  log.t.resize(n);
  log.q.resize(n, joints);
  log.tau.resize(n, joints);
  if (!qd_columns.empty()) log.qd = Eigen::MatrixXd(n, joints);
  if (!qdd_columns.empty()) log.qdd = Eigen::MatrixXd(n, joints);
  for (Eigen::Index r = 0; r < n; ++r) {
    const double* row = values.data() + static_cast<std::size_t>(r) * width;
    log.t[r] = row[t_column];
    for (Eigen::Index k = 0; k < joints; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      log.q(r, k) = row[q_columns[kk]];
      log.tau(r, k) = row[tau_columns[kk]];
      if (log.qd) (*log.qd)(r, k) = row[qd_columns[kk]];
      if (log.qdd) (*log.qdd)(r, k) = row[qdd_columns[kk]];
    }
  }
  return log;
}

}  // namespace dyncc::diagnose
