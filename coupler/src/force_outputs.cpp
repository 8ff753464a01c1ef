// The coupler's contact pressure map and plots; see force_outputs.hpp.
#include "coupler/force_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "coupler/exchange_forces.hpp"
#include "cosim/outputs.hpp"
#include "cosim/signal.hpp"

namespace coupler {

namespace {

// The forces.csv columns drawn, by name: F3, F1, F2, F5 and the drawbar pull.
const char* const kPlottedColumns[5] = {"traction_force_N", "motion_resistance_N", "groove_force_N",
                                        "rolling_resistance_force_N", "drawbar_pull_N"};

// 0-based position of `name` in `header`; -1 if absent.
int column_of(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return static_cast<int>(k);
  return -1;
}

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream row(line);
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
  return cells;
}

// time_s and the plotted columns of forces.csv, found by their names in its
// header and streamed (a long run's file has a row per window); false if
// unreadable or a column is missing.
bool read_force_columns(const std::string& path, std::vector<double>& t, std::vector<std::vector<double>>& forces) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_row(line);
  const int time_column = column_of(header, "time_s");
  int wanted[5];
  for (int j = 0; j < 5; ++j) wanted[j] = column_of(header, kPlottedColumns[j]);
  if (time_column < 0 || *std::min_element(wanted, wanted + 5) < 0) return false;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split_row(line);
    if (cells.size() < header.size()) return false;
    t.push_back(std::strtod(cells[time_column].c_str(), nullptr));
    for (int j = 0; j < 5; ++j) forces[j].push_back(std::strtod(cells[wanted[j]].c_str(), nullptr));
  }
  return true;
}

}  // namespace

void write_contact_pressure_map(const std::string& path, const FacetLoads& facets) {
  cosim::CsvWriter map(path,
                       {"centroid_x_m", "centroid_y_m", "centroid_z_m", "contact_pressure_Pa", "contact_area_m2"});
  for (std::size_t i = 0; i < facets.size(); ++i) {
    const double a = facets.contact_area_m2[i];
    const double pn = std::sqrt(facets.pressure_x_N[i] * facets.pressure_x_N[i] +
                                facets.pressure_y_N[i] * facets.pressure_y_N[i] +
                                facets.pressure_z_N[i] * facets.pressure_z_N[i]);
    map.row({facets.centroid_x_m[i], facets.centroid_y_m[i], facets.centroid_z_m[i],
             a > 0 ? pn / a : 0.0, a});
  }
}

void plot_coupler_outputs(cosim::RunRecord& record, const cosim::scene::Scene& scene) {
  const std::string name = scene.name();
  record.plot_map("contact_pressure.csv", "contact_pressure.png", 1, 2, 4,
                  name + ": contact pressure on the tyre (last step, seen from above)", "x [m]", "y [m]",
                  "pressure [Pa]");
  // The raw per-step forces swing by +-1000 N on a coarse scene as particles
  // enter and leave contact: a centred moving mean is drawn over them, and the
  // averaging window of the results is shaded. Read back from forces.csv (the
  // run keeps only its averaging window's rows): time and F3, F1, F2, F5, drawbar pull.
  const double filter_s = scene.coupling().force_plot_filter_s();
  std::vector<double> t;
  std::vector<std::vector<double>> raw(5);
  if (!read_force_columns(record.path("forces.csv"), t, raw) || t.empty()) return;
  std::vector<std::vector<double>> filtered;
  for (const auto& series : raw) filtered.push_back(cosim::centred_moving_mean(t, series, filter_s));
  {
    std::vector<std::string> columns{"time_s"};
    columns.insert(columns.end(), std::begin(kPlottedColumns), std::end(kPlottedColumns));
    cosim::CsvWriter out(record.path("forces_filtered.csv"), columns);
    for (std::size_t i = 0; i < t.size(); ++i)
      out.row({t[i], filtered[0][i], filtered[1][i], filtered[2][i], filtered[3][i], filtered[4][i]});
  }
  cosim::PlotOptions o;
  char filter_ms[32];
  std::snprintf(filter_ms, sizeof filter_ms, "%g", filter_s * 1e3);
  o.title = name + ": force decomposition (faint: per step; bold: " + filter_ms + " ms centred mean)";
  o.x_label = "time [s]", o.y_label = "force [N]";
  const auto& results = record.results();
  if (results.contains("averaging_window_start_s"))
    o.extra_commands = "set object 1 rect from " + std::to_string(results["averaging_window_start_s"].get<double>()) +
                       ", graph 0 to " + std::to_string(results["averaging_window_end_s"].get<double>()) +
                       ", graph 1 behind fc rgb '#eeeeee' fs solid noborder\n";
  // forces.csv's columns of F3, F1, F2, F5, drawbar pull (gnuplot counts from 1); forces_filtered.csv's 2-6.
  int raw_column[5];
  for (int k = 0; k < 5; ++k) raw_column[k] = column_of(forces_csv_columns(), kPlottedColumns[k]) + 1;
  const char* names[5] = {"traction F3", "motion resistance F1", "groove F2", "F5", "drawbar pull"};
  const char* colours[5] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#000000"};
  std::vector<cosim::PlotCurve> curves;
  for (int k = 0; k < 5; ++k)
    curves.push_back({record.path("forces.csv"), "1:" + std::to_string(raw_column[k]),
                      std::string("lines lw 1 lc rgb '#b0") + (colours[k] + 1) + "'", ""});
  for (int k = 0; k < 5; ++k)
    curves.push_back({record.path("forces_filtered.csv"), "1:" + std::to_string(k + 2),
                      std::string("lines lw 3 lc rgb '") + colours[k] + "'", names[k]});
  if (cosim::plot_png(record.path("forces.png"), o, curves)) record.summary()["plots"].push_back("forces.png");
}

}  // namespace coupler
