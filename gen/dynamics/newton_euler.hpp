// The same rigid-body torque as the Lagrangian model, by the recursive Newton-Euler algorithm,
// symbolically: tau(q, qd, qdd) = H qdd + C qd + tau_g + rotor inertia, in the standard
// parameter symbols.
//
// Why a second formulation in the generator: the energy route gives H, C and the Christoffel
// symbols the proofs need, but its expressions are sums over all link pairs; Newton-Euler
// shares each link's velocities, accelerations and forces between all joints, so inverse
// dynamics, gravity and the identification regressor come out several times smaller as code.
// The code generator lowers both and emits the cheaper program; the tests check that the two
// agree to rounding.
//
// Velocities, accelerations, forces and moments are propagated in link coordinates (Craig's
// outward/inward recursion, for both D-H conventions, revolute and prismatic joints). Closed
// chains listed as a tree with joint variables that are affine in the coordinates
// (theta = offset + sum_k c_k q_k, as the Kraft arm's parallelogram) are covered exactly: the
// generalised force is tau_k = sum_links c_{link,k} * joint force (virtual work). Other joint
// maps are not affine and get no Newton-Euler form.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "dynamics/model.hpp"
#include "robot/description.hpp"
#include "sym/bindings.hpp"

namespace dyncc::dyn {

struct NewtonEulerInputs {
  std::span<const sym::Expr> qd;   // joint-space rates
  std::span<const sym::Expr> qdd;  // joint-space accelerations
  bool gravity = true;             // include tau_g (the base accelerates upwards by -g)
  /// Value of each standard parameter (parallel to model.params.list); empty: their symbols.
  std::span<const sym::Expr> parameters = {};
  /// When given, every link's velocities, accelerations, forces and moments are bound to fresh
  /// symbols (see sym/bindings.hpp): compact code, but not for differentiation.
  sym::Bindings* bindings = nullptr;
};

/// tau per coordinate, in the model's coordinates and standard parameter symbols, with the
/// description's constants substituted by their values. nullopt when a joint variable is not
/// affine in the coordinates.
std::optional<std::vector<sym::Expr>> newton_euler_torque(const robot::RobotDescription& robot,
                                                          const DynamicModel& model, const NewtonEulerInputs& in);

/// H(q) by the composite-rigid-body algorithm (each subtree's mass, first moment and inertia
/// about its root's origin, accumulated leaf to root; the force a unit acceleration of a joint
/// needs, carried up to every ancestor joint), mapped onto the coordinates as G^T H_tree G
/// plus the rotor inertias. Same conditions and parameter symbols as newton_euler_torque.
std::optional<Matrix> composite_rigid_body_mass_matrix(const robot::RobotDescription& robot, const DynamicModel& model,
                                                       std::span<const sym::Expr> parameters = {},
                                                       sym::Bindings* bindings = nullptr);

}  // namespace dyncc::dyn
