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
  const auto& params = model.params.list;
  r.rows.assign(n, std::vector<sym::Expr>(params.size()));
  for (std::size_t l = 0; l < params.size(); ++l) {
    if (params[l].kind == StandardKind::FC || params[l].kind == StandardKind::FV) continue;
    sym::Differentiator d(params[l].symbol);
    for (std::size_t i = 0; i < n; ++i) r.rows[i][l] = d(r.rigid_body_torque[i]);
  }
  return r;
}

}  // namespace dyncc::dyn
