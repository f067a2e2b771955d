// What the blind bench (`dyncc sim2real-bench`) counts as naming the effect it injected, and how
// large it counts an effect injected into a closed-loop run.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "diagnose/dataset.hpp"
#include "diagnose/synthetic_log.hpp"

namespace dyncc::diagnose {

/// Whether `named` (a verdict's first effect) names the largest of the injected effects (the
/// front of `injected`): its own name, or a Stribeck friction where the truth put a Coulomb
/// friction and a Stribeck excess on the same joint. A Stribeck friction is a Coulomb friction
/// with an excess near rest (its fit has both, fc and fs), so those two injected together are one
/// Stribeck friction, and its fc measures the Coulomb friction.
bool names_injected_effect(const std::string& named, const std::vector<Injection>& injected);

/// The torque an effect of a joint adds along a closed-loop log (`data`, the run without it), from
/// its own formula on the log's motion and through the filter the diagnosis applies: per-joint
/// RMS, by which the bench scales the effect to its share of the torque. (The residual change
/// between a run with the effect and a clean run would also count how the two runs' small
/// residuals at reversals differ once the motion shifts, and size small effects too small.) A
/// friction counts only where the joint is seen to move, outside the band near zero velocity where
/// the velocity estimate is the positions' noise (zero_velocity_band): in a hold the plant's friction holds whatever
/// keeps the joint still, not the sign of that noise. Counted at that sign (to 2 mrad/s, until the thirty-fourth
/// session), the holds that fill 70 % of a Kraft tele-operation log made about half of a Stribeck
/// excess's size there (blind seed 617 case 54: an excess of joint 3 counted as 20 % of its
/// joint's torque beside a gain of joint 2 counted as 10 %; the diagnosis fitted both within
/// 0.2 %, and the fitted excess's torque is 8.8 % of its joint's, the gain's 10.9 %). Empty for the effects whose plant
/// model has no formula here (payload on the hook, table contact): those are sized by a probe run.
std::optional<Eigen::VectorXd> closed_loop_effect_rms(const Dataset& data, const Injection& e);

}  // namespace dyncc::diagnose
