// The payload candidates: a load on the payload link as a point mass m at a point c of the link
// frame, carried over the whole log or only while it was picked up (payload_window). Its standard
// parameters are m, m c and m (|c|^2 I - c c^T): linear in m and m c once the point is known, so
// the point is found by a few fixed-point passes (fit m and m c with the second moments of the
// last point, read c = m c / m) and the fit stays four columns, not the ten of a free rigid body,
// which would also absorb what is not a load (the link's own inertia errors are
// inertial_parameters).
#pragma once

#include <array>
#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/effects.hpp"
#include "diagnose/payload_window.hpp"

namespace dyncc::diagnose {

/// Places the payload candidates for the robot's payload link: its columns conditioned once,
/// then, for each residual the load is placed against, the effects (conditioned, in the analysis
/// rows). Constant once made; `d` must outlive it.
class PayloadPlacer {
 public:
  /// The window of a load carried for a while is searched outside `rests` (A*n, 1 in a joint's
  /// holds: in_long_rests).
  PayloadPlacer(const Dataset& d, const pipeline::Derivation& derivation, const Eigen::VectorXd& rests);

  /// Appends the load over the whole log and, when one is found, while carried, each placed (its
  /// point, and the window) against `residual` (A*n) with the `fixed` columns (A*n x m: the effects
  /// accepted before it; none, 0 columns, at the first step) fitted beside the load's.
  void add_effects(const Eigen::VectorXd& residual, const Eigen::MatrixXd& fixed, std::vector<Effect>& out) const;

 private:
  // A placed load's effect told what its fitted values mean in the standard parameters (at its
  // point, over `window`'s rows or everywhere).
  void set_standard_change(Effect& e, const Eigen::Vector3d& point, const PayloadWindow* window) const;

  const Dataset& d_;
  std::array<int, 10> of_{};  // the payload link's standard parameters' indices (-1: none)
  Eigen::Index parameter_count_ = 0;
  Eigen::MatrixXd all_;  // the link's ten standard columns (evaluation rows); empty: no payload link
  Eigen::MatrixXd conditioned_;
  Eigen::VectorXd weight_, scored_;
  std::array<bool, 3> resolved_{};  // the first moments the data resolves
};

}  // namespace dyncc::diagnose
