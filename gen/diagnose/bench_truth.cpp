#include "diagnose/bench_truth.hpp"

#include <algorithm>

namespace dyncc::diagnose {

bool names_injected_effect(const std::string& named, const std::vector<Injection>& injected) {
  if (injected.empty()) return named == "none";
  const Injection& largest = injected.front();
  if (named == largest.effect) return true;
  return named == "stribeck_friction" && largest.effect == "coulomb_friction" &&
         std::any_of(injected.begin() + 1, injected.end(),
                     [&](const Injection& e) { return e.effect == "stribeck_friction" && e.joint == largest.joint; });
}

}  // namespace dyncc::diagnose
