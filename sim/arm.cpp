#include "arm.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace dyncc::sim {
namespace {

namespace gen = dyncc::generated::kraft_right;

int link_index(const char* name) {
  for (int i = 0; i < gen::kLinkParameters; ++i) {
    if (std::strcmp(gen::kLinkParameterNames[i], name) == 0) return i;
  }
  throw std::logic_error(std::string("the generated Kraft model has no link parameter ") + name);
}

using Mat3 = std::array<double, 9>;  // row-major

Vec3 rotate(const Mat3& r, const Vec3& v) {
  return {r[0] * v[0] + r[1] * v[1] + r[2] * v[2], r[3] * v[0] + r[4] * v[1] + r[5] * v[2],
          r[6] * v[0] + r[7] * v[1] + r[8] * v[2]};
}
Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) c[i * 3 + j] += a[i * 3 + k] * b[k * 3 + j];
    }
  }
  return c;
}
Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 subtract(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

struct Frame {
  Mat3 rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 origin{};
};

// One modified (Craig) D-H step: Rot_x(alpha) Trans_x(a) Rot_z(theta) Trans_z(d).
Frame modified_dh(const Frame& parent, double a, double alpha, double d, double theta) {
  const double ca = std::cos(alpha), sa = std::sin(alpha), ct = std::cos(theta), st = std::sin(theta);
  const Mat3 local{ct, -st, 0, st * ca, ct * ca, -sa, st * sa, ct * sa, ca};
  const Vec3 offset{a, -sa * d, ca * d};
  return {multiply(parent.rotation, local), add(parent.origin, rotate(parent.rotation, offset))};
}

// The D-H rows of robots/kraft.yaml from the base to the forearm (constants l2, b1, b2). The
// description is the source of these numbers; tests/sim_rigid_plant_test.cpp checks this chain
// against MuJoCo's forward kinematics of the MJCF that dyncc exports from the same description.
constexpr double kL2 = 0.180, kB1 = 0.075, kB2 = 0.130;
constexpr double kHalfPi = 1.57079632679489661923;

struct ForearmChain {
  Frame upper_arm, forearm;
};
ForearmChain chain(const Joints& q) {
  const Frame yaw = modified_dh(Frame{}, 0.0, 0.0, 0.0, q[0]);
  const Frame upper = modified_dh(yaw, 0.0, -kHalfPi, kB1, q[1]);
  return {upper, modified_dh(upper, kL2, 0.0, kB2 - kB1, q[2] - q[1])};
}

// Parallel-axis term m (|d|^2 1 - d d^T) of the inertia tensor.
Mat3 point_inertia(double m, const Vec3& d) {
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  Mat3 out{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out[i * 3 + j] = m * ((i == j ? dd : 0.0) - d[i] * d[j]);
  }
  return out;
}

}  // namespace

std::array<double, gen::kLinkParameters> link_parameters_with(const Payload& payload) {
  std::array<double, gen::kLinkParameters> link{};
  for (int i = 0; i < gen::kLinkParameters; ++i) link[i] = gen::kNominalLinkParameters[i];
  if (payload.mass <= 0.0) return link;
  const int im = link_index("m3"), ix = link_index("x3"), iy = link_index("y3"), iz = link_index("z3");
  // Inertia tensor entries of the forearm about its centre of mass (off-diagonals are tensor
  // entries, -integral(x y dm), as in the description).
  const std::array<int, 9> it{link_index("i3xx"), link_index("i3xy"), link_index("i3xz"),
                              link_index("i3xy"), link_index("i3yy"), link_index("i3yz"),
                              link_index("i3xz"), link_index("i3yz"), link_index("i3zz")};
  const double m3 = link[im], m = payload.mass, total = m3 + m;
  const Vec3 c3{link[ix], link[iy], link[iz]};
  const Vec3& r = payload.position_in_forearm;
  const Vec3 c{(m3 * c3[0] + m * r[0]) / total, (m3 * c3[1] + m * r[1]) / total, (m3 * c3[2] + m * r[2]) / total};
  const Mat3 forearm_shift = point_inertia(m3, subtract(c3, c));
  const Mat3 payload_shift = point_inertia(m, subtract(r, c));
  const double sphere = 0.4 * m * payload.radius * payload.radius;  // a solid sphere about its centre
  std::array<double, 9> tensor{};
  for (int k = 0; k < 9; ++k) {
    tensor[k] = link[it[k]] + forearm_shift[k] + payload_shift[k] + (k % 4 == 0 ? sphere : 0.0);
  }
  link[im] = total;
  link[ix] = c[0];
  link[iy] = c[1];
  link[iz] = c[2];
  for (const int k : {0, 1, 2, 4, 5, 8}) link[it[k]] = tensor[k];
  return link;
}

Parameters true_parameters(const Payload& payload) { return true_parameters(payload, {}); }

Parameters true_parameters(const Payload& payload, const std::array<bool, kDof>& motor_apart) {
  auto link = link_parameters_with(payload);
  for (int k = 0; k < kDof; ++k) {
    if (motor_apart[k]) link[link_index(("jm" + std::to_string(k + 1)).c_str())] = 0.0;
  }
  Parameters p{};
  gen::base_parameters_from_link<double>(link.data(), p.data());
  return p;
}

Joints rotor_inertias() {
  Joints out{};
  for (int k = 0; k < kDof; ++k)
    out[k] = gen::kNominalLinkParameters[link_index(("jm" + std::to_string(k + 1)).c_str())];
  return out;
}

Vec3 forearm_point(const Joints& q, const Vec3& point_in_forearm) {
  const Frame f = chain(q).forearm;
  return add(f.origin, rotate(f.rotation, point_in_forearm));
}

std::array<double, 9> forearm_point_jacobian(const Joints& q, const Vec3& point_in_forearm) {
  // Revolute axes z_i through origins o_i: dp/dtheta_i = z_i x (p - o_i). The forearm's D-H
  // angle is q3 - q2, so q2 turns the upper arm forward and the forearm back.
  const ForearmChain c = chain(q);
  const Vec3 p = add(c.forearm.origin, rotate(c.forearm.rotation, point_in_forearm));
  const Vec3 z{0, 0, 1};
  const Vec3 d1 = cross(z, p);
  const Vec3 upper = cross(rotate(c.upper_arm.rotation, z), subtract(p, c.upper_arm.origin));
  const Vec3 fore = cross(rotate(c.forearm.rotation, z), subtract(p, c.forearm.origin));
  std::array<double, 9> j{};
  for (int row = 0; row < 3; ++row) {
    j[row * 3 + 0] = d1[row];
    j[row * 3 + 1] = upper[row] - fore[row];
    j[row * 3 + 2] = fore[row];
  }
  return j;
}

int base_parameter_index(const char* name) {
  for (int i = 0; i < kParameters; ++i) {
    if (std::strcmp(Kraft::parameter_names[i], name) == 0) return i;
  }
  return -1;
}

}  // namespace dyncc::sim
