#include <cstdio>
#include <string>
#include "scenario.hpp"
#include "summary.hpp"
using namespace dyncc::sim;
int main(int argc, char** argv) {
  std::vector<Summary> rows;
  for (const char* name : {"paper-0.5kg", "paper-1kg", "paper-simplified", "paper-contact", "unloaded"}) {
    for (bool adapt : {true, false}) {
      auto s = scenario_settings(std::string(name) == "unloaded" ? "paper-0.5kg" : name);
      if (std::string(name) == "unloaded") { s.payload = 0; s.name = "unloaded"; }
      s.adaptation = adapt;
      if (argc > 1) s.payload = std::stod(argv[1]);
      auto run = simulate(s);
      if (std::string(name) == "paper-0.5kg") write_csv(run, std::string("/tmp/") + name + (adapt ? "-a" : "-f") + ".csv");
      rows.push_back(summarize(run));
    }
  }
  std::fputs(summary_table(rows).c_str(), stdout);
  std::fputs(estimate_table(rows).c_str(), stdout);
}
