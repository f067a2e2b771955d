// The diagnosis as an HTML page with figures (`dyncc diagnose --out DIR`): the verdict, the
// tables of diagnosis_json (gap per joint, ranking, fitted parameters, audit) and the figures of
// report_figures.hpp, all in one folder that can be moved or archived as a whole.
#pragma once

#include <filesystem>

#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"
#include "pipeline/derivation.hpp"

namespace dyncc::diagnose {

/// Writes `dir`/report.html and the figures it shows beside it (NAME.svg, which the page embeds,
/// and NAME.png); creates `dir` when missing. Throws std::runtime_error when a file cannot be
/// written.
void write_diagnosis_report(const Dataset& data, const pipeline::Derivation& derivation, const Diagnosis& diagnosis,
                            const std::filesystem::path& dir);

}  // namespace dyncc::diagnose
