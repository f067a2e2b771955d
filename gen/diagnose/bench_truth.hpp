// What the blind bench (`dyncc sim2real-bench`) counts as naming the effect it injected.
#pragma once

#include <string>
#include <vector>

#include "diagnose/synthetic_log.hpp"

namespace dyncc::diagnose {

/// Whether `named` (a verdict's first effect) names the largest of the injected effects (the
/// front of `injected`): its own name, or a Stribeck friction where the truth put a Coulomb
/// friction and a Stribeck excess on the same joint. A Stribeck friction is a Coulomb friction
/// with an excess near rest (its fit has both, fc and fs), so those two injected together are one
/// Stribeck friction, and its fc measures the Coulomb friction.
bool names_injected_effect(const std::string& named, const std::vector<Injection>& injected);

}  // namespace dyncc::diagnose
