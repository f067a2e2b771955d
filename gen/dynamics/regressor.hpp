// The Slotine-Li regressor: Y(q, qd, v, a) p = H a + C v + tau_g + FC sgn(qd) + FV v.
//
// Columns follow the standard parameters. Inertial and rotor columns are exact expressions
// (derivatives of the torque with respect to each parameter, which the model is linear in);
// friction columns are sgn(qd_k) and v_k on row k, applied numerically since sgn is not an
// expression. The identification form is the same with v = qd and a = qdd.
#pragma once

#include <vector>

#include "dynamics/model.hpp"

namespace dyncc::dyn {

struct Regressor {
  /// rows[i][l]: d tau_i / d p_l for inertial and rotor parameters; 0 for friction columns.
  Matrix rows;
  /// tau_i = H a + C v + tau_g (without friction), linear in the parameters.
  std::vector<sym::Expr> rigid_body_torque;
};

Regressor derive_regressor(const DynamicModel& model);

}  // namespace dyncc::dyn
