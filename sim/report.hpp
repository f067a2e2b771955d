// Figures of runs in the style of the paper's Figs. 4-8 and the HTML page that gathers every
// scenario on both plants (`dyncc report`).
#pragma once

#include <filesystem>
#include <vector>

#include "findings.hpp"
#include "scenario.hpp"

namespace dyncc::sim {

/// angles.{png,svg} (master and slave, Figs. 4-5), errors.{png,svg} (s1..s3, Fig. 6) and
/// estimates.{png,svg} (p^ over time) of one run, in `dir`.
void write_run_figures(const Run& run, const std::filesystem::path& dir);

/// `dir`/index.html with, per plant, the findings, the summary and estimate tables and the
/// figures (written beside it, under dir/<plant>/).
void write_report(const std::vector<PaperRuns>& plants, const std::filesystem::path& dir);

}  // namespace dyncc::sim
