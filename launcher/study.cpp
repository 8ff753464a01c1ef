#include "study.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/process.hpp"
#include "cosim/result_references.hpp"
#include "coupled_run.hpp"
#include "coupler/scene_checks.hpp"
#include "snow_sph/scene.hpp"
#include "tyre_fe/run.hpp"

namespace cosim {

std::vector<std::string> participants(const scene::Scene& scene) {
  if (scene.has_tyre() && scene.coupling().terrain() == "rigid_road") return {"tyre_fe"};
  if (scene.has_sph() && has_fe_body(scene)) {
    if (scene.coupling().terrain().empty())
      throw Error("scene '" + scene.name() + "' has an FE body and an SPH terrain but no `coupling { terrain: ... }`");
    return {"coupler", "snow_sph", "tyre_fe"};
  }
  if (scene.has_tyre()) return {"tyre_fe"};
  if (scene.has_sph()) return {"snow_sph"};
  throw Error("scene '" + scene.name() + "' has nothing to run (no `sph` terrain, no `tyre` or `tread_block`)");
}

void check_scene(const LoadedScene& scene) {
  ValidationReport report;
  // A tyre on the rigid road ignores the scene's terrain blocks.
  if (scene.message.coupling().terrain() != "rigid_road") snow_sph::validate_sph_scene(scene, report);
  tyre_fe::validate_fe_body_scene(scene, report);
  coupler::validate_coupling_scene(scene, report);
  report.throw_if_failed();
}

int run_scene_processes(const RunRequest& request) {
  const auto scene = load_scene(request.scene_file, request.sets);
  check_scene(*scene);
  const auto programs = participants(scene->message);
  if (programs.size() > 1) return run_coupled(request, *scene);
  const char* why = programs.front() == "tyre_fe" ? "(tyre on a rigid road: no SPH, no DDS)"
                                                  : "(no tyre, no DDS)";
  std::fprintf(stderr, "cosim: scene '%s' needs: %s alone %s\n", scene->message.name().c_str(),
               programs.front().c_str(), why);
  std::vector<std::string> args{request.scene_file, "--out", request.out_dir};
  for (const auto& s : request.sets) args.insert(args.end(), {"--set", s});
  if (request.quiet) args.push_back("--quiet");
  if (request.no_vtk) args.push_back("--no-vtk");
  if (request.mesh_only) {
    if (programs.front() != "tyre_fe") throw Error("--mesh-only applies to tyre scenes");
    args.push_back("--mesh-only");
  }
  const int code = run_child(executable_folder() + "/" + programs.front(), args);
  if (code != 0) std::fprintf(stderr, "cosim: %s exited with code %d\n", programs.front().c_str(), code);
  return code;
}

namespace {

std::string csv_number(const nlohmann::json& v) {
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";  // e.g. plate_at_rest
  if (!v.is_number()) return "";
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v.get<double>());
  return b;
}

void plot(const std::string& dir, const std::string& field, const std::string& title) {
  PlotOptions o;
  o.title = title, o.x_label = "wall time [s]", o.y_label = "|error| in " + field + " [%]";
  o.log_x = true, o.key = false;
  o.extra_commands = "set offsets graph 0.05, graph 0.15, graph 0.1, graph 0.1\n";
  const std::string table = dir + "/table.csv";
  if (!plot_png(dir + "/error_vs_runtime.png", o,
                {{table, "6:(abs($9)*100)", "linespoints pt 7 ps 1.5 lw 2", ""},
                 {table, "6:(abs($9)*100):1", "labels offset 0,1.2", ""}}))
    throw Error("gnuplot failed on " + dir + "/error_vs_runtime.png (is gnuplot installed? scripts/setup.sh installs it)");
}

// The case's earlier run, if it completed with the same overrides (cosim study --resume).
nlohmann::json completed_before(const std::string& case_dir, const LoadedScene& scene) {
  const std::string file = case_dir + "/summary.json";
  if (!std::ifstream(file)) return nullptr;
  nlohmann::json summary;
  try {
    summary = nlohmann::json::parse(read_file(file));
  } catch (const std::exception&) {
    return nullptr;  // cut short while written: run it again
  }
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& [k, v] : scene.overrides) overrides[k] = v;
  if (summary.value("status", "") != "completed" || summary.value("overrides", nlohmann::json()) != overrides)
    return nullptr;
  return summary;
}

// table.csv, summary.json and the plot of the cases in `summaries` (the first ones of the study).
void tabulate(const scene::Study& s, const std::string& out_dir, const std::string& scene_file,
              const std::vector<nlohmann::json>& summaries) {
  const double reference = s.compare_with_last_case()
                               ? summaries.back()["results"][s.result_field()].get<double>()
                               : s.reference_value();
  std::ofstream table(out_dir + "/table.csv");
  table << "case,particle_spacing_m,size,time_step_s,steps,wall_time_s," << s.result_field()
        << ",reference,relative_error";
  for (const auto& f : s.extra_result_fields()) table << "," << f;
  table << "\n";
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t c = 0; c < summaries.size(); ++c) {
    const auto& summary = summaries[c];
    const auto& label = s.cases(static_cast<int>(c)).label();
    const auto& result = summary["results"][s.result_field()];
    const double value = result.get<double>();
    const double error = reference != 0 ? (value - reference) / reference : 0.0;
    // size: particles (SPH) or elements (FE); time step: the mean (SPH) or the fixed step (FE).
    const nlohmann::json size = summary.contains("particles") ? summary["particles"] : summary.value("elements", nlohmann::json());
    nlohmann::json dt = summary.value("dt_s", nlohmann::json());
    if (dt.is_object()) dt = dt.value("mean", nlohmann::json());
    table << label << "," << csv_number(summary.value("particle_spacing_m", nlohmann::json())) << ","
          << csv_number(size) << "," << csv_number(dt) << "," << summary["steps"].get<long>() << ","
          << csv_number(summary["wall_time_s"]) << "," << csv_number(result) << "," << reference << ","
          << csv_number(error);
    nlohmann::json row = {{"case", label}, {"wall_time_s", summary["wall_time_s"]}, {s.result_field(), value},
                          {"relative_error", error}, {"size", size}, {"steps", summary["steps"]}};
    for (const auto& f : s.extra_result_fields()) {
      table << "," << csv_number(summary["results"].value(f, nlohmann::json()));
      row[f] = summary["results"].value(f, nlohmann::json());
    }
    table << "\n";
    rows.push_back(row);
  }
  table.close();
  write_json(out_dir + "/summary.json", {{"study", s.name()}, {"scene", scene_file},
                                         {"reference_value", reference}, {"compared_with_last_case", s.compare_with_last_case()},
                                         {"reference_source", s.reference_source()}, {"cases", rows},
                                         {"cases_completed", summaries.size()}, {"cases_planned", s.cases_size()}});
  plot(out_dir, s.result_field(), s.name() + ": error against run time");
}

std::string assignment(const std::string& field, double value) {
  char b[64];
  std::snprintf(b, sizeof b, "=%.17g", value);
  return field + b;
}

int case_index(const scene::Study& s, const std::string& label) {
  for (int c = 0; c < s.cases_size(); ++c)
    if (s.cases(c).label() == label) return c;
  return -1;
}

// The case's own sets, then those derived from earlier cases' results, then the
// spin of its slip ratio (thesis eq. 5.1). `earlier` null: placeholders (1) for
// the derived values, to validate the fields before anything runs.
std::vector<std::string> case_sets(const scene::Study& s, int c, const std::vector<nlohmann::json>* earlier,
                                   const std::string& study_file, double forward_speed_m_per_s, bool coupled) {
  const auto& k = s.cases(c);
  std::vector<std::string> sets(k.set().begin(), k.set().end());
  auto result_of = [&](const std::string& label, const std::string& result) -> double {
    if (!earlier) return 1.0;
    const nlohmann::json* v = result_at((*earlier)[case_index(s, label)]["results"], result);
    if (!v || !v->is_number())
      throw Error("study case '" + k.label() + "': case '" + label + "' has no result '" + result + "'");
    return v->get<double>();
  };
  for (const auto& d : k.derived())
    sets.push_back(assignment(d.field(), (d.scale() != 0.0 ? d.scale() : 1.0) * result_of(d.from_case(), d.result())));
  if (k.has_slip_ratio()) {
    // A coupled run nests the tyre's results under "tyre"; a tyre on the road has them at the top.
    std::string radius_key = "tyre.rolling_radius_m";
    if (earlier && !result_at((*earlier)[case_index(s, k.rolling_radius_case())]["results"], radius_key))
      radius_key = "rolling_radius_m";
    const double r = result_of(k.rolling_radius_case(), radius_key);
    sets.push_back(assignment("tyre.rim.angular_velocity_rad_per_s", forward_speed_m_per_s / (r * (1.0 - k.slip_ratio()))));
    if (coupled) {  // F5 = RRM / r is the coupler's
      sets.push_back(assignment("coupling.rolling_radius_m", r));
      sets.push_back("coupling.rolling_radius_source=case '" + k.rolling_radius_case() + "' of " + study_file +
                     " (its tyre rolling_radius_m, zero traction)");
    }
  }
  return sets;
}

}  // namespace

int run_study(const std::string& study_file, const std::string& out_dir, bool no_vtk, bool resume) {
  const auto study = load_study(study_file);
  const auto& s = study->message;
  const auto loc = study->locator();
  ValidationReport report;
  if (s.scene().empty()) report.fail(loc.where("scene"), "a study needs a scene");
  if (s.cases_size() == 0) report.fail(loc.where("cases"), "a study needs cases");
  if (s.result_field().empty()) report.fail(loc.where("result_field"), "name the summary result to compare");
  for (int c = 0; c < s.cases_size(); ++c) {
    const auto& k = s.cases(c);
    const auto at = loc.child("cases", c);
    for (int d = 0; d < k.derived_size(); ++d) {
      const int from = case_index(s, k.derived(d).from_case());
      if (from < 0 || from >= c)
        report.fail(at.child("derived", d).where("from_case"),
                    "'" + k.derived(d).from_case() + "' is not the label of an earlier case");
    }
    if (k.has_slip_ratio()) {
      const int from = case_index(s, k.rolling_radius_case());
      if (from < 0 || from >= c)
        report.fail(at.where("rolling_radius_case"),
                    "a case with a slip ratio needs the label of an earlier case that measured the rolling radius");
      if (!(k.slip_ratio() < 1.0)) report.fail(at.where("slip_ratio"), "must be below 1 (eq. 5.1: w = v / (r (1 - sigma)))");
    }
  }
  report.throw_if_failed();
  const std::string scene_file = folder_of(study_file) + "/" + s.scene();
  make_folder(out_dir);
  // Validate every case before running any.
  std::vector<std::unique_ptr<LoadedScene>> scenes;
  const bool coupled = load_scene(scene_file, {})->message.has_coupling();
  for (int c = 0; c < s.cases_size(); ++c) {
    scenes.push_back(load_scene(scene_file, case_sets(s, c, nullptr, study_file, 0.0, coupled)));
    check_scene(*scenes.back());
  }
  // Run every case, then tabulate (the last case is the reference when comparing with the finest).
  std::vector<nlohmann::json> summaries;
  try {
    for (int c = 0; c < s.cases_size(); ++c) {
      const auto& k = s.cases(c);
      const bool derived = k.derived_size() > 0 || k.has_slip_ratio();
      RunRequest request{scene_file, out_dir + "/" + k.label(),
                         case_sets(s, c, &summaries, study_file, scenes[c]->message.tyre().rim().forward_speed_m_per_s(),
                                   coupled),
                         false, no_vtk};
      if (derived) scenes[c] = load_scene(scene_file, request.sets);  // the overrides --resume compares
      nlohmann::json earlier = resume ? completed_before(request.out_dir, *scenes[c]) : nullptr;
      if (!earlier.is_null()) {
        std::fprintf(stderr, "cosim study: case %d/%d '%s' completed before (%s/summary.json): kept\n", c + 1,
                     s.cases_size(), k.label().c_str(), request.out_dir.c_str());
        summaries.push_back(std::move(earlier));
      } else {
        std::fprintf(stderr, "cosim study: case %d/%d '%s'\n", c + 1, s.cases_size(), k.label().c_str());
        const int code = run_scene_processes(request);
        if (code != 0) throw Error("study case '" + k.label() + "' failed (exit code " + std::to_string(code) + ")");
        summaries.push_back(nlohmann::json::parse(read_file(request.out_dir + "/summary.json")));
      }
      if (!summaries.back()["results"][s.result_field()].is_number())
        throw Error(loc.where("result_field") + ": summary of case '" + k.label() + "' has no result '" +
                    s.result_field() + "'");
    }
  } catch (const Error& e) {
    // Nothing completed is lost: the finished cases are tabulated, and --resume runs the rest.
    if (!summaries.empty() && summaries.back()["results"][s.result_field()].is_number()) {
      tabulate(s, out_dir, scene_file, summaries);
      std::fprintf(stderr, "cosim study: wrote the %zu completed case(s) to %s/table.csv; `--resume` runs the rest\n",
                   summaries.size(), out_dir.c_str());
    }
    throw;
  }
  tabulate(s, out_dir, scene_file, summaries);
  std::fprintf(stderr, "cosim study: wrote %s/table.csv and %s/error_vs_runtime.png\n", out_dir.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace cosim
