#include "coupled_run.hpp"
#include "run_report.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/checkpoint.hpp"
#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/process.hpp"
#include "cosim/result_references.hpp"
#include "run_energy.hpp"
#include "study.hpp"

namespace cosim {

std::map<std::string, transport::Vendor> parse_vendor_map(const std::string& text) {
  std::map<std::string, transport::Vendor> vendors{
      {"tyre", transport::Vendor::cyclone}, {"terrain", transport::Vendor::cyclone}, {"coupler", transport::Vendor::cyclone}};
  if (text.find('=') == std::string::npos) {
    const auto v = transport::parse_vendor(text);
    for (auto& [role, vendor] : vendors) vendor = v;
    return vendors;
  }
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    const std::string role = item.substr(0, eq);
    if (eq == std::string::npos || !vendors.count(role))
      throw Error("--dds '" + text + "': '" + item + "' is not role=vendor with a role among tyre, terrain, coupler");
    vendors[role] = transport::parse_vendor(item.substr(eq + 1));
  }
  return vendors;
}

namespace {

nlohmann::json read_json_or_null(const std::string& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception&) {
    return nullptr;
  }
}

std::string hex(std::uint64_t v) {
  char b[32];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

}  // namespace

std::uint64_t newest_common_checkpoint(const std::string& out, std::string& listing) {
  std::set<std::uint64_t> common;
  bool first = true;
  listing.clear();
  for (const auto& [role, program] : coupled_processes) {
    std::set<std::uint64_t> steps;
    std::string list;
    for (const auto& f : list_checkpoints(out + "/" + role, program)) {
      steps.insert(f.step);
      list += (list.empty() ? "" : ", ") + std::to_string(f.step);
    }
    listing += std::string(listing.empty() ? "" : "; ") + program + ": " + (list.empty() ? "none" : list);
    if (first) common = steps;
    else {
      std::set<std::uint64_t> both;
      for (auto e : steps)
        if (common.count(e)) both.insert(e);
      common = both;
    }
    first = false;
  }
  return common.empty() ? 0 : *common.rbegin();
}

namespace {

// What every process of one coupled run is started with, apart from its role.
struct CoupledLaunch {
  std::map<std::string, transport::Vendor> vendors;
  int domain = 0;
  std::string out;           // the run's folder: one folder per role inside
  std::string bin;           // the folder of the three programs
  std::string security_dir;  // absolute; empty: no DDS security
};

CoupledLaunch plan_launch(const RunRequest& request, const LoadedScene& scene) {
  CoupledLaunch launch;
  launch.vendors = parse_vendor_map(request.dds);
  const auto& vendors = launch.vendors;
  // Secured handshakes between Debian's Fast DDS 2.9 and Cyclone DDS 0.10 fail
  // when Fast DDS starts them (Cyclone cannot decode Fast's DH public key:
  // eclipse-cyclonedds/cyclonedds#701, eProsima/Fast-DDS#3259; measured with the
  // transport probe, docs/reliability.md): a secured run uses one vendor.
  if (!request.security_dir.empty() &&
      std::set<transport::Vendor>{vendors.at("tyre"), vendors.at("terrain"), vendors.at("coupler")}.size() > 1)
    throw Error("--security with --dds " + request.dds +
                ": a secured run needs one DDS vendor for every process (Fast DDS 2.9 and Cyclone DDS 0.10 do not "
                "complete each other's secured handshake; docs/reliability.md, \"DDS Security\")");
  launch.domain = request.domain >= 0 ? request.domain : scene.message.coupling().domain_id();
  launch.out = request.out_dir;
  launch.bin = executable_folder();
  launch.security_dir =
      request.security_dir.empty() ? std::string() : std::filesystem::absolute(request.security_dir).string();
  return launch;
}

void prepare_run_folder(const std::string& out) {
  make_folder(out);
  // forces.csv is the coupler's; a link at the top of the run folder finds it.
  std::error_code ignored;
  std::filesystem::remove(out + "/forces.csv", ignored);
  std::filesystem::create_symlink("coupler/forces.csv", out + "/forces.csv", ignored);
}

// A restart continues every process from the newest exchange all three
// checkpointed (docs/reliability.md, "Coupled runs"); 0: a run from the start.
std::uint64_t exchange_to_restart_from(const RunRequest& request, const std::string& out) {
  if (!request.restart) return 0;
  std::string listing;
  const std::uint64_t from_exchange = newest_common_checkpoint(out, listing);
  if (from_exchange == 0)
    throw Error(out + ": no checkpoint common to the coupler, the terrain and the tyre to restart from (" + listing + ")");
  return from_exchange;
}

// The command line of the process of `role`: the solvers get --coupled; the
// tyre alone prints progress.
std::vector<std::string> process_args(const RunRequest& request, const CoupledLaunch& launch, const std::string& role,
                                      std::uint64_t run_id, std::uint64_t from_exchange) {
  const std::string dir = launch.out + "/" + role;
  const bool solver = role != "coupler";
  const bool quiet = role != "tyre";
  std::vector<std::string> a{request.scene_file, "--out", dir,  "--run-id", hex(run_id),
                             "--dds", transport::vendor_name(launch.vendors.at(role)), "--domain",
                             std::to_string(launch.domain)};
  if (solver) a.push_back("--coupled");
  for (const auto& s : request.sets) a.insert(a.end(), {"--set", s});
  if (quiet || request.quiet) a.push_back("--quiet");
  if (request.no_vtk && solver) a.push_back("--no-vtk");
  if (from_exchange > 0) a.insert(a.end(), {"--restart-at", std::to_string(from_exchange)});
  if (!request.security_dir.empty()) a.insert(a.end(), {"--security", launch.security_dir});
  return a;
}

// One attempt: the three processes started under `run_id`, and waited for.
std::vector<ChildResult> run_attempt(const RunRequest& request, const LoadedScene& scene, const CoupledLaunch& launch,
                                     std::uint64_t run_id, std::uint64_t from_exchange) {
  std::fprintf(stderr,
               "cosim: scene '%s' couples the tyre to an SPH terrain: coupler (%s) + snow_sph (%s) + tyre_fe (%s), "
               "DDS domain %d, run %s%s\n",
               scene.message.name().c_str(), transport::vendor_name(launch.vendors.at("coupler")),
               transport::vendor_name(launch.vendors.at("terrain")), transport::vendor_name(launch.vendors.at("tyre")),
               launch.domain, hex(run_id).c_str(),
               from_exchange > 0 ? (", continuing from exchange " + std::to_string(from_exchange)).c_str() : "");
  // A process that fails before it writes its summary must not leave an
  // earlier attempt's in its place (read afterwards as this attempt's).
  std::error_code ignored;
  for (const auto& p : coupled_processes)
    std::filesystem::remove(launch.out + "/" + p.role + "/summary.json", ignored);
  // Each process's results (its stdout) go to its folder, beside its summary.json; its
  // progress and messages (stderr) stay on the terminal. The run's report is printed once, at the end.
  std::vector<ChildSpec> children;
  for (const auto& [role, program] : coupled_processes) {
    std::filesystem::create_directories(launch.out + "/" + role);
    children.push_back({program,
                        launch.bin + "/" + program,
                        process_args(request, launch, role, run_id, from_exchange),
                        {launch.out + "/" + role + "/results.txt", ""}});
  }
  return run_children(children, 10.0);
}

// The process that failed first (null: none failed); `signalled`: the user
// asked the run to stop (a stop signal was passed on to the processes).
const ChildResult* first_failure(const std::vector<ChildResult>& results, bool& signalled) {
  const ChildResult* first_failed = nullptr;
  signalled = false;
  for (const auto& r : results) {
    signalled = signalled || r.signal_forwarded;
    if (r.exit_code != 0 && (!first_failed || r.ended_after_s < first_failed->ended_after_s)) first_failed = &r;
  }
  return first_failed;
}

// The attempts of a run: the last one's processes, its run id, and the restarts
// after a failure that led to it.
struct Attempts {
  std::vector<ChildResult> results;
  std::uint64_t run_id = 0;
  nlohmann::json restarts = nlohmann::json::array();
};

// Runs the processes; after a failure, up to --restart-on-failure times again
// from the newest common checkpoint.
Attempts run_attempts(const RunRequest& request, const LoadedScene& scene, const CoupledLaunch& launch,
                      std::uint64_t from_exchange) {
  Attempts attempts;
  std::string listing;
  for (int attempt = 0;; ++attempt) {
    attempts.run_id = transport::new_run_id();  // a new id: nothing of an earlier attempt is taken for this one's
    attempts.results = run_attempt(request, scene, launch, attempts.run_id, from_exchange);
    bool signalled = false;
    const ChildResult* first_failed = first_failure(attempts.results, signalled);
    // A stop asked for by the user is not a failure to recover from.
    if (!first_failed || signalled || attempt >= request.restart_on_failure) break;
    const std::uint64_t next = newest_common_checkpoint(launch.out, listing);
    if (next == 0) {
      std::fprintf(stderr, "cosim: %s ended with code %d and there is no common checkpoint to restart from (%s)\n",
                   first_failed->name.c_str(), first_failed->exit_code, listing.c_str());
      break;
    }
    std::fprintf(stderr, "cosim: %s ended with code %d after %.1f s; restarting every process from exchange %llu "
                 "(restart %d of at most %d)\n", first_failed->name.c_str(), first_failed->exit_code,
                 first_failed->ended_after_s, static_cast<unsigned long long>(next), attempt + 1,
                 request.restart_on_failure);
    attempts.restarts.push_back({{"failed", first_failed->name}, {"exit_code", first_failed->exit_code},
                                 {"after_s", first_failed->ended_after_s}, {"from_exchange", next},
                                 {"run_id", hex(attempts.run_id)}});
    from_exchange = next;
  }
  return attempts;
}

// The summaries the three processes wrote (null: one wrote none).
struct ProcessSummaries {
  nlohmann::json coupler, tyre, terrain;
};

ProcessSummaries read_process_summaries(const std::string& out) {
  return {read_json_or_null(out + "/coupler/summary.json"), read_json_or_null(out + "/tyre/summary.json"),
          read_json_or_null(out + "/terrain/summary.json")};
}

// Each process's exit and status, and the launcher's exit code from them.
struct ProcessTable {
  nlohmann::json participants = nlohmann::json::object();
  int code = 0;
  bool all_completed = true;
};

ProcessTable process_table(const std::vector<ChildResult>& results, const CoupledLaunch& launch,
                           const ProcessSummaries& summaries) {
  ProcessTable table;
  for (const auto& r : results) {
    std::string role;
    for (const auto& p : coupled_processes)
      if (r.name == p.program) role = p.role;
    const nlohmann::json& own =
        role == "tyre" ? summaries.tyre : role == "terrain" ? summaries.terrain : summaries.coupler;
    table.participants[r.name] = {{"dds", transport::vendor_name(launch.vendors.at(role))},
                                  {"exit_code", r.exit_code}, {"ended_after_s", r.ended_after_s},
                                  {"terminated_by_launcher", r.terminated_by_us},
                                  {"status", own.is_object() ? own.value("status", "unknown") : "no summary"},
                                  {"summary", role + "/summary.json"}};
    if (own.is_object() && own.contains("error")) table.participants[r.name]["error"] = own["error"];
    if (r.exit_code != 0) {
      table.all_completed = false;
      // A participant killed by a signal (128 + n) is the run's failure (2), not
      // the launcher's own death by that signal, which a shell would read it as.
      if (table.code == 0) table.code = r.exit_code < 128 ? r.exit_code : 2;
      std::fprintf(stderr, "cosim: %s ended with code %d after %.1f s%s\n", r.name.c_str(), r.exit_code,
                   r.ended_after_s, r.terminated_by_us ? " (terminated by the launcher)" : "");
    }
  }
  return table;
}

// The run's results: the coupler's (the force decomposition), the terrain's
// beside them (the rut and the deepest penetration), the tyre's under "tyre".
nlohmann::json merged_results(const ProcessSummaries& s) {
  nlohmann::json results_json = nlohmann::json::object();
  if (s.coupler.is_object() && s.coupler.contains("results")) results_json = s.coupler["results"];
  // The terrain's results at the top level too; a key the coupler has keeps the coupler's value.
  if (s.terrain.is_object() && s.terrain.contains("results") && results_json.is_object())
    for (const auto& [k, v] : s.terrain["results"].items())
      if (!results_json.contains(k)) results_json[k] = v;
  if (s.tyre.is_object() && s.tyre.contains("results"))
    for (const auto& [k, v] : s.tyre["results"].items()) results_json["tyre"][k] = v;
  return results_json;
}

// The run's speed and what the coupling did (docs/coupling.md).
nlohmann::json merged_performance(const ProcessSummaries& s) {
  nlohmann::json performance = nlohmann::json::object();
  if (s.coupler.is_object() && s.coupler.contains("performance")) performance = s.coupler["performance"];
  if (s.terrain.is_object() && s.terrain.contains("performance"))
    for (const char* k : {"active_particle_share", "active_domain_margin_m", "compute_s_per_step"})
      if (s.terrain["performance"].contains(k))
        performance[std::string(k == std::string("compute_s_per_step") ? "terrain_" : "") + k] =
            s.terrain["performance"][k];
  if (s.tyre.is_object() && s.tyre.contains("performance") && s.tyre["performance"].contains("compute_s_per_step"))
    performance["tyre_compute_s_per_step"] = s.tyre["performance"]["compute_s_per_step"];
  return performance;
}

// The run's summary.json from the processes' own, with each process's status;
// prints the results if every process succeeded. Returns the launcher's exit code.
int write_run_summary(const RunRequest& request, const LoadedScene& scene, const CoupledLaunch& launch,
                      const Attempts& attempts, std::uint64_t restarted_from) {
  nlohmann::json summary = {
      {"scene", scene.message.name()}, {"scene_file", scene.file},
      {"revision", source_revision()}, {"run_id", hex(attempts.run_id)}, {"dds_domain", launch.domain},
      {"dds_security", launch.security_dir.empty() ? nlohmann::json() : nlohmann::json(launch.security_dir)}};
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& [k, v] : scene.overrides) overrides[k] = v;
  summary["overrides"] = overrides;
  const ProcessSummaries own = read_process_summaries(launch.out);
  const ProcessTable table = process_table(attempts.results, launch, own);
  summary["participants"] = table.participants;
  if (!attempts.restarts.empty()) summary["restarts_after_failure"] = attempts.restarts;
  if (request.restart) summary["restarted_from_exchange"] = restarted_from;
  const nlohmann::json results_json = merged_results(own);
  summary["results"] = results_json;
  // The coupler's wall time counts the attempts before a restart up to the
  // checkpoint it continued from (cosim::RunRecord): what the whole run cost.
  for (const char* k : {"wall_time_s", "wall_time_this_attempt_s", "sim_time_s", "steps", "time_step", "friction",
                        "rejected_samples"})
    if (own.coupler.is_object() && own.coupler.contains(k)) summary[k] = own.coupler[k];
  if (own.terrain.is_object()) summary["particles"] = own.terrain.value("particles", nlohmann::json());
  if (own.tyre.is_object()) summary["elements"] = own.tyre.value("elements", nlohmann::json());
  const nlohmann::json performance = merged_performance(own);
  summary["performance"] = performance;
  summary["status"] = table.all_completed ? "completed" : "failed";
  if (scene.message.references_size() > 0)
    summary["comparison"] = compare_with_references(scene.message.references(), results_json);
  const nlohmann::json energy = coupled_run_energy(launch.out, own.coupler, own.terrain, own.tyre);
  if (!energy.is_null()) summary["energy"] = energy;
  write_json(launch.out + "/summary.json", summary);
  if (table.code == 0) {
    print_run_report({results_json, performance, summary, launch.out + "/summary.json"});
  }
  return table.code;
}

}  // namespace

int run_coupled(const RunRequest& request, const LoadedScene& scene) {
  const CoupledLaunch launch = plan_launch(request, scene);
  prepare_run_folder(launch.out);
  const std::uint64_t restarted_from = exchange_to_restart_from(request, launch.out);
  // Three processes share the cores and wait on each other every step: OpenMP
  // threads that spin while idle would take the core a peer needs (measured: 56
  // against 150 steps/s on 2 cores). A user's own setting is kept.
  setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
  const Attempts attempts = run_attempts(request, scene, launch, restarted_from);
  const int code = write_run_summary(request, scene, launch, attempts, restarted_from);
  // A study prints its progress to stderr between runs; stdout redirected to the same
  // file is block-buffered, so without this a run's results land inside the next run's lines.
  std::fflush(stdout);
  return code;
}

}  // namespace cosim
