#pragma once
// What `cosim run` prints at the end of a coupled run, for a person: the force
// decomposition of thesis chapter 2 with each force's steadiness over the
// averaging window, where the work went (the terrain's and the tyre's energy
// terms), and the scene's references beside the results. Everything else is in
// the run's summary.json, whose path it names.
#include <string>

#include <nlohmann/json.hpp>

namespace cosim {

struct RunReportInputs {
  const nlohmann::json& results;      // the run's merged results
  const nlohmann::json& performance;  // the run's merged performance
  const nlohmann::json& summary;      // the run's summary.json (wall time, comparison, energy)
  std::string summary_path;
};

void print_run_report(const RunReportInputs& in);

}  // namespace cosim
