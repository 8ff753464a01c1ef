#pragma once
// The rows of a study (one per completed run of a case in a pass) and what is
// read from them: column values, row filters, and the thesis's orderings
// (tests/data/torque_force_orderings.csv) evaluated into hold / fail.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/scene_io.hpp"

namespace cosim {

struct StudyRow {
  std::string pass;   // "" in a study without passes
  std::string label;  // the case
  std::map<std::string, std::string> parameters;  // parameter column -> value ("tread" -> "smooth")
  std::map<std::string, double> computed;         // columns the study computes ("slip_ratio")
  nlohmann::json summary;                         // the run's summary.json
};

// A column's number in a row: a computed column, a numeric parameter, the
// run's wall_time_s, a result (dotted path into "results"), or "A-B" / "A+B"
// of two of those. NaN when absent or not a number.
double row_number(const StudyRow& row, const std::string& quantity);

// A result field of a study file, "COLUMN=PATH" or a plain PATH: the table's
// column, and the result's path in the run's summary.
std::string field_column(const std::string& field);
std::string field_path(const std::string& field);
// A parameter's text, else the number's ("%.6g"), else "".
std::string row_text(const StudyRow& row, const std::string& column);

// A row filter: conditions joined by ';', each COLUMN OP VALUE with OP one of
// = != > >= < <= (= and != compare text, the others numbers). "" keeps every row.
// Throws cosim::Error naming the condition if one cannot be read.
bool row_matches(const StudyRow& row, const std::string& where);

// A statement of the thesis about the order of a result across runs.
//   kind order:      in every group of runs that differ only in `column`, the
//                    values listed in `order` ("smooth>block_sipes>block")
//                    rank by `quantity` in that order;
//   kind increasing / decreasing: within every such group, `quantity` rises /
//                    falls with the numeric `column`;
//   kind negative / positive: `quantity` < 0 / > 0 in every run.
// `where` restricts the runs first (row_matches).
struct Ordering {
  std::string id, claim, source, quantity, kind, column, order, where;
  std::string location;  // FILE:LINE, for messages
};
// Reads an orderings CSV (columns id,claim,source,quantity,kind,column,order,where);
// throws cosim::Error naming the file, line and field of a bad entry.
std::vector<Ordering> read_orderings(const std::string& csv_path);

struct OrderingOutcome {
  int compared = 0, held = 0;
  std::string ours;  // what our runs show, e.g. "3 of 4 hold; soft/0: block 0.061 > smooth 0.052; ..."
  std::string hold;  // "hold" (every comparison), "fail" (one or more not), "not run" (none to compare)
};
// Evaluates an ordering over `rows` of one pass; groups are rows equal in every
// parameter column but the ordering's own.
OrderingOutcome evaluate_ordering(const Ordering& ordering, const std::vector<StudyRow>& rows);

// F5, the drawbar pull and F3 - F5 of each row recomputed with the r its
// reference run measured (Study.f5_radius; scene.proto says which run): F5 =
// RRM / r is linear in 1 / r, and so is its mean over a window of constant r,
// so the recomputation from the run's RRM and F5 is exact. Sets the computed
// columns rolling_radius_for_F5_m, rolling_resistance_force_N, drawbar_pull_N
// and traction_minus_rrf_N; rows without a reference run keep their own.
void apply_f5_radius(const scene::StudyF5Radius& f5_radius, std::vector<StudyRow>& rows);

}  // namespace cosim
