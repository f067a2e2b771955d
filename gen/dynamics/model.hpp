// The dynamic model in the independent coordinates, derived by energy (Lagrange):
//   tau = H(q) qdd + C(q, qd) qd + tau_g(q) + FC sgn(qd) + FV qd
// H from the kinetic energy in barycentric form (linear in the standard parameters), C from
// Christoffel symbols of H, tau_g = dV/dq. Expressions contain the coordinates, the velocity
// symbols, the standard parameter symbols and the description's named constants.
#pragma once

#include <string>
#include <vector>

#include "dynamics/parameters.hpp"
#include "kinematics/kinematics.hpp"
#include "robot/description.hpp"

namespace dyncc::dyn {

using Matrix = std::vector<std::vector<sym::Expr>>;

struct DynamicModel {
  std::vector<sym::Expr> q;   // coordinates
  std::vector<sym::Expr> qd;  // their rates (qd1, ... ; named after the coordinates)
  std::vector<sym::Expr> v;   // reference velocity of the Slotine-Li regressor (qd_r)
  std::vector<sym::Expr> a;   // reference acceleration (qdd_r)
  StandardParameters params;
  Matrix H;                  // symmetric: H[i][j] and H[j][i] are the same node
  Matrix C;                  // Christoffel form: Hdot - 2C is skew-symmetric
  std::vector<sym::Expr> g;  // gravity torque
  sym::Expr kinetic_energy;
  sym::Expr potential_energy;
  std::vector<Matrix> christoffel;  // christoffel[k][i][j] = c_ijk, so C_ij = sum_k c_ijk qd_k
};

DynamicModel derive_model(const robot::RobotDescription& robot, const kin::Kinematics& kin);

/// Hdot = sum_k dH/dq_k * qd_k.
Matrix mass_matrix_rate(const DynamicModel& model);

}  // namespace dyncc::dyn
