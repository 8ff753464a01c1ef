// report.html of a study: one page, no external resource (readable offline,
// opened from disk), showing the set-up, the tables (the thesis's numbers
// beside ours), the plots and each run's force curves (raw per-step signal with
// its moving mean, drawn by the coupler). A script marks on <body> how many of
// its figures and tables loaded (data-figures-loaded="k/n", data-tables="m"),
// which the headless-browser test reads.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include "cosim/csv.hpp"
#include "cosim/error.hpp"
#include "study_report.hpp"

namespace cosim {
namespace {

std::string esc(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// A CSV file of the study as an HTML table; the cell of a "hold"/"agrees" column is coloured.
void csv_table(std::ostream& html, const std::string& dir, const std::string& file) {
  const CsvTable t = read_csv(dir + "/" + file);
  html << "<div class=\"scroll\"><table class=\"data\" data-file=\"" << esc(file) << "\"><thead><tr>";
  for (const auto& h : t.header) html << "<th>" << esc(h) << "</th>";
  html << "</tr></thead><tbody>\n";
  for (const auto& r : t.rows) {
    html << "<tr>";
    for (std::size_t c = 0; c < t.header.size(); ++c) {
      const std::string v = c < r.fields.size() ? r.fields[c] : "";
      const bool verdict = t.header[c] == "hold" || t.header[c] == "agrees";
      const char* cls = !verdict ? "" : (v == "hold" || v == "yes") ? " class=\"ok\"" : (v == "fail" || v == "no") ? " class=\"bad\"" : "";
      html << "<td" << cls << ">" << esc(v) << "</td>";
    }
    html << "</tr>\n";
  }
  html << "</tbody></table></div>\n<p class=\"file\">" << esc(file) << "</p>\n";
}

const char* kStyle = R"(<style>
body{font-family:sans-serif;max-width:1200px;margin:1em auto;padding:0 1em;color:#222}
h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #ccc;margin-top:1.6em}
table.data{border-collapse:collapse;font-size:0.85em}table.data td,table.data th{border:1px solid #ccc;padding:2px 6px;text-align:left;vertical-align:top}
table.data th{background:#f0f0f0}td.ok{background:#d8f0d8}td.bad{background:#f6d6d6}
.scroll{overflow-x:auto;max-height:40em}figure{display:inline-block;width:47%;margin:0.5em;vertical-align:top}
figure img{max-width:100%;border:1px solid #ddd}figcaption,.file{font-size:0.8em;color:#666}
code{background:#f4f4f4;padding:0 3px}
</style>
)";

// Marks on <body> how many figures decoded and how many tables are present.
const char* kCheckScript = R"(<script>
window.addEventListener('load', function () {
  var images = document.querySelectorAll('img');
  var loaded = 0;
  images.forEach(function (img) { if (img.complete && img.naturalWidth > 0) loaded++; });
  document.body.setAttribute('data-figures-loaded', loaded + '/' + images.length);
  document.body.setAttribute('data-tables', document.querySelectorAll('table.data').length);
});
</script>
)";

}  // namespace

void write_study_html(const StudyOutputs& o, const std::vector<StudyRow>& rows, const std::vector<std::string>& figures,
                      const std::vector<std::string>& tables) {
  const auto& s = o.study;
  std::ofstream html(o.out_dir + "/report.html");
  if (!html) throw Error(o.out_dir + "/report.html: cannot be written");
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << esc(s.name())
       << "</title>\n" << kStyle << "</head>\n<body data-tables-expected=\"" << tables.size() << "\">\n";
  html << "<h1>Study " << esc(s.name()) << "</h1>\n";
  if (!s.description().empty()) html << "<p>" << esc(s.description()) << "</p>\n";
  html << "<h2>Set-up</h2>\n<ul><li>study: <code>" << esc(o.study_file) << "</code></li><li>scene: <code>"
       << esc(o.scene_file) << "</code></li><li>runs completed: " << rows.size() << " of " << o.runs_planned
       << "</li>\n";
  if (!s.reference_source().empty())
    html << "<li>reference: " << esc(s.reference_source()) << "</li>\n";
  html << "</ul>\n";
  for (const auto& p : s.passes()) {
    html << "<p><b>pass " << esc(p.name()) << "</b>: " << esc(p.description()) << "<br>overrides:";
    for (const auto& set : p.set()) html << " <code>" << esc(set) << "</code>";
    html << "</p>\n";
  }
  auto section = [&](const std::string& file, const std::string& title, const std::string& text) {
    if (std::find(tables.begin(), tables.end(), file) == tables.end()) return;
    html << "<h2>" << title << "</h2>\n" << (text.empty() ? "" : "<p>" + text + "</p>\n");
    csv_table(html, o.out_dir, file);
  };
  section("thesis_comparison.csv", "Against the thesis's numbers",
          "Each check: the thesis's value, ours, their difference (relative for a run's result, in the x "
          "quantity for a curve's feature) and whether it is within the stated tolerance.");
  section("orderings.csv", "The thesis's orderings",
          "Each statement of the thesis (its section, line and figure), what our runs show, and whether every "
          "comparison holds.");
  html << "<h2>Figures</h2>\n";
  for (const auto& f : figures)
    html << "<figure><img src=\"" << esc(f) << "\" alt=\"" << esc(f) << "\"><figcaption>" << esc(f)
         << "</figcaption></figure>\n";
  section("table.csv", "Every run", "One row per run of a case in a pass: its parameters, size, cost and results.");
  section("error_vs_runtime.csv", "Error against run time",
          "Each reported quantity of each run against its reference: the same case in the finest pass (a study "
          "with passes) or the study's reference value, with the run's wall time.");
  // Each coupled run's force curves (the coupler's forces.png: faint per-step signal, bold moving mean).
  bool any = false;
  for (const auto& r : rows) {
    const std::string png = (r.pass.empty() ? "" : r.pass + "/") + r.label + "/coupler/forces.png";
    if (!std::filesystem::exists(o.out_dir + "/" + png)) continue;
    if (!any) html << "<h2>Force curves of every run</h2>\n<p>The shaded band is the averaging window of the "
                      "run's results.</p>\n", any = true;
    html << "<figure><img src=\"" << esc(png) << "\" alt=\"" << esc(png) << "\"><figcaption>"
         << esc(png) << "</figcaption></figure>\n";
  }
  html << kCheckScript << "</body></html>\n";
}

}  // namespace cosim
