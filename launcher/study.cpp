#include "study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/process.hpp"
#include "cosim/result_references.hpp"
#include "coupled_run.hpp"
#include "study_report.hpp"
#include "study_table.hpp"
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
  if (request.restart_on_failure > 0 && programs.size() == 1)
    throw Error(request.scene_file + ": --restart-on-failure restarts the processes of a coupled run; this scene runs " +
                programs.front() + " alone (restart it with --restart)");
  if (programs.size() > 1) return run_coupled(request, *scene);
  const char* why = programs.front() == "tyre_fe" ? "(tyre on a rigid road: no SPH, no DDS)"
                                                  : "(no tyre, no DDS)";
  std::fprintf(stderr, "cosim: scene '%s' needs: %s alone %s\n", scene->message.name().c_str(),
               programs.front().c_str(), why);
  std::vector<std::string> args{request.scene_file, "--out", request.out_dir};
  for (const auto& s : request.sets) args.insert(args.end(), {"--set", s});
  if (request.quiet) args.push_back("--quiet");
  if (request.no_vtk) args.push_back("--no-vtk");
  if (request.restart) args.push_back("--restart");
  if (request.mesh_only) {
    if (programs.front() != "tyre_fe") throw Error("--mesh-only applies to tyre scenes");
    args.push_back("--mesh-only");
  }
  const int code = run_child(executable_folder() + "/" + programs.front(), args);
  if (code != 0) std::fprintf(stderr, "cosim: %s exited with code %d\n", programs.front().c_str(), code);
  return code;
}

namespace {

// The case's earlier run, if it completed with the same overrides.
nlohmann::json completed_before(const std::string& case_dir, const LoadedScene& scene) {
  const std::string file = case_dir + "/summary.json";
  if (!std::ifstream(file)) return nullptr;
  nlohmann::json summary;
  try {
    summary = nlohmann::json::parse(read_file(file));
  } catch (const std::exception&) {
    return nullptr;  // cut short while written: run it again
  }
  // Settings that change how a run is carried, not what it computes: a case run
  // by hand on another DDS domain, with checkpoints or a longer step timeout, is
  // the study's case (a coupled run reproduces bit for bit whatever they are).
  static const char* const carriage[] = {"coupling.domain_id", "coupling.step_timeout_s",
                                         "output.checkpoint_interval_s"};
  auto physics = [](nlohmann::json o) {
    if (o.is_object())
      for (const char* key : carriage) o.erase(key);
    return o;
  };
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& [k, v] : scene.overrides) overrides[k] = v;
  if (summary.value("status", "") != "completed" ||
      physics(summary.value("overrides", nlohmann::json())) != physics(overrides))
    return nullptr;
  return summary;
}

std::string assignment(const std::string& field, double value) {
  char b[64];
  std::snprintf(b, sizeof b, "=%.17g", value);
  return field + b;
}

int case_index(const std::vector<scene::StudyCase>& cases, const std::string& label) {
  for (std::size_t c = 0; c < cases.size(); ++c)
    if (cases[c].label() == label) return static_cast<int>(c);
  return -1;
}

// A result of an earlier case's run, or null.
const nlohmann::json* earlier_result(const std::vector<nlohmann::json>& summaries, int c, const std::string& result) {
  if (c < 0 || c >= static_cast<int>(summaries.size()) || summaries[c].is_null()) return nullptr;
  const nlohmann::json* v = result_at(summaries[c]["results"], result);
  return v && v->is_number() ? v : nullptr;
}

// The rolling radius an earlier case measured: a coupled run nests the tyre's
// results under "tyre", a tyre on the road has them at the top.
const nlohmann::json* measured_rolling_radius(const std::vector<nlohmann::json>& summaries, int c) {
  const nlohmann::json* r = earlier_result(summaries, c, "tyre.rolling_radius_m");
  return r ? r : earlier_result(summaries, c, "rolling_radius_m");
}

// The case's own sets, then those derived from earlier cases' results, then the
// spin of its slip ratio (thesis eq. 5.1). `earlier` null: placeholders (1) for
// the derived values, to validate the fields before anything runs. Throws if an
// earlier case it needs has not completed.
std::vector<std::string> case_sets(const std::vector<scene::StudyCase>& cases, int c,
                                   const std::vector<nlohmann::json>* earlier, const std::string& study_file,
                                   double forward_speed_m_per_s, bool coupled) {
  const auto& k = cases[c];
  std::vector<std::string> sets(k.set().begin(), k.set().end());
  auto missing = [&](const std::string& label, const std::string& result) {
    return Error("study case '" + k.label() + "': case '" + label + "' has no result '" + result +
                 "' (not completed in this pass: run it too, or give it with --case)");
  };
  for (const auto& d : k.derived()) {
    double value = 1.0;
    if (earlier) {
      const nlohmann::json* v = earlier_result(*earlier, case_index(cases, d.from_case()), d.result());
      if (!v) throw missing(d.from_case(), d.result());
      value = v->get<double>();
    }
    sets.push_back(assignment(d.field(), (d.scale() != 0.0 ? d.scale() : 1.0) * value));
  }
  if (k.has_slip_ratio()) {
    double r = 1.0;
    if (earlier) {
      const nlohmann::json* v = measured_rolling_radius(*earlier, case_index(cases, k.rolling_radius_case()));
      if (!v) throw missing(k.rolling_radius_case(), "tyre.rolling_radius_m");
      r = v->get<double>();
    }
    sets.push_back(assignment("tyre.rim.angular_velocity_rad_per_s", forward_speed_m_per_s / (r * (1.0 - k.slip_ratio()))));
    if (coupled) {  // F5 = RRM / r is the coupler's
      sets.push_back(assignment("coupling.rolling_radius_m", r));
      sets.push_back("coupling.rolling_radius_source=case '" + k.rolling_radius_case() + "' of " + study_file +
                     " (its tyre rolling_radius_m, zero traction)");
    }
  }
  return sets;
}

void validate_study(const scene::Study& s, const std::vector<scene::StudyCase>& cases, const FieldLocator& loc,
                    const std::string& pass) {
  ValidationReport report;
  if (s.scene().empty()) report.fail(loc.where("scene"), "a study needs a scene");
  if (cases.empty()) report.fail(loc.where("cases"), "a study needs cases (or grids)");
  if (s.result_field().empty()) report.fail(loc.where("result_field"), "name the summary result to compare");
  std::map<std::string, int> seen;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const auto& k = cases[c];
    const bool explicit_case = static_cast<int>(c) < s.cases_size();
    const std::string at = explicit_case ? loc.child("cases", static_cast<int>(c)).where("label")
                                         : loc.where("grids") + " (case '" + k.label() + "')";
    if (k.label().empty()) report.fail(at, "a case needs a label");
    if (seen.count(k.label())) report.fail(at, "label '" + k.label() + "' is used twice");
    seen[k.label()] = static_cast<int>(c);
    for (const auto& p : k.parameter())
      if (p.find('=') == std::string::npos || p.front() == '=')
        report.fail(at, "parameter '" + p + "' is not COLUMN=VALUE");
    if (!explicit_case) continue;
    const auto cl = loc.child("cases", static_cast<int>(c));
    for (int d = 0; d < k.derived_size(); ++d) {
      const int from = case_index(cases, k.derived(d).from_case());
      if (from < 0 || from >= static_cast<int>(c))
        report.fail(cl.child("derived", d).where("from_case"),
                    "'" + k.derived(d).from_case() + "' is not the label of an earlier case");
    }
    if (k.has_slip_ratio()) {
      const int from = case_index(cases, k.rolling_radius_case());
      if (from < 0 || from >= static_cast<int>(c))
        report.fail(cl.where("rolling_radius_case"),
                    "a case with a slip ratio needs the label of an earlier case that measured the rolling radius");
      if (!(k.slip_ratio() < 1.0)) report.fail(cl.where("slip_ratio"), "must be below 1 (eq. 5.1: w = v / (r (1 - sigma)))");
    }
  }
  if (!s.slip_radius_case().empty() && case_index(cases, s.slip_radius_case()) < 0)
    report.fail(loc.where("slip_radius_case"), "'" + s.slip_radius_case() + "' is not the label of a case");
  for (int p = 0; p < s.passes_size(); ++p)
    if (s.passes(p).name().empty()) report.fail(loc.child("passes", p).where("name"), "a pass needs a name");
  if (!pass.empty()) {
    bool known = false;
    std::string names;
    for (const auto& p : s.passes()) known = known || p.name() == pass, names += " " + p.name();
    if (!known)
      report.fail(loc.where("passes"), "--pass " + pass + ": the study's passes are" + (names.empty() ? " none" : names));
  }
  report.throw_if_failed();
}

// The passes to go through: the study's, or one unnamed pass without overrides.
std::vector<scene::StudyPass> passes_of(const scene::Study& s) {
  if (s.passes_size() == 0) return {scene::StudyPass()};
  return {s.passes().begin(), s.passes().end()};
}

std::string pass_dir(const std::string& out_dir, const scene::StudyPass& pass) {
  return pass.name().empty() ? out_dir : out_dir + "/" + pass.name();
}

struct StudyPlan {
  const scene::Study& study;
  std::vector<scene::StudyCase> cases;
  std::string study_file, scene_file;
  bool coupled = false;
};

// The overrides of case c in `pass` (the pass's, then the case's), given the
// pass's summaries so far; throws if an earlier case it needs is missing.
std::vector<std::string> pass_case_sets(const StudyPlan& plan, const scene::StudyPass& pass, int c,
                                        const std::vector<nlohmann::json>* earlier) {
  std::vector<std::string> sets(pass.set().begin(), pass.set().end());
  // The rim's speed of the case (eq. 5.1) as the pass and the case's own sets leave it.
  std::vector<std::string> plain = sets;
  plain.insert(plain.end(), plan.cases[c].set().begin(), plan.cases[c].set().end());
  const double v = load_scene(plan.scene_file, plain)->message.tyre().rim().forward_speed_m_per_s();
  const auto own = case_sets(plan.cases, c, earlier, plan.study_file, v, plan.coupled);
  sets.insert(sets.end(), own.begin(), own.end());
  return sets;
}

// The case's scene in the pass, given the pass's summaries so far; nullptr
// while an earlier case it takes results from has not completed.
std::unique_ptr<LoadedScene> case_scene(const StudyPlan& plan, const scene::StudyPass& pass, int c,
                                        const std::vector<nlohmann::json>& summaries) {
  try {
    return load_scene(plan.scene_file, pass_case_sets(plan, pass, c, &summaries));
  } catch (const Error&) {
    return nullptr;
  }
}

// Every completed run of the pass in DIR, as rows (cases whose earlier cases
// are missing are left out), with the computed slip ratio.
void gather_pass(const StudyPlan& plan, const scene::StudyPass& pass, const std::string& out_dir,
                 std::vector<StudyRow>& rows) {
  const auto& s = plan.study;
  std::vector<nlohmann::json> summaries(plan.cases.size());
  std::vector<double> speed(plan.cases.size(), 0.0);
  const std::size_t first = rows.size();
  for (std::size_t c = 0; c < plan.cases.size(); ++c) {
    const auto scene = case_scene(plan, pass, static_cast<int>(c), summaries);
    if (!scene) continue;
    summaries[c] = completed_before(pass_dir(out_dir, pass) + "/" + plan.cases[c].label(), *scene);
    if (summaries[c].is_null()) continue;
    speed[c] = scene->message.tyre().rim().forward_speed_m_per_s();
    StudyRow row{pass.name(), plan.cases[c].label(), {}, {}, summaries[c]};
    for (const auto& p : plan.cases[c].parameter()) {
      const auto eq = p.find('=');
      row.parameters[p.substr(0, eq)] = p.substr(eq + 1);
    }
    std::vector<std::string> fields(s.extra_result_fields().begin(), s.extra_result_fields().end());
    fields.push_back(s.result_field());
    for (const auto& f : fields)  // named columns: COLUMN=PATH
      if (field_column(f) != f) {
        // A run without the result leaves the column to a result of that name, if any
        // (a tyre on the road has its spin_rate_rad_per_s at the top, not under "tyre").
        const double v = row_number(row, field_path(f));
        if (!std::isnan(v)) row.computed[field_column(f)] = v;
      }
    rows.push_back(std::move(row));
  }
  if (s.slip_radius_case().empty()) return;
  // Eq. 5.1 with each run's mean spin and the reference case's rolling radius.
  const nlohmann::json* r = measured_rolling_radius(summaries, case_index(plan.cases, s.slip_radius_case()));
  if (!r) return;
  for (std::size_t i = first; i < rows.size(); ++i) {
    const int c = case_index(plan.cases, rows[i].label);
    double omega = row_number(rows[i], "tyre.spin_rate_rad_per_s");
    if (std::isnan(omega)) omega = row_number(rows[i], "spin_rate_rad_per_s");
    if (std::isnan(omega) || omega == 0.0) continue;
    rows[i].computed["slip_ratio"] = 1.0 - speed[c] / (r->get<double>() * omega);
    rows[i].computed["slip_radius_m"] = r->get<double>();
  }
}

std::vector<StudyRow> gather(const StudyPlan& plan, const std::string& out_dir) {
  std::vector<StudyRow> rows;
  for (const auto& pass : passes_of(plan.study)) gather_pass(plan, pass, out_dir, rows);
  if (plan.study.has_f5_radius()) apply_f5_radius(plan.study.f5_radius(), rows);
  return rows;
}

// Runs the cases of one pass; a case that completed before with the same
// overrides is kept when resuming.
void run_pass(const StudyPlan& plan, const scene::StudyPass& pass, const StudyRequest& request) {
  const auto& s = plan.study;
  std::vector<nlohmann::json> summaries(plan.cases.size());
  const std::string prefix = pass.name().empty() ? "" : "pass '" + pass.name() + "': ";
  const int n = static_cast<int>(plan.cases.size());
  for (int c = 0; c < n; ++c) {
    const auto& k = plan.cases[c];
    const auto& only = request.cases;
    if (!only.empty() && std::find(only.begin(), only.end(), k.label()) == only.end()) {
      // Not to be run: its completed run in DIR, if any, for the cases that depend on it.
      if (const auto scene = case_scene(plan, pass, c, summaries))
        summaries[c] = completed_before(pass_dir(request.out_dir, pass) + "/" + k.label(), *scene);
      continue;
    }
    RunRequest run{plan.scene_file, pass_dir(request.out_dir, pass) + "/" + k.label(),
                   pass_case_sets(plan, pass, c, &summaries), false, request.no_vtk};
    const auto scene = load_scene(plan.scene_file, run.sets);
    nlohmann::json earlier = request.resume ? completed_before(run.out_dir, *scene) : nullptr;
    if (!earlier.is_null()) {
      std::fprintf(stderr, "cosim study: %scase %d/%d '%s' completed before (%s/summary.json): kept\n", prefix.c_str(),
                   c + 1, n, k.label().c_str(), run.out_dir.c_str());
      summaries[c] = std::move(earlier);
    } else {
      std::fprintf(stderr, "cosim study: %scase %d/%d '%s'\n", prefix.c_str(), c + 1, n, k.label().c_str());
      make_folder(pass_dir(request.out_dir, pass));
      const int code = run_scene_processes(run);
      if (code != 0) throw Error("study case '" + k.label() + "' failed (exit code " + std::to_string(code) + ")");
      summaries[c] = nlohmann::json::parse(read_file(run.out_dir + "/summary.json"));
    }
    // A case of another kind (a tyre on the road in a study on snow) may lack it: its row leaves it empty.
    if (!result_at(summaries[c]["results"], field_path(s.result_field())))
      std::fprintf(stderr, "cosim study: %scase '%s' has no result '%s' (result_field): its row leaves it empty\n",
                   prefix.c_str(), k.label().c_str(), s.result_field().c_str());
  }
}

}  // namespace

std::vector<scene::StudyCase> expand_cases(const scene::Study& s) {
  std::vector<scene::StudyCase> cases(s.cases().begin(), s.cases().end());
  for (const auto& grid : s.grids()) {
    // Odometer over the axes' values, the last axis fastest.
    std::vector<int> at(grid.axes_size(), 0);
    bool empty = grid.axes_size() == 0;
    for (const auto& axis : grid.axes()) empty = empty || axis.values_size() == 0;
    while (!empty) {
      scene::StudyCase k;
      std::string label;
      for (const auto& set : grid.set()) k.add_set(set);
      for (const auto& p : grid.parameter()) k.add_parameter(p);
      for (int a = 0; a < grid.axes_size(); ++a) {
        const auto& value = grid.axes(a).values(at[a]);
        label += (label.empty() ? "" : "_") + (value.label().empty() ? value.value() : value.label());
        for (const auto& set : value.set()) k.add_set(set);
        k.add_parameter(grid.axes(a).column() + "=" + value.value());
      }
      k.set_label(label);
      cases.push_back(std::move(k));
      int a = grid.axes_size() - 1;
      while (a >= 0 && ++at[a] == grid.axes(a).values_size()) at[a--] = 0;
      if (a < 0) break;
    }
  }
  return cases;
}

int run_study(const StudyRequest& request) {
  const auto study = load_study(request.study_file);
  const auto& s = study->message;
  StudyPlan plan{s, expand_cases(s), request.study_file, folder_of(request.study_file) + "/" + s.scene()};
  validate_study(s, plan.cases, study->locator(), request.pass);
  for (const auto& label : request.cases)
    if (case_index(plan.cases, label) < 0) {
      std::string labels;
      for (const auto& k : plan.cases) labels += " " + k.label();
      throw Error(request.study_file + ": --case " + label + ": the study's cases are" + labels);
    }
  make_folder(request.out_dir);
  plan.coupled = load_scene(plan.scene_file, {})->message.has_coupling();
  // Validate every case of every pass before running any.
  for (const auto& pass : passes_of(s))
    for (std::size_t c = 0; c < plan.cases.size(); ++c)
      check_scene(*load_scene(plan.scene_file, pass_case_sets(plan, pass, static_cast<int>(c), nullptr)));
  StudyOutputs outputs{s, request.study_file, plan.scene_file, request.out_dir,
                       static_cast<int>(plan.cases.size() * passes_of(s).size())};
  try {
    for (const auto& pass : passes_of(s))
      if (!request.tabulate_only && (request.pass.empty() || pass.name() == request.pass)) run_pass(plan, pass, request);
  } catch (const Error&) {
    // Nothing completed is lost: what finished is written, and --resume runs the rest.
    const auto rows = gather(plan, request.out_dir);
    if (!rows.empty()) {
      write_study_outputs(outputs, rows);
      std::fprintf(stderr, "cosim study: wrote the %zu completed run(s) to %s/table.csv; `--resume` runs the rest\n",
                   rows.size(), request.out_dir.c_str());
    }
    throw;
  }
  write_study_outputs(outputs, gather(plan, request.out_dir));
  std::fprintf(stderr, "cosim study: wrote %s/table.csv and %s/report.html\n", request.out_dir.c_str(),
               request.out_dir.c_str());
  return 0;
}

}  // namespace cosim
