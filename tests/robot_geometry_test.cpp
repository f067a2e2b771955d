// The shipped descriptions mean what their comments say: numeric forward kinematics straight
// from the D-H fields (independent of the kinematics stage) checks frames and loop closure.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "robot/load.hpp"
#include "sym/evaluate.hpp"

namespace dyncc::robot {
namespace {

using Matrix4 = std::array<std::array<double, 4>, 4>;
using Vector3 = std::array<double, 3>;

Matrix4 multiply(const Matrix4& a, const Matrix4& b) {
  Matrix4 c{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

Matrix4 rot_x(double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return Matrix4{{{1, 0, 0, 0}, {0, c, -s, 0}, {0, s, c, 0}, {0, 0, 0, 1}}};
}
Matrix4 rot_z(double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return Matrix4{{{c, -s, 0, 0}, {s, c, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
}
Matrix4 translate(double x, double y, double z) {
  return Matrix4{{{1, 0, 0, x}, {0, 1, 0, y}, {0, 0, 1, z}, {0, 0, 0, 1}}};
}

class Geometry {
 public:
  Geometry(const RobotDescription& robot, const std::vector<double>& q) : robot_(robot) {
    for (const auto& [name, value] : robot.constant_doubles()) values_[name] = value;
    for (std::size_t i = 0; i < q.size(); ++i) values_[robot.coordinates[i].name()] = q[i];
    for (std::size_t i = 0; i < robot.links.size(); ++i) world_.push_back(link_to_world(i));
  }

  [[nodiscard]] Vector3 point(int link, const std::array<sym::Expr, 3>& at) const {
    const Matrix4 frame = link < 0 ? translate(0, 0, 0) : world_[static_cast<std::size_t>(link)];
    const double local[3] = {value(at[0]), value(at[1]), value(at[2])};
    Vector3 result{};
    for (int i = 0; i < 3; ++i)
      result[i] = frame[i][3] + frame[i][0] * local[0] + frame[i][1] * local[1] + frame[i][2] * local[2];
    return result;
  }
  [[nodiscard]] Vector3 axis(int link, int column) const {
    const Matrix4& frame = world_[static_cast<std::size_t>(link)];
    return {frame[0][column], frame[1][column], frame[2][column]};
  }
  [[nodiscard]] Vector3 origin(int link) const { return axis(link, 3); }

 private:
  [[nodiscard]] double value(sym::Expr e) const { return sym::evaluate(e, values_); }

  Matrix4 link_to_world(std::size_t index) const {
    const Link& link = robot_.links[index];
    const double a = value(link.a);
    const double alpha = value(link.alpha);
    const double d = value(link.d);
    const double theta = value(link.theta);
    const Matrix4 local =
        robot_.convention == Convention::Modified
            ? multiply(multiply(rot_x(alpha), translate(a, 0, 0)), multiply(rot_z(theta), translate(0, 0, d)))
            : multiply(multiply(rot_z(theta), translate(0, 0, d)), multiply(translate(a, 0, 0), rot_x(alpha)));
    if (link.parent < 0) return local;
    return multiply(world_[static_cast<std::size_t>(link.parent)], local);
  }

  const RobotDescription& robot_;
  std::unordered_map<std::string, double> values_;
  std::vector<Matrix4> world_;
};

double distance(const Vector3& a, const Vector3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

RobotDescription load(const std::string& file) {
  LoadResult result = load_robot(std::string(DYNCC_SOURCE_DIR) + "/robots/" + file);
  if (!result.ok()) throw std::runtime_error("cannot load " + file);
  return std::move(*result.robot);
}

TEST(RobotGeometry, KraftParallelogramClosesAndKeepsLinksParallel) {
  const RobotDescription robot = load("kraft.yaml");
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  const double b1 = 0.075;
  const double b2 = 0.130;
  const double b3 = 0.10;
  for (int sample = 0; sample < 50; ++sample) {
    const std::vector<double> q = {angle(random), angle(random), angle(random)};
    const Geometry g(robot, q);
    const Loop& loop = robot.loops.at(0);
    EXPECT_LT(distance(g.point(loop.points[0].link, loop.points[0].at),
                       g.point(loop.points[1].link, loop.points[1].at)),
              1e-12);
    // ERRATA 6-7: forearm at absolute angle q3 (parallel to the crank), coupler parallel to the upper arm.
    const int upper_arm = 1;
    const int forearm = 2;
    const int crank = 3;
    const int coupler = 4;
    EXPECT_LT(distance(g.axis(forearm, 0), g.axis(crank, 0)), 1e-12);
    EXPECT_LT(distance(g.axis(coupler, 0), g.axis(upper_arm, 0)), 1e-12);
    // Elevation: the upper arm's x axis points down for positive q2 (it is (c2, 0, -s2) in the yaw frame).
    EXPECT_NEAR(g.axis(upper_arm, 0)[2], -std::sin(q[1]), 1e-12);
    EXPECT_NEAR(g.axis(forearm, 0)[2], -std::sin(q[2]), 1e-12);
    // Lateral planes along the shoulder axis (the yaw frame's y axis): b1, b2, b3, b1.
    const Vector3 lateral = g.axis(0, 1);
    const auto offset = [&](int link) {
      const Vector3 o = g.origin(link);
      return o[0] * lateral[0] + o[1] * lateral[1] + o[2] * lateral[2];
    };
    EXPECT_NEAR(offset(upper_arm), b1, 1e-12);
    EXPECT_NEAR(offset(forearm), b2, 1e-12);
    EXPECT_NEAR(offset(crank), b3, 1e-12);
    EXPECT_NEAR(offset(coupler), b1, 1e-12);
  }
}

TEST(RobotGeometry, PlanarTwoLinkTipFollowsTheTextbook) {
  const RobotDescription robot = load("planar_2link.yaml");
  const double l1 = 1.0;
  const double l2 = 0.8;
  for (const auto& q : std::vector<std::vector<double>>{{0.3, -0.7}, {1.2, 0.4}, {-2.0, 2.5}}) {
    const Geometry g(robot, q);
    const Vector3 tip = g.origin(1);
    EXPECT_NEAR(tip[0], l1 * std::cos(q[0]) + l2 * std::cos(q[0] + q[1]), 1e-12);
    EXPECT_NEAR(tip[1], l1 * std::sin(q[0]) + l2 * std::sin(q[0] + q[1]), 1e-12);
    EXPECT_NEAR(tip[2], 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace dyncc::robot
