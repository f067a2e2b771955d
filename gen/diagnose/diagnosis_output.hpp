// The diagnosis for people and programs: a plain-text summary for the terminal and the JSON
// the issue specifies ({"verdict", "ranking", "gap"}; joints numbered from 1).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"

namespace dyncc::diagnose {

nlohmann::json diagnosis_json(const Dataset& data, const Diagnosis& diagnosis);
std::string diagnosis_text(const Dataset& data, const Diagnosis& diagnosis);

/// Why nothing was named where the verdict is `unknown` or `none` (empty otherwise).
/// `unknown`: the first step's best candidate with what it removes held out and its 95 %
/// interval, and, where the residual's flagged windows make one or two bursts, that so rare an
/// event is not something blocks held out in time can test (a fit on the blocks without it has
/// nothing to learn it from), so the log should be looked at there.
/// `none`: that no joint's gap is both above its floors and material, and where the first step's best
/// candidate still removes part of it significantly held out, which one, how much, and why it
/// was not accepted (a small effect may hide below the floors: the user decides whether to look).
std::string why_not_named(const Diagnosis& diagnosis);

}  // namespace dyncc::diagnose
