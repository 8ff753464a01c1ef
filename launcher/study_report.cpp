#include "study_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "cosim/csv.hpp"
#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/result_references.hpp"

namespace cosim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A number for a CSV cell ("" when absent).
std::string num(double v) { return std::isnan(v) ? "" : number_text(v); }

std::string json_num(const nlohmann::json& v) {
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";  // e.g. plate_at_rest
  return v.is_number() ? num(v.get<double>()) : "";
}

// A CSV field, quoted when it holds a comma or a quote.
std::string field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::vector<std::string> pass_names(const scene::Study& s) {
  if (s.passes_size() == 0) return {""};
  std::vector<std::string> names;
  for (const auto& p : s.passes()) names.push_back(p.name());
  return names;
}

// The table columns of the study's result and extra results.
std::vector<std::string> reported_quantities(const scene::Study& s) {
  std::vector<std::string> quantities{field_column(s.result_field())};
  for (const auto& f : s.extra_result_fields()) quantities.push_back(field_column(f));
  return quantities;
}

std::vector<StudyRow> rows_of(const std::vector<StudyRow>& rows, const std::string& pass) {
  std::vector<StudyRow> out;
  for (const auto& r : rows)
    if (r.pass == pass) out.push_back(r);
  return out;
}

// Parameter columns in the order they first appear.
std::vector<std::string> parameter_columns(const std::vector<StudyRow>& rows, const scene::Study& s) {
  std::vector<std::string> columns;
  auto add = [&](const std::string& p) {
    const std::string name = p.substr(0, p.find('='));
    if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
  };
  for (const auto& k : s.cases())
    for (const auto& p : k.parameter()) add(p);
  for (const auto& g : s.grids()) {
    for (const auto& p : g.parameter()) add(p);
    for (const auto& a : g.axes()) add(a.column() + "=");
  }
  for (const auto& r : rows)
    for (const auto& [name, v] : r.parameters) add(name + "=");
  return columns;
}

// The reference of a run's relative error: the pass's last case, or the study's value.
double reference_for(const scene::Study& s, const std::vector<StudyRow>& rows, const std::string& pass) {
  // A study of characteristics (no reference value, no finest case) has no error column.
  if (!s.compare_with_last_case()) return s.reference_value() != 0 ? s.reference_value() : kNaN;
  const std::string last = s.cases_size() ? s.cases(s.cases_size() - 1).label() : "";
  for (const auto& r : rows)
    if (r.pass == pass && r.label == last) return row_number(r, field_column(s.result_field()));
  return kNaN;
}

void write_table(const StudyOutputs& o, const std::vector<StudyRow>& rows, const std::vector<std::string>& params,
                 bool with_slip) {
  const auto& s = o.study;
  std::ofstream table(o.out_dir + "/table.csv");
  table << "case";
  if (s.passes_size()) table << ",pass";
  for (const auto& p : params) table << "," << p;
  if (with_slip) table << ",slip_ratio";
  table << ",particle_spacing_m,size,time_step_s,steps,wall_time_s," << field_column(s.result_field()) << ",reference,relative_error";
  for (const auto& f : s.extra_result_fields()) table << "," << field_column(f);
  table << "\n";
  for (const auto& r : rows) {
    const auto& summary = r.summary;
    // size: particles (SPH) or elements (FE); time step: the mean (SPH) or the fixed step (FE).
    const nlohmann::json size = summary.contains("particles") ? summary["particles"] : summary.value("elements", nlohmann::json());
    nlohmann::json dt = summary.value("dt_s", nlohmann::json());
    if (dt.is_object()) dt = dt.value("mean", nlohmann::json());
    const double value = row_number(r, field_column(s.result_field()));
    const double reference = reference_for(s, rows, r.pass);
    table << field(r.label);
    if (s.passes_size()) table << "," << r.pass;
    for (const auto& p : params) table << "," << field(r.parameters.count(p) ? r.parameters.at(p) : "");
    if (with_slip) table << "," << num(r.computed.count("slip_ratio") ? r.computed.at("slip_ratio") : kNaN);
    table << "," << json_num(summary.value("particle_spacing_m", nlohmann::json())) << "," << json_num(size) << ","
          << json_num(dt) << "," << summary.value("steps", 0L) << "," << json_num(summary["wall_time_s"]) << ","
          << num(value) << "," << num(reference) << ","
          << num(reference != 0 && !std::isnan(reference) ? (value - reference) / reference : kNaN);
    for (const auto& f : s.extra_result_fields()) {
      const nlohmann::json* v = summary.contains("results") ? result_at(summary["results"], f) : nullptr;
      // A named column, or a result the study recomputed (Study.f5_radius), is the row's number.
      const bool computed = f.find('=') != std::string::npos || r.computed.count(f);
      table << "," << (computed ? num(row_number(r, field_column(f))) : v ? json_num(*v) : "");
    }
    table << "\n";
  }
}

// The reference of a run in a study with passes: the same case's run in the
// latest pass after its own that completed (a medium pass run for a few cases
// is the coarse pass's reference where the fine one is not run); the last
// pass's runs are their own. nullptr: no finer run of the case.
const StudyRow* finer_run(const std::vector<std::string>& passes, const std::vector<StudyRow>& rows,
                          const StudyRow& r) {
  const auto index = [&](const std::string& pass) {
    return std::find(passes.begin(), passes.end(), pass) - passes.begin();
  };
  if (r.pass == passes.back()) return &r;
  const StudyRow* best = nullptr;
  for (const auto& f : rows)
    if (f.label == r.label && index(f.pass) > index(r.pass) && (!best || index(f.pass) > index(best->pass))) best = &f;
  return best;
}

// error_vs_runtime.csv: each reported quantity of each run against the
// reference: the finest later pass's run of the same case (finer_run; a study
// with passes), or the study's reference (one pass).
void write_error_vs_runtime(const StudyOutputs& o, const std::vector<StudyRow>& rows) {
  const auto& s = o.study;
  const auto passes = pass_names(s);
  const auto quantities = reported_quantities(s);
  std::ofstream out(o.out_dir + "/error_vs_runtime.csv");
  out << "case,quantity,pass,value,wall_time_s,reference_pass,reference,relative_error\n";
  for (const auto& r : rows) {
    const StudyRow* finer = passes.size() > 1 ? finer_run(passes, rows, r) : nullptr;
    const std::string reference_pass =
        passes.size() == 1 ? "reference" : finer ? finer->pass : passes.back() + " (not run)";
    for (const auto& q : quantities) {
      const double v = row_number(r, q);
      double ref = kNaN;
      if (passes.size() > 1) ref = finer ? row_number(*finer, q) : kNaN;
      else if (q == field_column(s.result_field())) ref = reference_for(s, rows, r.pass);
      const double error = ref != 0 && !std::isnan(ref) ? (v - ref) / std::fabs(ref) : kNaN;
      out << field(r.label) << "," << q << "," << r.pass << "," << num(v) << "," << num(row_number(r, "wall_time_s"))
          << "," << reference_pass << "," << num(ref) << "," << num(error) << "\n";
    }
  }
}

// The |relative error| of the result against run time (the table's columns).
std::string plot_error_vs_runtime(const StudyOutputs& o, const std::vector<StudyRow>& rows) {
  const auto& s = o.study;
  const std::string data = o.out_dir + "/error_vs_runtime_points.csv";
  {
    std::ofstream out(data);
    out << "wall_time_s,abs_error_percent,case\n";
    for (const auto& r : rows) {
      const double ref = reference_for(s, rows, r.pass);
      const double v = row_number(r, field_column(s.result_field()));
      if (ref == 0 || std::isnan(ref) || std::isnan(v)) continue;
      out << num(row_number(r, "wall_time_s")) << "," << num(100 * std::fabs((v - ref) / ref)) << ","
          << field(r.pass.empty() ? r.label : r.pass + "/" + r.label) << "\n";
    }
  }
  PlotOptions p;
  p.title = s.name() + ": error against run time", p.x_label = "wall time [s]";
  p.y_label = "|error| in " + field_column(s.result_field()) + " [%]";
  p.log_x = true, p.key = false;
  p.extra_commands = "set offsets graph 0.05, graph 0.15, graph 0.1, graph 0.1\n";
  const std::string png = o.out_dir + "/error_vs_runtime.png";
  if (!plot_png(png, p, {{data, "1:2", "linespoints pt 7 ps 1.5 lw 2", ""}, {data, "1:2:3", "labels offset 0,1.2", ""}}))
    throw Error("gnuplot failed on " + png + " (is gnuplot installed? scripts/setup.sh installs it)");
  return "error_vs_runtime.png";
}

// Coarse against fine: each quantity's relative difference against the coarse run's wall time.
std::string plot_pass_errors(const StudyOutputs& o, const std::vector<StudyRow>& rows) {
  const auto& s = o.study;
  const auto passes = pass_names(s);
  const auto quantities = reported_quantities(s);
  std::vector<PlotCurve> curves;
  make_folder(o.out_dir + "/plots");
  for (const auto& q : quantities) {
    const std::string data = o.out_dir + "/plots/pass_error_" + q + ".csv";
    std::ofstream out(data);
    out << "wall_time_s,abs_difference_percent\n";
    int n = 0;
    for (const auto& r : rows) {
      const StudyRow* f = finer_run(passes, rows, r);
      if (!f || f == &r) continue;
      const double v = row_number(r, q), ref = row_number(*f, q);
      if (ref == 0 || std::isnan(ref) || std::isnan(v)) continue;
      // Equal to round-off in both passes: an input of the case (a prescribed
      // spin), not a result; on a log axis it would only stretch the scale.
      if (std::fabs(v - ref) <= 1e-9 * std::fabs(ref)) continue;
      out << num(row_number(r, "wall_time_s")) << "," << num(100 * std::fabs((v - ref) / ref)) << "\n", ++n;
    }
    if (n) curves.push_back({data, "1:2", "points pt 7 ps 1.3", q});
  }
  if (curves.empty()) return "";
  PlotOptions p;
  p.title = s.name() + ": each run against its case's run in the finest later pass";
  p.x_label = "wall time of the run [s]", p.y_label = "|difference| from the finer run [%]";
  p.log_x = true, p.log_y = true;
  const std::string png = o.out_dir + "/error_vs_runtime.png";
  return plot_png(png, p, curves) ? "error_vs_runtime.png" : "";
}

PlotOptions plot_options(const scene::StudyPlot& plot, const std::string& pass) {
  PlotOptions p;
  p.title = plot.title() + (pass.empty() ? "" : " (" + pass + " pass)");
  p.x_label = plot.x_label().empty() ? plot.x() : plot.x_label();
  p.y_label = plot.y_label().empty() ? plot.y(0) : plot.y_label();
  p.extra_commands = "set xzeroaxis lt -1\nset key outside right\n";
  p.width_px = 1000;
  return p;
}

// A plot of a CSV every run writes (plot.run_csv): its x and y columns, one
// line per case, drawn from the run's own file (the hydroplaning study's road
// force against speed). A case whose run has no such file is left out.
std::string draw_run_csv_plot(const StudyOutputs& o, const scene::StudyPlot& plot,
                              const std::vector<StudyRow>& pass_rows, const std::string& pass) {
  std::vector<PlotCurve> curves;
  for (const auto& r : pass_rows) {
    if (!row_matches(r, plot.where())) continue;
    const std::string csv = o.out_dir + (pass.empty() ? "" : "/" + pass) + "/" + r.label + "/" + plot.run_csv();
    if (!std::ifstream(csv)) continue;
    const CsvTable table = read_csv(csv);
    std::string name;
    for (const auto& c : plot.series()) name += (name.empty() ? "" : ", ") + row_text(r, c);
    if (name.empty()) name = r.label;
    for (int k = 0; k < plot.y_size(); ++k) {
      const std::string columns =
          std::to_string(table.column(plot.x()) + 1) + ":" + std::to_string(table.column(plot.y(k)) + 1);
      curves.push_back({csv, columns, "lines lw 2", plot.y_size() > 1 ? name + ": " + plot.y(k) : name});
    }
  }
  if (curves.empty()) return "";
  const std::string png = (pass.empty() ? "" : pass + "_") + plot.file();
  return plot_png(o.out_dir + "/" + png, plot_options(plot, pass), curves) ? png : "";
}

// A plot of the study (thesis-figure style): y against x, a line per series.
std::string draw_plot(const StudyOutputs& o, const scene::StudyPlot& plot, const std::vector<StudyRow>& pass_rows,
                      const std::string& pass) {
  if (!plot.run_csv().empty()) return draw_run_csv_plot(o, plot, pass_rows, pass);
  std::map<std::string, std::vector<const StudyRow*>> series;
  for (const auto& r : pass_rows) {
    if (!row_matches(r, plot.where()) || std::isnan(row_number(r, plot.x()))) continue;
    std::string name;
    for (const auto& c : plot.series()) name += (name.empty() ? "" : ", ") + row_text(r, c);
    series[name].push_back(&r);
  }
  if (series.empty()) return "";
  make_folder(o.out_dir + "/plots");
  const std::string stem = (pass.empty() ? "" : pass + "_") + plot.file().substr(0, plot.file().rfind('.'));
  std::vector<PlotCurve> curves;
  int index = 0;
  for (auto& [name, members] : series) {
    std::sort(members.begin(), members.end(),
              [&](const StudyRow* a, const StudyRow* b) { return row_number(*a, plot.x()) < row_number(*b, plot.x()); });
    const std::string data = o.out_dir + "/plots/" + stem + "_" + std::to_string(index++) + ".csv";
    std::ofstream out(data);
    out << plot.x();
    for (const auto& y : plot.y()) out << "," << y;
    out << "\n";
    for (const auto* r : members) {
      out << num(row_number(*r, plot.x()));
      for (const auto& y : plot.y()) out << "," << num(row_number(*r, y));
      out << "\n";
    }
    out.close();
    for (int k = 0; k < plot.y_size(); ++k) {
      std::string title = plot.y_size() > 1 ? plot.y(k) : "";
      if (!name.empty()) title = title.empty() ? name : title + " (" + name + ")";
      curves.push_back({data, "1:" + std::to_string(k + 2), "linespoints pt 7 ps 1.2 lw 2", title});
    }
  }
  const std::string png = stem + ".png";
  return plot_png(o.out_dir + "/" + png, plot_options(plot, pass), curves) ? png : "";
}

}  // namespace

CheckOutcome evaluate_check(const scene::StudyCheck& c, const std::vector<StudyRow>& rows) {
  CheckOutcome out;
  out.ours = out.difference = kNaN;
  out.agrees = "not run";
  if (c.kind() == scene::StudyCheck::CASE_RESULT) {
    for (const auto& r : rows)
      if (r.label == c.case_label()) out.ours = row_number(r, c.result());
    out.how = c.result() + " of case " + c.case_label();
    if (std::isnan(out.ours)) return out;
    out.difference = c.value() != 0 ? (out.ours - c.value()) / std::fabs(c.value()) : out.ours;
  } else {
    std::vector<const StudyRow*> curve;
    for (const auto& r : rows)
      if (row_matches(r, c.where()) && !std::isnan(row_number(r, c.x())) && !std::isnan(row_number(r, c.result())))
        curve.push_back(&r);
    std::sort(curve.begin(), curve.end(),
              [&](const StudyRow* a, const StudyRow* b) { return row_number(*a, c.x()) < row_number(*b, c.x()); });
    if (curve.size() < 2) return out;
    if (c.kind() == scene::StudyCheck::ZERO_CROSSING) {
      out.how = c.x() + " where " + c.result() + " first changes sign (linear between runs)";
      for (std::size_t i = 0; i + 1 < curve.size() && std::isnan(out.ours); ++i) {
        const double y0 = row_number(*curve[i], c.result()), y1 = row_number(*curve[i + 1], c.result());
        if ((y0 < 0) != (y1 < 0)) {
          const double x0 = row_number(*curve[i], c.x()), x1 = row_number(*curve[i + 1], c.x());
          out.ours = x0 + (x1 - x0) * (0 - y0) / (y1 - y0);
        }
      }
      if (std::isnan(out.ours)) {
        out.agrees = "no";
        out.how += ": no sign change over the runs";
        return out;
      }
    } else {
      const bool max = c.kind() == scene::StudyCheck::ARG_MAX;
      out.how = c.x() + " of the " + (max ? "largest " : "smallest ") + c.result() + " over the runs";
      const StudyRow* best = curve.front();
      for (const auto* r : curve) {
        const double y = row_number(*r, c.result()), b = row_number(*best, c.result());
        if (max ? y > b : y < b) best = r;
      }
      out.ours = row_number(*best, c.x());
      if (best == curve.front() || best == curve.back()) {
        // At the end of the runs' range the curve may go on rising (falling): no extreme was found.
        out.difference = out.ours - c.value();
        out.agrees = "no";
        out.how += ": at the end of the range run, no extreme inside it";
        return out;
      }
    }
    out.difference = out.ours - c.value();
  }
  out.agrees = std::fabs(out.difference) <= c.tolerance() ? "yes" : "no";
  return out;
}

void write_study_outputs(const StudyOutputs& o, const std::vector<StudyRow>& rows) {
  const auto& s = o.study;
  const auto params = parameter_columns(rows, s);
  bool with_slip = false;
  for (const auto& r : rows) with_slip = with_slip || r.computed.count("slip_ratio");
  write_table(o, rows, params, with_slip);
  write_error_vs_runtime(o, rows);
  std::vector<std::string> figures, tables{"table.csv", "error_vs_runtime.csv"};
  const std::string error_png =
      pass_names(s).size() > 1 ? plot_pass_errors(o, rows)
      : (s.compare_with_last_case() || s.reference_value() != 0) ? plot_error_vs_runtime(o, rows) : "";
  nlohmann::json checks = nlohmann::json::array(), orderings = nlohmann::json::array();
  if (s.checks_size()) {
    std::ofstream out(o.out_dir + "/thesis_comparison.csv");
    out << "check,source,pass,thesis,ours,difference,tolerance,agrees,compared\n";
    for (const auto& pass : pass_names(s))
      for (const auto& c : s.checks()) {
        const auto r = evaluate_check(c, rows_of(rows, pass));
        out << field(c.name()) << "," << field(c.source()) << "," << pass << "," << num(c.value()) << ","
            << num(r.ours) << "," << num(r.difference) << "," << num(c.tolerance()) << "," << r.agrees << ","
            << field(r.how) << "\n";
        checks.push_back({{"check", c.name()}, {"pass", pass}, {"thesis", c.value()},
                          {"ours", std::isnan(r.ours) ? nlohmann::json() : nlohmann::json(r.ours)}, {"agrees", r.agrees}});
      }
    tables.push_back("thesis_comparison.csv");
  }
  if (!s.orderings_file().empty()) {
    const auto list = read_orderings(folder_of(o.study_file) + "/" + s.orderings_file());
    std::ofstream out(o.out_dir + "/orderings.csv");
    out << "ordering,claim,source,pass,ours,hold\n";
    for (const auto& pass : pass_names(s))
      for (const auto& ord : list) {
        const auto r = evaluate_ordering(ord, rows_of(rows, pass));
        out << ord.id << "," << field(ord.claim) << "," << field(ord.source) << "," << pass << "," << field(r.ours)
            << "," << r.hold << "\n";
        orderings.push_back({{"ordering", ord.id}, {"pass", pass}, {"hold", r.hold}, {"held", r.held},
                             {"compared", r.compared}});
      }
    tables.push_back("orderings.csv");
  }
  for (const auto& pass : pass_names(s))
    for (const auto& plot : s.plots()) {
      const auto png = draw_plot(o, plot, rows_of(rows, pass), pass);
      if (!png.empty()) figures.push_back(png);
    }
  if (!error_png.empty()) figures.push_back(error_png);
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& r : rows) {
    nlohmann::json row = {{"case", r.label}, {"wall_time_s", r.summary.value("wall_time_s", nlohmann::json())},
                          {"steps", r.summary.value("steps", nlohmann::json())}};
    if (!r.pass.empty()) row["pass"] = r.pass;
    for (const auto& [k, v] : r.parameters) row[k] = v;
    for (const auto& [k, v] : r.computed) row[k] = v;
    row[field_column(s.result_field())] = row_number(r, field_column(s.result_field()));
    for (const auto& f : s.extra_result_fields()) {
      const double v = row_number(r, field_column(f));
      row[field_column(f)] = std::isnan(v) ? nlohmann::json() : nlohmann::json(v);
    }
    runs.push_back(row);
  }
  write_json(o.out_dir + "/summary.json",
             {{"study", s.name()}, {"scene", o.scene_file}, {"reference_value", s.reference_value()},
              {"compared_with_last_case", s.compare_with_last_case()}, {"reference_source", s.reference_source()},
              {"cases", runs}, {"cases_completed", rows.size()}, {"cases_planned", o.runs_planned},
              {"checks", checks}, {"orderings", orderings}});
  write_study_html(o, rows, figures, tables);
}

}  // namespace cosim
