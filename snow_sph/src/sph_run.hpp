#pragma once
// The SPH terrain under the run skeleton (cosim/participant.hpp) as a coupled
// participant (cosim_coupling/coupled_participant.hpp): on its own (plate
// sinkage, water column, dam break) or as the terrain of a coupled run, whose
// step reads
//   before_exchange (the end checks, the solver's sub-steps up to the exchange)
//   -> exchange (surface in -> contact -> loads out)
//   -> after_exchange (the step closed, rest tracking, statistics).
// The base answers the coupled questions of the skeleton (the peers told of
// the end or a failure, the window, a stop at a checkpoint).
//
// Its code is in three files: run.cpp (the set-up and the step),
// run_outputs.cpp (CSV rows, VTK frames, the rut's CSV and plots) and
// run_summary.cpp (what summary.json says of the set-up and the results).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosim/outputs.hpp"
#include "cosim/participant.hpp"
#include "cosim_coupling/coupled_participant.hpp"
#include "snow_sph/run.hpp"
#include "snow_sph/rut.hpp"
#include "snow_sph/solver.hpp"

namespace snow_sph {

// Where and when a particle went deepest into the surface (-1: none yet).
struct DeepestContact {
  double time_s = -1.0, particle_x_m = -1.0, particle_y_m = -1.0, particle_z_m = -1.0, facet = -1.0;
};

// Surge front along +x: the farthest water particle that still has
// neighbours (isolated drops do not count), plus half a spacing (run_outputs.cpp).
double surge_front(const Model& m);

// The rut's cells, row by row (y, then x along the row): those that held
// particles at step 0 and hold some now (run_outputs.cpp).
void write_rut_csv(const std::string& path, const RutGrid& grid, const RutSurface& rut);

class SphRun final : public cosim::coupling::CoupledParticipant {
 public:
  SphRun(const cosim::LoadedScene& loaded, const RunOptions& options)
      : CoupledParticipant(options.exchange), scene_(loaded.message), options_(options),
        surface_port_(options.exchange) {}

  double initialize(cosim::RunRecord& record) override;
  double time_s() const override { return solver_ ? solver_->time() : 0.0; }
  std::uint64_t steps() const override { return solver_ ? solver_->steps() : 0; }
  void output(cosim::RunRecord& record) override;
  void finalize(cosim::RunRecord& record) override;
  void plots(cosim::RunRecord& record) override;
  // On its own: every checkpoint_interval_s. Coupled: between windows, at the
  // exchanges its peers take theirs (docs/reliability.md, "Coupled runs").
  bool can_checkpoint() const override { return true; }
  // Exchange n's loads sent and the step after it completed: n + 1 exchanges
  // done, as the coupler and the tyre count them.
  std::optional<std::uint64_t> exchanges_completed() const override {
    return surface_port_ && !stopped_ ? std::optional<std::uint64_t>(exchange_ + 1) : std::nullopt;
  }
  void save(cosim::CheckpointWriter& out) const override;
  void restore(const cosim::CheckpointReader& in) override;

 private:
  bool before_exchange() override;
  bool exchange() override { return exchange_surface(exchange_ + 1); }
  bool after_exchange(bool peers_go_on) override;

  // run.cpp
  // Coupled set-up: the rut grid, the contact, the window agreed with the
  // peers and exchange 0 (a restart's comes from its checkpoint).
  void join_coupled_run(cosim::RunRecord& record);
  // Exchange stage: the surface of exchange n in, its contact with the
  // particles, the loads out. False when the surface's owner ended the run.
  bool exchange_surface(std::uint64_t exchange);
  void report_substeps(const StepStats& st);
  void track_rest();            // after each step: the bodies' rest criterion
  bool bodies_at_rest() const;  // every body with a criterion has met it

  // run_outputs.cpp
  void open_series(cosim::RunRecord& record);
  void record_rows(bool force);
  void plot_energy_split(cosim::RunRecord& record, const std::string& name);
  void write_frame();

  // run_summary.cpp
  void describe_setup(cosim::RunRecord& record) const;  // particles, kernel, materials, blocks
  // `wall`: the run's wall time [s], read once for every figure of the summary.
  void summarise_steps(cosim::RunRecord& record, double wall) const;  // time steps, energy, performance
  void summarise_coupling(cosim::RunRecord& record, double wall) const;
  void coupled_results(cosim::RunRecord& record) const;  // rut, penetration, drained water
  void body_results(cosim::RunRecord& record) const;
  void probe_results(cosim::RunRecord& record) const;  // floor pressure, surge front

  const cosim::scene::Scene& scene_;
  RunOptions options_;
  SurfaceExchange* surface_port_;  // the link(), as the terrain's port; null on its own
  ContactSurface surface_;         // of the current exchange
  std::vector<std::int64_t> compact_scratch_;
  cosim::SurfaceLoads loads_out_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Solver> solver_;
  StepStats step_stats_;  // of the step under way (before_exchange -> after_exchange)
  std::vector<std::string> energy_columns_;  // energy.csv's
  cosim::CsvWriter *energy_csv_ = nullptr, *bodies_csv_ = nullptr, *front_csv_ = nullptr, *probe_csv_ = nullptr,
                   *contact_csv_ = nullptr;
  std::unique_ptr<cosim::VtkSeries> vtk_;
  double wall_at_coupling_s_ = 0.0, exchange_wait_s_ = 0.0;
  std::uint64_t exchange_ = 0, windows_ = 0;  // windows_: steps made (coupled: windows)
  bool stopped_ = false;
  double dt_min_ = 1e300, dt_max_ = 0.0, dt_sum_ = 0.0;
  std::uint32_t reported_substeps_ = 1;  // the most sub-steps in one window reported on the log
  std::string substeps_cause_;            // what set the terrain's limit at that window
  std::size_t clamped_ = 0;
  double probe_sum_ = 0.0, probe_time_ = 0.0, probe_from_ = 0.0, last_dt_ = 0.0;
  double next_csv_ = 0.0, next_vtk_ = 0.0, csv_interval_ = 0.0, vtk_interval_ = 0.0;
  double floor_x_ = 0.0, floor_y_ = 0.0;
  // Coupled: the terrain's top at step 0 per plan cell, and the deepest
  // penetration of a particle into the surface over the exchanges so far.
  RutGrid rut_grid_;
  double particle_radius_m_ = 0.0, max_penetration_m_ = 0.0;
  DeepestContact deepest_;
};

}  // namespace snow_sph
