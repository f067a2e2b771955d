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

}  // namespace dyncc::diagnose
