// The logged torque's noise where effect columns are made from the logged torque itself: a
// spring's shift is the torque its transmission carries (shifted_positions.hpp), so its columns
// carry the torque sensor's noise, through the filter and twice differentiated (H w''), beside
// the same noise in the residual they are fitted to. That is errors in variables: the noise's
// square in the column pulls the compliance toward zero and its product with the residual's noise
// pushes it away (on a soft Kraft spring at 81 Hz, 0.01 N m of torque noise read 17.81 N m/rad as
// 20.59). Draws of white noise of the audited size, made into columns and residual exactly as the
// log's torque is, give the fit the expected share to take off (NoiseDraws, crossval.hpp).
#pragma once

#include <memory>

#include "diagnose/crossval.hpp"
#include "diagnose/dataset.hpp"
#include "diagnose/shifted_positions.hpp"

namespace dyncc::diagnose {

inline constexpr int kTorqueNoiseDraws = 8;

/// Draws of the audited torque noise (per log and joint, white, at the evaluation rows' rate with
/// the log's spectral density in the filter's band): `columns` are each joint's shift tangent made
/// from the draw as the spring's are from the carried torque (A*n x n, conditioned; `at` lists the
/// joints), `target` the draw in the residual (A*n). Deterministic (a fixed seed).
NoiseDraws carried_torque_noise(const Dataset& d, const ModelSensitivity& m);

}  // namespace dyncc::diagnose
