// The true Kraft slave arm that the simulation plays: its geometry (the hook on the forearm), the
// payload and what the payload does to the base parameters. The dynamics themselves are the
// generated model (generated/kraft): the plant never re-derives them.
#pragma once

#include <array>

#include "dyncc/runtime/small_matrix.hpp"
#include "kraft/model.hpp"

namespace dyncc::sim {

using Kraft = dyncc::generated::kraft_right::Model;
inline constexpr int kDof = Kraft::dof;
inline constexpr int kParameters = Kraft::parameters;
using Joints = std::array<double, kDof>;
using Vec3 = std::array<double, 3>;
using Parameters = std::array<double, kParameters>;
using MassMatrix = runtime::Matrix<double, kDof>;  // row-major

/// A point mass (a small sphere) hung on the hook.
struct Payload {
  double mass = 0.0;                     // kg; 0 = no payload
  Vec3 position_in_forearm{0.40, 0, 0};  // m, in the forearm's D-H frame (x along the forearm)
  double radius = 0.03;                  // m, for its own inertia
};

/// Where the hook sits on the forearm (m, forearm D-H frame): the clamp at the wrist.
inline constexpr Vec3 kHookInForearm{0.40, 0.0, 0.0};

/// The description's nominal link parameters (kLinkParameterNames order) with the payload merged
/// into the forearm (mass, first moment, inertia about the new centre of mass).
std::array<double, dyncc::generated::kraft_right::kLinkParameters> link_parameters_with(const Payload& payload);

/// The true base parameters of the arm carrying `payload`, computed by the generated
/// base_parameters_from_link from link_parameters_with (payload.mass = 0: the nominal ones).
Parameters true_parameters(const Payload& payload);

/// The same with the reflected rotor inertia (jm1..jm3) left out of the joints for which
/// `motor_apart` is true: what the links alone are when those motors are bodies of their own
/// (a transmission that is not rigid, sim/joint_effects.hpp).
Parameters true_parameters(const Payload& payload, const std::array<bool, kDof>& motor_apart);

/// The description's reflected rotor inertias jm1..jm3 (kg m^2), about each coordinate.
Joints rotor_inertias();

/// Position (m, base frame, z up) of a point given in the forearm's D-H frame, at q.
Vec3 forearm_point(const Joints& q, const Vec3& point_in_forearm);

/// d forearm_point / dq (3 x 3 row-major: rows x, y, z; columns q1..q3).
std::array<double, 9> forearm_point_jacobian(const Joints& q, const Vec3& point_in_forearm);

/// Index of a base parameter by name (kBaseParameterNames), -1 if absent.
int base_parameter_index(const char* name);

}  // namespace dyncc::sim
