#include "study.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/process.hpp"
#include "snow_sph/scene.hpp"

namespace cosim {

std::vector<std::string> participants(const scene::Scene& scene) {
  std::vector<std::string> list;
  if (scene.has_sph()) list.push_back("snow_sph");
  if (list.empty()) throw Error("scene '" + scene.name() + "' has nothing to run (no sph terrain)");
  return list;
}

void check_scene(const LoadedScene& scene) {
  ValidationReport report;
  snow_sph::validate_sph_scene(scene, report);
  report.throw_if_failed();
}

int run_scene_processes(const RunRequest& request) {
  const auto scene = load_scene(request.scene_file, request.sets);
  check_scene(*scene);
  const auto programs = participants(scene->message);
  std::fprintf(stderr, "cosim: scene '%s' needs: %s alone (no tyre, no DDS)\n",
               scene->message.name().c_str(), programs.front().c_str());
  std::vector<std::string> args{request.scene_file, "--out", request.out_dir};
  for (const auto& s : request.sets) args.insert(args.end(), {"--set", s});
  if (request.quiet) args.push_back("--quiet");
  if (request.no_vtk) args.push_back("--no-vtk");
  const int code = run_child(executable_folder() + "/" + programs.front(), args);
  if (code != 0) std::fprintf(stderr, "cosim: %s exited with code %d\n", programs.front().c_str(), code);
  return code;
}

namespace {

std::string csv_number(const nlohmann::json& v) {
  if (!v.is_number()) return "";
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v.get<double>());
  return b;
}

void plot(const std::string& dir, const std::string& field, const std::string& title) {
  const std::string script = dir + "/error_vs_runtime.gp";
  std::ofstream gp(script);
  gp << "set terminal pngcairo size 900,600 font ',11'\n"
     << "set output '" << dir << "/error_vs_runtime.png'\n"
     << "set datafile separator ','\n"
     << "set title '" << title << "'\n"
     << "set xlabel 'wall time [s]'\nset ylabel '|error| in " << field << " [%]'\n"
     << "set logscale x\nset grid\nset key off\nset offsets graph 0.05, graph 0.15, graph 0.1, graph 0.1\n"
     << "plot '" << dir << "/table.csv' using 5:(abs($8)*100) every ::1 with linespoints pt 7 ps 1.5 lw 2, "
     << "'' using 5:(abs($8)*100):1 every ::1 with labels offset 0,1.2\n";
  gp.close();
  const int code = std::system(("gnuplot '" + script + "' 2>&1").c_str());
  if (code != 0) throw Error("gnuplot failed on " + script + " (is gnuplot installed? scripts/setup.sh installs it)");
}

}  // namespace

int run_study(const std::string& study_file, const std::string& out_dir, bool no_vtk) {
  const auto study = load_study(study_file);
  const auto& s = study->message;
  const auto loc = study->locator();
  ValidationReport report;
  if (s.scene().empty()) report.fail(loc.where("scene"), "a study needs a scene");
  if (s.cases_size() == 0) report.fail(loc.where("cases"), "a study needs cases");
  if (s.result_field().empty()) report.fail(loc.where("result_field"), "name the summary result to compare");
  report.throw_if_failed();
  const std::string scene_file = folder_of(study_file) + "/" + s.scene();
  make_folder(out_dir);
  // Validate every case before running any.
  for (int c = 0; c < s.cases_size(); ++c) {
    std::vector<std::string> sets(s.cases(c).set().begin(), s.cases(c).set().end());
    check_scene(*load_scene(scene_file, sets));
  }
  std::ofstream table(out_dir + "/table.csv");
  table << "case,particle_spacing_m,particles,steps,wall_time_s," << s.result_field()
        << ",reference,relative_error\n";
  nlohmann::json rows = nlohmann::json::array();
  for (int c = 0; c < s.cases_size(); ++c) {
    const auto& k = s.cases(c);
    RunRequest request{scene_file, out_dir + "/" + k.label(),
                       std::vector<std::string>(k.set().begin(), k.set().end()), false, no_vtk};
    std::fprintf(stderr, "cosim study: case %d/%d '%s'\n", c + 1, s.cases_size(), k.label().c_str());
    const int code = run_scene_processes(request);
    if (code != 0) throw Error("study case '" + k.label() + "' failed (exit code " + std::to_string(code) + ")");
    const auto summary = nlohmann::json::parse(read_file(request.out_dir + "/summary.json"));
    const auto& result = summary["results"][s.result_field()];
    if (!result.is_number())
      throw Error(loc.where("result_field") + ": summary of case '" + k.label() + "' has no result '" +
                  s.result_field() + "'");
    const double value = result.get<double>();
    const double error = s.reference_value() != 0 ? (value - s.reference_value()) / s.reference_value() : 0.0;
    table << k.label() << "," << csv_number(summary["particle_spacing_m"]) << ","
          << summary["particles"].get<long>() << "," << summary["steps"].get<long>() << ","
          << csv_number(summary["wall_time_s"]) << "," << csv_number(result) << ","
          << s.reference_value() << "," << csv_number(error) << "\n";
    table.flush();
    rows.push_back({{"case", k.label()}, {"wall_time_s", summary["wall_time_s"]},
                    {s.result_field(), value}, {"relative_error", error},
                    {"particles", summary["particles"]}, {"steps", summary["steps"]}});
  }
  table.close();
  write_json(out_dir + "/summary.json", {{"study", s.name()}, {"scene", scene_file},
                                         {"reference_value", s.reference_value()},
                                         {"reference_source", s.reference_source()}, {"cases", rows}});
  plot(out_dir, s.result_field(), s.name() + ": error against run time");
  std::fprintf(stderr, "cosim study: wrote %s/table.csv and %s/error_vs_runtime.png\n", out_dir.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace cosim
