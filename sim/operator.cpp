#include "operator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace dyncc::sim {
namespace {

// Poses of the task (rad). Hook heights (base frame, z up, hook 0.40 m along the forearm):
// home -0.14 m, above the payload -0.33 m, the payload's top (the contact plane) at -0.34 m,
// the press pose 0.05 rad "through" it (a light push), the lift pose -0.13 m: high enough that
// even the fixed-model arm, which sags under the payload, carries it clear of the table.
constexpr Joints kHome{0.0, -0.30, 0.50};
constexpr Joints kAbove{0.30, 0.0, 0.95};
constexpr Joints kPress{0.30, 0.0, 1.07};
constexpr Joints kLift{0.30, -0.35, 0.50};

}  // namespace

TaskScript TaskScript::paper() {
  TaskScript s;
  auto move = [&s](double start, double end, const Joints& from, const Joints& to) {
    s.segments_.push_back({start, end, from, to, -1, 0, 1});
  };
  auto sweep = [&s](double start, int joint, double amplitude, double period, int cycles) {
    s.segments_.push_back({start, start + period * cycles, kLift, kLift, joint, amplitude, period});
  };
  move(0.0, 1.0, kHome, kHome);
  move(1.0, 5.5, kHome, kAbove);    // reach towards the payload
  move(5.5, 8.0, kAbove, kPress);   // down onto it: contact at about 7 s
  move(8.0, 17.0, kPress, kPress);  // press on it
  move(17.0, 20.0, kPress, kLift);  // lift: the payload clears the table
  move(20.0, 23.0, kLift, kLift);   // hold
  sweep(23.0, 0, 0.50, 5.0, 2);     // joint 1 back and forth
  move(33.0, 35.0, kLift, kLift);
  sweep(35.0, 1, 0.22, 4.5, 2);  // joint 2
  move(44.0, 45.0, kLift, kLift);
  sweep(45.0, 2, 0.28, 4.5, 2);      // joint 3
  move(54.0, 57.0, kLift, kAbove);   // back over the table
  move(57.0, 59.5, kAbove, kPress);  // put the payload down
  move(59.5, 61.0, kPress, kPress);
  move(61.0, 64.0, kPress, kHome);  // away
  move(64.0, 66.0, kHome, kHome);
  return s;
}

TrajectoryPoint TaskScript::at(double t) const {
  TrajectoryPoint out;
  if (segments_.empty()) return out;
  const Segment* seg = &segments_.back();
  for (const Segment& candidate : segments_) {
    if (t < candidate.end) {
      seg = &candidate;
      break;
    }
  }
  const double span = seg->end - seg->start;
  const double tau = std::clamp(t - seg->start, 0.0, span);
  out.q = seg->from;
  if (seg->sweep_joint >= 0) {
    // a sin^3(w tau): starts and ends at rest with zero acceleration.
    const double w = 2 * std::numbers::pi / seg->period, s = std::sin(w * tau), c = std::cos(w * tau);
    const auto k = static_cast<std::size_t>(seg->sweep_joint);
    out.q[k] += seg->amplitude * s * s * s;
    out.qd[k] = seg->amplitude * 3 * s * s * c * w;
    out.qdd[k] = seg->amplitude * w * w * (6 * s * c * c - 3 * s * s * s);
    return out;
  }
  // Minimum-jerk blend: 10u^3 - 15u^4 + 6u^5.
  const double u = span > 0 ? tau / span : 1.0;
  const double shape = u * u * u * (10 - 15 * u + 6 * u * u);
  const double rate = span > 0 ? 30 * u * u * (1 - u) * (1 - u) / span : 0.0;
  const double curve = span > 0 ? 60 * u * (1 - u) * (1 - 2 * u) / (span * span) : 0.0;
  for (std::size_t k = 0; k < static_cast<std::size_t>(kDof); ++k) {
    const double delta = seg->to[k] - seg->from[k];
    out.q[k] += delta * shape;
    out.qd[k] = delta * rate;
    out.qdd[k] = delta * curve;
  }
  return out;
}

RecordedMaster RecordedMaster::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the master trajectory");
  auto fail = [&path](int line, int column, const std::string& what) {
    throw std::runtime_error(path + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + what);
  };
  std::string text;
  if (!std::getline(in, text)) fail(1, 1, "empty file: expected a header with t,q1,q2,q3");
  std::vector<std::string> header;
  {
    std::stringstream cells(text);
    std::string cell;
    while (std::getline(cells, cell, ',')) header.push_back(cell);
  }
  auto find = [&](const std::string& a, const std::string& b) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == a || header[i] == b) return static_cast<int>(i);
    }
    return -1;
  };
  const int time_column = find("t", "time");
  std::array<int, kDof> columns{};
  for (int k = 0; k < kDof; ++k) {
    const std::string name = fmt::format("q{}", k + 1);
    columns[static_cast<std::size_t>(k)] = find(name, fmt::format("master_{}", name));
    if (columns[static_cast<std::size_t>(k)] < 0)
      fail(1, 1, fmt::format("header has no column {} (or master_{})", name, name));
  }
  if (time_column < 0) fail(1, 1, "header has no column t");
  RecordedMaster m;
  int line = 1;
  while (std::getline(in, text)) {
    ++line;
    if (text.empty()) continue;
    std::vector<std::string> cells;
    std::vector<int> starts;
    std::size_t begin = 0;
    while (true) {
      const std::size_t comma = text.find(',', begin);
      starts.push_back(static_cast<int>(begin) + 1);
      cells.push_back(text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
      if (comma == std::string::npos) break;
      begin = comma + 1;
    }
    auto number = [&](int column, const std::string& field) {
      if (column >= static_cast<int>(cells.size()))
        fail(line, static_cast<int>(text.size()) + 1, "missing field " + field);
      const std::string& cell = cells[static_cast<std::size_t>(column)];
      std::size_t used = 0;
      double value = 0;
      try {
        value = std::stod(cell, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != cell.size() || !std::isfinite(value)) {
        fail(line, starts[static_cast<std::size_t>(column)],
             fmt::format("field {}: expected a finite number, got '{}'", field, cell));
      }
      return value;
    };
    const double t = number(time_column, "t");
    if (!m.t_.empty() && t <= m.t_.back())
      fail(line, starts[static_cast<std::size_t>(time_column)], "field t: time must increase");
    Joints q{};
    for (int k = 0; k < kDof; ++k)
      q[static_cast<std::size_t>(k)] = number(columns[static_cast<std::size_t>(k)],
                                              header[static_cast<std::size_t>(columns[static_cast<std::size_t>(k)])]);
    m.t_.push_back(t);
    m.q_.push_back(q);
  }
  if (m.t_.size() < 3) fail(line, 1, "expected at least three samples");
  return m;
}

TrajectoryPoint RecordedMaster::at(double t) const {
  TrajectoryPoint out;
  const auto n = t_.size();
  std::size_t i = 1;
  while (i + 1 < n && t_[i] < t) ++i;  // [i-1, i] brackets t (clamped)
  const double span = t_[i] - t_[i - 1];
  const double u = std::clamp((t - t_[i - 1]) / span, 0.0, 1.0);
  // Central differences at the bracketing samples, blended like the positions.
  auto rate_at = [&](std::size_t j) {
    const std::size_t a = j == 0 ? 0 : j - 1, b = j + 1 < n ? j + 1 : n - 1;
    Joints r{};
    for (std::size_t k = 0; k < static_cast<std::size_t>(kDof); ++k) r[k] = (q_[b][k] - q_[a][k]) / (t_[b] - t_[a]);
    return r;
  };
  const Joints r0 = rate_at(i - 1), r1 = rate_at(i);
  for (std::size_t k = 0; k < static_cast<std::size_t>(kDof); ++k) {
    out.q[k] = q_[i - 1][k] + u * (q_[i][k] - q_[i - 1][k]);
    out.qd[k] = r0[k] + u * (r1[k] - r0[k]);
    out.qdd[k] = (r1[k] - r0[k]) / span;
  }
  return out;
}

}  // namespace dyncc::sim
