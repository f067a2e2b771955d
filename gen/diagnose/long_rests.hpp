// Where a joint rests for a while: the holds in which a static friction can keep a torque, which
// the selection leaves out of its scores once a friction is evident on the joint (diagnosis.cpp,
// mark_static_holds).
#pragma once

#include <Eigen/Dense>

#include "diagnose/dataset.hpp"

namespace dyncc::diagnose {

/// Per stacked analysis row (A*n): 1 where joint i is near zero velocity (`away` 0, see
/// away_from_zero_velocity) in a stretch of at least kLongRest within one log: a hold, where a
/// static friction can keep any torque within its band, rather than a reversal, which passes
/// through the band in a fraction of a second (on the bench's Fourier logs no stretch lasts 1 s;
/// on its tele-operation logs 90 % of the rows near zero lie in stretches of 1 s or more).
inline constexpr double kLongRest = 1.0;  // s
Eigen::VectorXd in_long_rests(const Dataset& d, const Eigen::VectorXd& away);

}  // namespace dyncc::diagnose
