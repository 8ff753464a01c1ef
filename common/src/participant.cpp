#include "cosim/participant.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>

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

// The first multiple of the interval after t (the same in a run and in its restart).
double next_checkpoint_after(double t, double interval) {
  return (std::floor(t / interval * (1.0 + 1e-12)) + 1.0) * interval;
}

// `step`: the participant's step, or for a coupled one the exchanges completed.
void write_checkpoint(Participant& p, RunRecord& record, std::uint64_t step) {
  CheckpointWriter out(record.program(), record.scene_hash(), step, p.time_s());
  record.save(out);
  p.save(out);
  out.commit(checkpoint_path(record.out_dir(), record.program(), step));
  // Two: if the newest were damaged on disk, the one before still restarts the run.
  prune_checkpoints(record.out_dir(), record.program(), 2);
}

// The newest checkpoint of this program that can be read (an older one if the
// newest is damaged); one of another scene is refused. Chosen before the run
// starts, so that a refused restart leaves the stopped run's files as they were.
std::unique_ptr<CheckpointReader> newest_checkpoint(const Participant& p, const RunRecord& record) {
  const std::string& program = record.program();
  if (!p.can_checkpoint()) throw Error(program + ": this scene's run cannot be restarted (no checkpoints)");
  const auto files = list_checkpoints(record.out_dir(), program);
  if (files.empty())
    throw Error(record.out_dir() + "/checkpoints: no checkpoint of " + program + " to restart from");
  if (const auto& at = record.restart_at()) {
    const std::string path = checkpoint_path(record.out_dir(), program, *at);
    for (const auto& f : files)
      if (f.path == path) {
        auto in = std::make_unique<CheckpointReader>(path);
        in->expect(program, record.scene_hash());
        return in;
      }
    throw Error(path + ": no such checkpoint of " + program + " to restart from (--restart-at " +
                std::to_string(*at) + ")");
  }
  for (auto it = files.rbegin(); it != files.rend(); ++it) {
    std::unique_ptr<CheckpointReader> in;
    try {
      in = std::make_unique<CheckpointReader>(it->path);
    } catch (const Error& e) {
      if (std::next(it) == files.rend()) throw;
      std::fprintf(stderr, "%s: %s; restarting from the one before\n", program.c_str(), e.what());
      continue;
    }
    in->expect(program, record.scene_hash());
    return in;
  }
  return nullptr;  // not reached: the loop returns or throws
}

// The checkpoints of a coupled participant: between windows, every `every`
// exchanges (the same count in every process of the run), and at the exchange
// named for a stop (Session::announce_checkpoint_stop).
struct CoupledCheckpoints {
  double interval_s;
  std::uint64_t last_written;  // the exchange of the newest checkpoint (the one resumed from)
  std::uint64_t every = 0;
  bool stop_requested = false;

  void after_step(Participant& p, RunRecord& record) {
    const std::uint64_t stop_at = p.checkpoint_stop_exchange();
    if (const auto done = p.exchanges_completed()) {
      if (every == 0 && interval_s > 0 && p.coupling_window_s() > 0)
        every = std::max<std::uint64_t>(1, std::llround(interval_s / p.coupling_window_s()));
      const bool periodic = every > 0 && *done > 0 && *done % every == 0;
      const bool stop_here = stop_at > 0 && *done == stop_at;
      if ((periodic || stop_here) && *done != last_written) write_checkpoint(p, record, *done), last_written = *done;
      if (stop_here)
        throw Error("stopped by a signal at exchange " + std::to_string(*done) + ", t = " + number_text(p.time_s()) +
                    " s: every process of the run wrote its checkpoint there (cosim run --restart continues)");
      if (stop_at > 0 && *done > stop_at)
        throw Error("passed exchange " + std::to_string(stop_at) + ", named for a stop at a common checkpoint");
    }
    if (interrupt_requested() && !stop_requested) {
      stop_requested = true;
      if (!p.request_checkpoint_stop())
        throw Error("interrupted by a signal at t = " + number_text(p.time_s()) +
                    " s, before joining the coupled run: no checkpoint");
    }
  }
};

}  // namespace

RunRecord::RunRecord(const LoadedScene& loaded, std::string out_dir, const std::string& program, bool restart)
    : out_dir_(std::move(out_dir)),
      program_(program),
      restart_(restart),
      scene_hash_(cosim::scene_hash(loaded.message)),
      checkpoint_interval_s_(loaded.message.output().checkpoint_interval_s()),
      start_s_(now_s()) {
  references_ = loaded.message.references();
  make_folder(out_dir_);
  nlohmann::json overrides = nlohmann::json::object();
  for (const auto& [k, v] : loaded.overrides) overrides[k] = v;
  summary_ = {{"scene", loaded.message.name()}, {"scene_file", loaded.file},
              {"revision", source_revision()}, {"participants", {program}},
              {"threads", max_threads()},       {"status", "running"},
              {"overrides", overrides},         {"results", nlohmann::json::object()}};
}

double RunRecord::wall_s() const { return wall_before_s_ + wall_this_attempt_s(); }

double RunRecord::wall_this_attempt_s() const { return now_s() - start_s_; }

CsvWriter& RunRecord::series(const std::string& file, const std::vector<std::string>& columns) {
  if (series_.count(file)) throw Error(path(file) + ": the run opened this series twice");
  auto& slot = series_[file];
  slot = std::make_unique<CsvWriter>(path(file), columns, restart_);
  return *slot;
}

void RunRecord::save(CheckpointWriter& out) {
  for (auto& [file, csv] : series_)
    if (csv) out.put_value<std::uint64_t>("record.series." + file, csv->length());
  out.put_text("record.summary", summary_.dump());
  out.put_value<double>("record.wall_s", wall_s());
}

void RunRecord::restore(const CheckpointReader& in) {
  // What the run had recorded by then (results of the stages it had finished);
  // this build's revision and thread count stay.
  nlohmann::json saved = nlohmann::json::parse(in.get_text("record.summary"));
  for (const char* key : {"revision", "threads"}) saved[key] = summary_[key];
  summary_ = std::move(saved);
  const std::string prefix = "record.series.";
  for (const std::string& name : in.names_with_prefix(prefix)) {
    const std::string file = name.substr(prefix.size());
    auto it = series_.find(file);
    if (it == series_.end() || !it->second)
      throw Error(in.path() + ": the checkpoint continues series " + file + ", which this run does not write");
    it->second->truncate(in.get_value<std::uint64_t>(name));
  }
  for (auto& [file, csv] : series_)
    if (csv && !in.has(prefix + file))
      throw Error(in.path() + ": the checkpoint does not continue series " + file + ", which this run writes");
  restart_ = false;  // a series opened from here on starts afresh
  // The attempts before this one, up to the checkpoint (work they did after it
  // is redone here and counted once). A checkpoint without it: none known.
  wall_before_s_ = in.has("record.wall_s") ? in.get_value<double>("record.wall_s") : 0.0;
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

void RunRecord::plot_stacked(const std::string& csv_file, const std::string& png_file, int x_column,
                             const std::vector<PlotSeries>& stacked, const std::vector<PlotSeries>& lines,
                             const std::string& title, const std::string& x_label, const std::string& y_label) {
  if (plot_csv_stacked(path(csv_file), path(png_file), x_column, stacked, lines, title, x_label, y_label))
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
  if (wall_before_s_ > 0.0) summary_["wall_time_this_attempt_s"] = wall_this_attempt_s();
  summary_["sim_time_s"] = sim_time_s;
  summary_["steps"] = steps;
  if (!references_.empty()) summary_["comparison"] = compare_with_references(references_, summary_["results"]);
  write_json(path("summary.json"), summary_);
}

nlohmann::json run_participant(Participant& p, RunRecord& record, const std::string& label, bool quiet) {
  bool finalized = false;
  const auto checkpoint = record.restarting() ? newest_checkpoint(p, record) : nullptr;
  if (checkpoint) record.set_resume_step(checkpoint->step());
  // A run started afresh in a folder replaces the checkpoints of one before it
  // (a restart must never continue another run's).
  if (!checkpoint && p.can_checkpoint()) prune_checkpoints(record.out_dir(), record.program(), 0);
  try {
    const double planned_end_s = p.initialize(record);
    if (checkpoint) {
      record.restore(*checkpoint);
      p.restore(*checkpoint);
      record.summary()["restarted_from"] = {
          {"checkpoint", checkpoint->path()}, {"step", checkpoint->step()}, {"time_s", checkpoint->time_s()}};
    }
    const double interval = p.can_checkpoint() ? record.checkpoint_interval_s() : 0.0;
    double next_checkpoint_s = interval > 0 ? next_checkpoint_after(p.time_s(), interval) : 0.0;
    CoupledCheckpoints coupled{interval, checkpoint ? checkpoint->step() : 0};
    Progress progress(label, planned_end_s, quiet);
    while (p.advance()) {
      p.output(record);
      progress.update(p.time_s(), p.steps());
      if (p.coupled()) {
        coupled.after_step(p, record);
        continue;
      }
      if (interval > 0 && p.time_s() >= next_checkpoint_s) {
        write_checkpoint(p, record, p.steps());
        next_checkpoint_s = next_checkpoint_after(p.time_s(), interval);
      }
      if (interrupt_requested()) {
        std::string kept;
        if (p.can_checkpoint()) {
          write_checkpoint(p, record, p.steps());
          kept = "; checkpoint written (--restart continues from it)";
        }
        throw Error("interrupted by a signal at step " + std::to_string(p.steps()) + ", t = " +
                    number_text(p.time_s()) + " s" + kept);
      }
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
