// Physical sense of a fitted effect: the stage between the fits and the selection that refuses
// a fit no real arm could have (the effect's columns soaking up something else).
#pragma once

#include "diagnose/diagnosis.hpp"
#include "diagnose/gap.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::diagnose {

// Physical sense of a fit: friction coefficients, a static friction excess, a payload's mass, a
// contact's force and stiffness (a surface only pushes), a joint's stiffness and a backlash's
// width are not negative (beyond twice their
// error). A fit that needs them negative is the effect's columns soaking up something else (e.g.
// a Stribeck "excess" below Coulomb sharpening a mis-estimated sign near zero velocity).
// A correction to a quantity the description already has (its Coulomb and viscous friction, its
// rotor inertia) is judged with it: the total must not be negative, the correction may be.
bool plausible_parameter(const FittedParameter& p, const pipeline::Derivation& derivation, const Gap& gap);

/// Every parameter of the effect plausible, and a load's or contact's point on its link.
bool plausible(const RankedEffect& r, const pipeline::Derivation& derivation, const Gap& gap);

}  // namespace dyncc::diagnose
