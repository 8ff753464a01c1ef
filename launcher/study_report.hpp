#pragma once
// What a study writes from its completed runs (cosim study, launcher/study.cpp):
// table.csv, summary.json, error_vs_runtime.csv/.png, orderings.csv,
// thesis_comparison.csv, its plots, and report.html, the one page a reader opens.
#include <string>
#include <vector>

#include "cosim/scene_io.hpp"
#include "study_table.hpp"

namespace cosim {

struct StudyOutputs {
  const scene::Study& study;
  std::string study_file, scene_file, out_dir;
  int runs_planned = 0;
};

// Writes every output from `rows` (each completed run of a case in a pass).
void write_study_outputs(const StudyOutputs& outputs, const std::vector<StudyRow>& rows);

// One check of the study against a thesis number, evaluated on one pass's rows.
struct CheckOutcome {
  double ours = 0.0;      // NaN when the runs cannot tell
  double difference = 0;  // relative (case results) or in x (curve features); NaN when not run
  std::string agrees;     // "yes", "no" or "not run"
  std::string how;        // what was compared, for the report
};
CheckOutcome evaluate_check(const scene::StudyCheck& check, const std::vector<StudyRow>& rows);

// report.html (launcher/study_html.cpp): the set-up, the tables beside the
// thesis's numbers, the plots and every run's force curves, readable offline.
// `figures` and `tables` are the files (relative to out_dir) the page shows.
void write_study_html(const StudyOutputs& outputs, const std::vector<StudyRow>& rows,
                      const std::vector<std::string>& figures, const std::vector<std::string>& tables);

}  // namespace cosim
