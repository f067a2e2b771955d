// The payload candidates: a load on the payload link as a point mass m at a point c of the link
// frame, carried over the whole log or only while it was picked up (payload_window). Its standard
// parameters are m, m c and m (|c|^2 I - c c^T): linear in m and m c once the point is known, so
// the point is found by a few fixed-point passes (fit m and m c with the second moments of the
// last point, read c = m c / m) and the fit stays four columns, not the ten of a free rigid body,
// which would also absorb what is not a load (the link's own inertia errors are
// inertial_parameters).
#pragma once

#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/effects.hpp"

namespace dyncc::diagnose {

/// Appends the payload effects (conditioned, in the analysis rows) for the robot's payload link,
/// placed (the load's point, and the window of a load carried for a while) against `residual`
/// (A*n) with the `fixed` columns (A*n x m: the effects accepted before, none at the first step)
/// fitted beside the load's; the window is searched outside `rests` (A*n, 1 in a joint's holds:
/// in_long_rests).
void add_payload_effects(const Dataset& d, const pipeline::Derivation& derivation, const Eigen::VectorXd& rests,
                         const Eigen::VectorXd& residual, const Eigen::MatrixXd& fixed, std::vector<Effect>& out);

}  // namespace dyncc::diagnose
