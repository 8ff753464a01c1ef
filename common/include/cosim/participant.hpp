#pragma once
// One skeleton for the run of every program (tyre_fe, snow_sph, coupler),
// after Chrono's co-simulation nodes (Initialize / Synchronize / Advance /
// Output; Serban et al., "Chrono::Vehicle co-simulation framework", 2019): the
// skeleton owns what every run needs the same way (summary.json, the CSV
// series, the progress line, interruption, the failure protocol, the plots);
// a participant supplies only its physics hooks. In a coupled participant the
// exchange with its peers is a named stage of its own `advance` (for example
// send surface -> forces -> receive loads -> update), not a call hidden in a
// physics kernel.
//
// Failure protocol: whatever throws, the CSV rows written so far are flushed,
// the participant tells its peers (`abort`), the results it can still give are
// recorded, and summary.json says "status": "failed" with the error; then the
// error is rethrown as cosim::Error for main() to turn into an exit code.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/checkpoint.hpp"
#include "cosim/outputs.hpp"
#include "cosim/result_references.hpp"
#include "cosim/scene_io.hpp"

namespace cosim {

// What a run keeps on disk: summary.json (written at the end, and on failure)
// and the CSV series, in one output folder.
class RunRecord {
 public:
  // Creates `out_dir`; the summary starts with the scene, its file, the source
  // revision, the program, the thread count and the --set overrides.
  // `restart`: the run continues from the newest checkpoint in out_dir
  // (docs/reliability.md); its series are reopened to be continued.
  RunRecord(const LoadedScene& loaded, std::string out_dir, const std::string& program, bool restart = false);

  const std::string& out_dir() const { return out_dir_; }
  const std::string& program() const { return program_; }
  bool restarting() const { return restart_; }
  std::uint64_t scene_hash() const { return scene_hash_; }
  // Scene output.checkpoint_interval_s (0: only on a stop signal).
  double checkpoint_interval_s() const { return checkpoint_interval_s_; }
  // Restart from the checkpoint of this step (a coupled run: this exchange)
  // rather than the newest; every process of a coupled run is given the same.
  void restart_at(std::uint64_t step) { restart_at_ = step; }
  const std::optional<std::uint64_t>& restart_at() const { return restart_at_; }
  // The step (coupled: exchange) of the checkpoint the run resumes from; set
  // by run_participant before initialize() (0 for a run from the start).
  std::uint64_t resume_step() const { return resume_step_; }
  void set_resume_step(std::uint64_t step) { resume_step_ = step; }
  // The record into a checkpoint (the series' lengths, the summary so far), and
  // back: each series cut to its length then, the summary's results restored.
  void save(CheckpointWriter& out);
  void restore(const CheckpointReader& in);
  std::string path(const std::string& file) const { return out_dir_ + "/" + file; }
  nlohmann::json& summary() { return summary_; }
  nlohmann::json& results() { return summary_["results"]; }
  // Wall time of the run [s]: since the record was made, plus, in a restarted
  // run, what the attempts before it had spent up to the checkpoint it
  // continues from (so that steps / wall time stays a speed across restarts).
  double wall_s() const;
  // Wall time of this attempt alone [s].
  double wall_this_attempt_s() const;

  // Opens out_dir/file with this header (once per file; the run owns it).
  CsvWriter& series(const std::string& file, const std::vector<std::string>& columns);
  void flush_series();
  void close_series();  // flushes and closes every series (before plotting them)

  // A PNG plot of CSV columns of a series (cosim::plot_csv), listed under
  // summary "plots" when drawn; a plot that cannot be drawn never fails a run.
  void plot(const std::string& csv_file, const std::string& png_file, int x_column,
            const std::vector<PlotSeries>& series, const std::string& title, const std::string& x_label,
            const std::string& y_label, const std::string& extra_commands = "");
  // A stacked plot of CSV columns (cosim::plot_csv_stacked), same rules.
  void plot_stacked(const std::string& csv_file, const std::string& png_file, int x_column,
                    const std::vector<PlotSeries>& stacked, const std::vector<PlotSeries>& lines,
                    const std::string& title, const std::string& x_label, const std::string& y_label);
  // A coloured map of a CSV (cosim::plot_csv_map), same rules.
  void plot_map(const std::string& csv_file, const std::string& png_file, int x_column, int y_column,
                int value_column, const std::string& title, const std::string& x_label, const std::string& y_label,
                const std::string& value_label);

  // Writes summary.json with the status, wall time, simulated time, steps and
  // the results beside the scene's references ("comparison", cosim/result_references.hpp).
  void write(const std::string& status, double sim_time_s, std::uint64_t steps);

 private:
  std::string out_dir_, program_;
  bool restart_ = false;
  std::optional<std::uint64_t> restart_at_;
  std::uint64_t resume_step_ = 0;
  std::uint64_t scene_hash_ = 0;
  double checkpoint_interval_s_ = 0.0;
  ResultReferences references_;  // the scene's
  nlohmann::json summary_;
  std::map<std::string, std::unique_ptr<CsvWriter>> series_;
  double start_s_;
  double wall_before_s_ = 0.0;  // the checkpoint's wall time, when restarted
};

// The hooks a program supplies. The skeleton calls, in order:
//   initialize -> (advance -> output)* -> finalize -> finish_peers -> plots
// and on any exception: abort -> finalize (best effort) -> plots (best effort).
class Participant {
 public:
  virtual ~Participant() = default;
  // Builds the model, writes its set-up figures into the record and makes the
  // first exchange of a coupled run; returns the planned end time [s] for the
  // progress line (0: nothing to step, as for a tyre's --mesh-only).
  virtual double initialize(RunRecord& record) = 0;
  // One step (a coupled participant: with its exchange stages); false when the
  // run is over (end time reached, a peer ended the run, step limit).
  virtual bool advance() = 0;
  virtual double time_s() const = 0;
  virtual std::uint64_t steps() const = 0;
  // After every step: CSV rows and frames as their intervals say.
  virtual void output(RunRecord& record) = 0;
  // After the last step (and after a failure, best effort): the results and
  // figures of the run into the record, the last rows and frames.
  virtual void finalize(RunRecord& record) = 0;
  // A coupled participant tells its peers the run ended normally.
  virtual void finish_peers() {}
  // The run failed: a coupled participant tells its peers why. Never throws.
  virtual void abort(const std::string& reason) noexcept { (void)reason; }
  // Pictures of the CSV series (record.plot); called with the series closed.
  virtual void plots(RunRecord& record) { (void)record; }
  // Status of a run that ended without error ("completed", "stopped_at_max_steps").
  virtual std::string end_status() const { return "completed"; }

  // Checkpoints (docs/reliability.md). save() writes the participant's whole
  // state after a completed step (with its output), restore() reads it back
  // after initialize() has built the model, so that the run goes on exactly as
  // if never stopped. A participant without them leaves can_checkpoint() false:
  // a restart of it is refused and no checkpoint is written.
  virtual bool can_checkpoint() const { return false; }
  virtual void save(CheckpointWriter& out) const { (void)out; }
  virtual void restore(const CheckpointReader& in) { (void)in; }

  // A coupled participant (docs/reliability.md, "Coupled runs") checkpoints
  // between coupling windows, at the same count of completed exchanges in
  // every process of the run (every round(checkpoint_interval_s / window)
  // exchanges), and its checkpoints are numbered by that count.
  virtual bool coupled() const { return false; }
  // The exchanges completed when the participant stands between two windows
  // of the coupled run; nullopt otherwise (not joined yet, inside a window).
  virtual std::optional<std::uint64_t> exchanges_completed() const { return std::nullopt; }
  virtual double coupling_window_s() const { return 0.0; }
  // A stop signal: ask the run for a stop at a common checkpoint; false if
  // this participant cannot (it has not joined the run yet).
  virtual bool request_checkpoint_stop() { return false; }
  // The exchange the run stops at for a restart, once named (0: none).
  virtual std::uint64_t checkpoint_stop_exchange() const { return 0; }
};

// Runs a participant under the skeleton; returns the summary (also written to
// out_dir/summary.json). `label` names the progress line. Checkpoints are
// written every checkpoint_interval_s of simulated time and when a stop signal
// ends the run; a restarting record resumes from the newest readable one.
nlohmann::json run_participant(Participant& participant, RunRecord& record, const std::string& label, bool quiet);

}  // namespace cosim
