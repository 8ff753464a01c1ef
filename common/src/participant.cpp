#include "cosim/participant.hpp"

#include <chrono>

#include "cosim/error.hpp"
#include "cosim/interrupt.hpp"
#include "cosim/parallel.hpp"
#include "cosim/progress.hpp"
#include "cosim/result_references.hpp"

namespace cosim {
namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

RunRecord::RunRecord(const LoadedScene& loaded, std::string out_dir, const std::string& program)
    : out_dir_(std::move(out_dir)), start_s_(now_s()) {
  references_ = loaded.message.references();
  make_folder(out_dir_);
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& [k, v] : loaded.overrides) overrides[k] = v;
  summary_ = {{"scene", loaded.message.name()}, {"scene_file", loaded.file},
              {"revision", source_revision()}, {"participants", {program}},
              {"threads", max_threads()},       {"status", "running"},
              {"overrides", overrides},         {"results", nlohmann::json::object()}};
}

double RunRecord::wall_s() const { return now_s() - start_s_; }

CsvWriter& RunRecord::series(const std::string& file, const std::vector<std::string>& columns) {
  if (series_.count(file)) throw Error(path(file) + ": the run opened this series twice");
  auto& slot = series_[file];
  slot = std::make_unique<CsvWriter>(path(file), columns);
  return *slot;
}

void RunRecord::flush_series() {
  for (auto& [file, csv] : series_)
    if (csv) csv->flush();
}

void RunRecord::close_series() {
  for (auto& [file, csv] : series_) csv.reset();
}

void RunRecord::plot(const std::string& csv_file, const std::string& png_file, int x_column,
                     const std::vector<PlotSeries>& series, const std::string& title, const std::string& x_label,
                     const std::string& y_label, const std::string& extra_commands) {
  if (plot_csv(path(csv_file), path(png_file), x_column, series, title, x_label, y_label, extra_commands))
    summary_["plots"].push_back(png_file);
}

void RunRecord::plot_map(const std::string& csv_file, const std::string& png_file, int x_column, int y_column,
                         int value_column, const std::string& title, const std::string& x_label,
                         const std::string& y_label, const std::string& value_label) {
  if (plot_csv_map(path(csv_file), path(png_file), x_column, y_column, value_column, title, x_label, y_label,
                   value_label))
    summary_["plots"].push_back(png_file);
}

void RunRecord::write(const std::string& status, double sim_time_s, std::uint64_t steps) {
  summary_["status"] = status;
  summary_["wall_time_s"] = wall_s();
  summary_["sim_time_s"] = sim_time_s;
  summary_["steps"] = steps;
  if (!references_.empty()) summary_["comparison"] = compare_with_references(references_, summary_["results"]);
  write_json(path("summary.json"), summary_);
}

nlohmann::json run_participant(Participant& p, RunRecord& record, const std::string& label, bool quiet) {
  bool finalized = false;
  try {
    const double planned_end_s = p.initialize(record);
    Progress progress(label, planned_end_s, quiet);
    while (p.advance()) {
      p.output(record);
      progress.update(p.time_s(), p.steps());
      if (interrupt_requested())
        throw Error("interrupted by a signal at step " + std::to_string(p.steps()) + ", t = " +
                    number_text(p.time_s()) + " s");
    }
    p.finalize(record);
    finalized = true;
    progress.finish(p.time_s(), p.steps());
    record.close_series();
    p.finish_peers();
    try {
      p.plots(record);
    } catch (const std::exception&) {
      // Pictures are a convenience; the numbers are on disk.
    }
    record.write(p.end_status(), p.time_s(), p.steps());
    return record.summary();
  } catch (const std::exception& e) {
    const std::string reason = e.what();
    record.flush_series();
    p.abort(reason);
    if (!finalized) {
      try {
        p.finalize(record);  // what the run can still tell, up to its last step
      } catch (const std::exception&) {
      }
    }
    record.close_series();
    try {
      p.plots(record);
    } catch (const std::exception&) {
    }
    record.summary()["error"] = reason;
    record.write("failed", p.time_s(), p.steps());
    throw Error(reason);
  }
}

}  // namespace cosim
