// The paper's findings (section 4 and the conclusions) as comparisons between simulated runs on
// one plant, each with the figures that decide it. Used by the tests (tests/sim_paper_test.cpp)
// and by the report, so both judge by the same definitions.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "scenario.hpp"
#include "summary.hpp"

namespace dyncc::sim {

/// Every scenario, adaptive and fixed, on one plant.
struct PaperRuns {
  PlantKind plant = PlantKind::dyncc;
  std::vector<Run> runs;
  std::vector<Summary> summaries;  // same order
  [[nodiscard]] const Run& run(const std::string& scenario, bool adaptive) const;
  [[nodiscard]] const Summary& summary(const std::string& scenario, bool adaptive) const;
};

/// Runs them (MuJoCo needs the exported MJCF). `progress(label, fraction)` reports each run.
PaperRuns run_paper_scenarios(PlantKind plant, const std::string& mjcf,
                              const std::function<void(const std::string&, double)>& progress = {});

struct Finding {
  std::string id;        // "a" .. "f", as in the issue
  std::string claim;     // what the paper says
  std::string evidence;  // the measured figures
  bool holds = false;
};

std::vector<Finding> paper_findings(const PaperRuns& runs);

}  // namespace dyncc::sim
