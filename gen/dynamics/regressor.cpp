#include "dynamics/regressor.hpp"

#include "sym/diff.hpp"

namespace dyncc::dyn {

Regressor derive_regressor(const DynamicModel& model) {
  const std::size_t n = model.q.size();
  Regressor r;
  r.rigid_body_torque.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    sym::Expr tau = model.g[i];
    for (std::size_t j = 0; j < n; ++j) tau += model.H[i][j] * model.a[j] + model.C[i][j] * model.v[j];
    r.rigid_body_torque[i] = tau;
  }
  // One reverse sweep per row gives the derivative by every parameter at once. Friction
  // symbols do not occur in the rigid-body torque, so their columns come out 0.
  const std::vector<sym::Expr> symbols = model.params.symbols();
  r.rows.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.rows[i] = sym::gradient(r.rigid_body_torque[i], symbols);
  return r;
}

}  // namespace dyncc::dyn
