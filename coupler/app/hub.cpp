#include "hub.hpp"

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>

#include "cosim/outputs.hpp"
#include "cosim/participant.hpp"
#include "cosim/surface_exchange.hpp"
#include "cosim_coupling/exchange_topics.hpp"
#include "cosim_coupling/session_link.hpp"
#include "coupler/coupling_scheme.hpp"
#include "coupler/exchange_forces.hpp"
#include "coupler/exchange_payload.hpp"
#include "coupler/force_outputs.hpp"
#include "coupler/force_window.hpp"
#include "coupler/resistance_work.hpp"
#include "coupler/scene_checks.hpp"
#include "coupler/scene_settings.hpp"
#include "coupler/wire.hpp"

namespace coupler {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The coupler under the run skeleton (cosim/participant.hpp). One window reads:
//   tyre's surface in -> friction per facet -> surface out to the terrain ->
//   wheel state in -> terrain's loads in -> loads out to the tyre -> decomposition.
// The physics of each is in the coupler library; here are the hooks and the topics.
class CouplerRun final : public cosim::coupling::CoupledParticipant {
 public:
  static constexpr std::uint64_t kPaceEvery = 20;
  CouplerRun(Session& session, const cosim::LoadedScene& loaded, const HubOptions& options)
      : CoupledParticipant(&link_),
        session_(session),
        link_(session, step_, "coupler"),
        loaded_(loaded),
        scene_(loaded.message),
        options_(options) {}

  double initialize(cosim::RunRecord& record) override;
  double time_s() const override { return sim_time_; }
  std::uint64_t steps() const override { return step_; }
  void output(cosim::RunRecord&) override {}
  void finalize(cosim::RunRecord& record) override;
  void plots(cosim::RunRecord& record) override {
    if (joined()) plot_coupler_outputs(record, scene_);
  }

  // Checkpoints between windows (docs/reliability.md, "Coupled runs").
  bool can_checkpoint() const override { return true; }
  std::optional<std::uint64_t> exchanges_completed() const override {
    return joined() ? std::optional<std::uint64_t>(step_) : std::nullopt;
  }
  void save(cosim::CheckpointWriter& out) const override;
  void restore(const cosim::CheckpointReader& in) override;

 private:
  // The coupler's whole window is its exchange; the decomposition follows it.
  bool before_exchange() override { return true; }
  bool exchange() override;
  bool after_exchange(bool peers_go_on) override;
 private:
  void open_topics();
  void join_peers(cosim::RunRecord& record, const SceneFriction& friction);
  void take_surface_mesh(cosim::RunRecord& record, const SceneFriction& friction);
  void open_series(cosim::RunRecord& record);

  std::uint64_t step_ = 0;  // before link_, which reads it
  Session& session_;
  cosim::coupling::SessionLink link_;
  const cosim::LoadedScene& loaded_;
  const cosim::scene::Scene& scene_;
  HubOptions options_;
  cosim::RunRecord* record_ = nullptr;
  std::unique_ptr<tp::Reader<tp::SurfaceMesh>> mesh_in_;
  std::unique_ptr<tp::Reader<tp::SurfaceKinematics>> tyre_kinematics_in_;
  std::unique_ptr<tp::Reader<tp::WheelState>> wheel_in_;
  std::unique_ptr<tp::Writer<tp::SurfaceKinematics>> terrain_kinematics_out_;
  std::unique_ptr<tp::Reader<tp::ContactLoads>> terrain_loads_in_;
  std::unique_ptr<tp::Writer<tp::ContactLoads>> tyre_loads_out_;
  std::unique_ptr<tp::Writer<tp::ForceSummary>> summary_out_;
  std::unique_ptr<tp::SampleFilter> mesh_filter_, tyre_filter_, wheel_filter_, terrain_filter_;
  cosim::CsvWriter *csv_ = nullptr, *pace_csv_ = nullptr;
  std::vector<double> mu_of_facet_;  // every surface facet's friction coefficient
  SurfacePositions surface_;
  tp::SurfaceMesh mesh_;
  cosim::SurfaceTopology topology_;     // the mesh, checked (its tags, its facets' nodes)
  cosim::SurfaceState checked_state_;   // scratch of the samples' checks
  cosim::SurfaceLoads checked_loads_;
  tp::SurfaceKinematics k_;
  tp::WheelState wheel_;
  tp::ContactLoads loads_;
  CouplingWindow window_;
  ForceWindow means_;  // the rows of the last averaging window
  ResistanceWork resistance_work_;  // integral F1 dx over the run
  ResidualWatch residuals_;
  FacetLoads last_facets_;
  DecompositionOptions decomposition_;
  double sim_time_ = 0.0;
  ExchangePayload payload_;
};

void CouplerRun::open_topics() {
  auto& p = session_.participant();
  mesh_in_ = p.create_reader<tp::SurfaceMesh>();
  tyre_kinematics_in_ = p.create_reader<tp::SurfaceKinematics>(channel_qos<tp::SurfaceKinematics>(kTyreChannel));
  wheel_in_ = p.create_reader<tp::WheelState>();
  terrain_kinematics_out_ = p.create_writer<tp::SurfaceKinematics>(channel_qos<tp::SurfaceKinematics>(kTerrainChannel));
  terrain_loads_in_ = p.create_reader<tp::ContactLoads>(channel_qos<tp::ContactLoads>(kTerrainChannel));
  tyre_loads_out_ = p.create_writer<tp::ContactLoads>(channel_qos<tp::ContactLoads>(kTyreChannel));
  summary_out_ = p.create_writer<tp::ForceSummary>();
}

// Joins the tyre and the terrain and agrees the coupling window with them (coupler/coupling_scheme.hpp).
void CouplerRun::join_peers(cosim::RunRecord& record, const SceneFriction& friction) {
  if (!options_.quiet)
    std::fprintf(stderr, "[coupler] waiting for the tyre and the terrain (run %016llx)\n",
                 static_cast<unsigned long long>(session_.run_id()));
  const tp::HandshakeResult joined =
      session_.join({tp::Role::tyre, tp::Role::terrain}, 0.0,
                    {mesh_in_.get(), tyre_kinematics_in_.get(), wheel_in_.get(), terrain_kinematics_out_.get(),
                     terrain_loads_in_.get(), tyre_loads_out_.get()},
                    record.resume_step());
  window_ = choose_coupling_window(joined.peer_time_step_s[0], joined.peer_time_step_s[1], scene_.coupling().scheme());
  session_.announce_start(window_.window_s, coupling_window_reason(window_));
  record.summary()["time_step"] = time_step_summary(window_);
  record.summary()["friction"] = friction_summary(friction);
  if (!options_.quiet)
    std::fprintf(stderr, "[coupler] started: window %.4g s, %d tyre sub-steps (tyre %.4g s, terrain %.4g s)\n",
                 window_.window_s, window_.tyre_substeps, window_.tyre_proposed_dt_s, window_.terrain_proposed_dt_s);
  joined_with_window(window_.window_s);
  mesh_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
  tyre_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
  wheel_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
  terrain_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
}

// The tyre's surface mesh, checked, and every facet's friction coefficient.
void CouplerRun::take_surface_mesh(cosim::RunRecord& record, const SceneFriction& friction) {
  if (!session_.wait_step(*mesh_in_, *mesh_filter_, 0, mesh_, "SurfaceMesh", tp::Role::tyre))
    throw cosim::Error("stopped before the first step");
  if (record.resume_step() > 0 && !options_.quiet)
    std::fprintf(stderr, "[coupler] continuing from exchange %llu\n", static_cast<unsigned long long>(record.resume_step()));
  // What the peers send is checked before it is used as an index (lengths, node
  // and facet numbers, finite values): a bad sample ends the run naming its field.
  cosim::coupling::from_topic(mesh_, topology_);
  cosim::check_surface_topology(topology_, "SurfaceMesh");
  fill_facet_friction(topology_.facet_tags, friction.tread_has_sipes, friction.terrain, friction.rules, mu_of_facet_);
  surface_.x_m = topology_.x_m, surface_.y_m = topology_.y_m, surface_.z_m = topology_.z_m;
}

void CouplerRun::open_series(cosim::RunRecord& record) {
  csv_ = &record.series("forces.csv", forces_csv_columns());
  // The pace of the coupled run: wall time against simulated time, every
  // kPaceEvery windows (bench/coupled_bench.sh measures the speed in contact from it).
  pace_csv_ = &record.series("pace.csv", {"time_s", "windows", "wall_time_s"});
}

double CouplerRun::initialize(cosim::RunRecord& record) {
  record_ = &record;
  const SceneFriction friction = scene_friction(loaded_);
  open_topics();
  join_peers(record, friction);
  take_surface_mesh(record, friction);
  means_ = ForceWindow(averaging_window_s(scene_));
  const auto& c = scene_.coupling();
  record.results()["rolling_radius_for_F5_m"] = c.rolling_radius_m();
  record.results()["rolling_radius_source"] = c.rolling_radius_source().empty() ? "scene" : c.rolling_radius_source();
  // Sinkage below the top of the terrain's particles, not the region's (they
  // differ when the spacing does not divide the block's height).
  decomposition_.terrain_surface_z_m = terrain_surface_z_m(scene_);
  record.results()["terrain_surface_z_m"] = decomposition_.terrain_surface_z_m;
  open_series(record);
  return cosim::planned_end_time_s(scene_);  // the FE body's stages: the coupled run's end
}

bool CouplerRun::exchange() {
  // Exchange, in: the tyre's surface of this window.
  if (!session_.wait_step(*tyre_kinematics_in_, *tyre_filter_, step_, k_, "SurfaceKinematics", tp::Role::tyre))
    return false;
  cosim::coupling::from_topic(k_, checked_state_);
  cosim::check_surface_state(checked_state_, topology_, "SurfaceKinematics of step " + std::to_string(step_));
  // A stop signal somewhere in the run: the solvers are both waiting on this
  // exchange's samples, so the next one is a point all three can still reach.
  if (session_.checkpoint_stop_requested() && session_.checkpoint_stop_exchange() == 0)
    session_.announce_checkpoint_stop(step_ + 1, {tp::Role::tyre, tp::Role::terrain});
  const auto t0 = Clock::now();
  // Friction per listed facet: the coupler's decision (thesis 4.3, 4.4, 6.1); sipe walls stay behind.
  keep_facets_with_friction(topology_.facet_tags, mu_of_facet_, step_, k_.facets, k_.friction_coefficient);
  terrain_kinematics_out_->write(k_);  // exchange, out: the surface with its friction, to the terrain
  payload_.forwarding_s += seconds_since(t0);
  payload_.nodes_sent += k_.nodes.size(), payload_.facets_sent += k_.facets.size();
  // Exchange, in: the wheel and the terrain's loads of this window; out: the loads to the tyre.
  if (!session_.wait_step(*wheel_in_, *wheel_filter_, step_, wheel_, "WheelState", tp::Role::tyre)) return false;
  check_wheel_state(wheel_, "WheelState of step " + std::to_string(step_));
  if (!session_.wait_step(*terrain_loads_in_, *terrain_filter_, step_, loads_, "ContactLoads", tp::Role::terrain))
    return false;
  cosim::coupling::from_topic(loads_, checked_loads_);
  cosim::check_surface_loads(checked_loads_, topology_, "ContactLoads of step " + std::to_string(step_));
  const auto t1 = Clock::now();
  tyre_loads_out_->write(loads_);
  payload_.forwarding_s += seconds_since(t1);
  payload_.loaded_nodes += loads_.nodes.size();
  return true;
}

bool CouplerRun::after_exchange(bool peers_go_on) {
  if (!peers_go_on) return false;
  sim_time_ = k_.header.sim_time_s;
  // The decomposition (thesis ch. 2), from the current facet geometry.
  surface_.update(k_);
  ExchangeForces f =
      decompose_exchange(surface_, topology_, wheel_, loads_, scene_.coupling().rolling_radius_m(), decomposition_);
  summary_out_->write(force_summary(f.d, k_.header));
  residuals_.add(f);  // every step: the facets' pressure and friction parts add up to the force on the tyre
  csv_->row(forces_csv_row(sim_time_, step_, f, wheel_));
  means_.add({sim_time_, f.d, wheel_.rim_longitudinal_force_N, f.total_x_N});
  resistance_work_.add(sim_time_, wheel_.rim_x_m, f.d.motion_resistance_N);
  last_facets_ = std::move(f.facet_loads);
  ++step_;
  if (step_ % kPaceEvery == 0) pace_csv_->row({sim_time_, double(step_), record_->wall_s()});
  return true;
}

// Named fields (docs/reliability.md, "Coupled runs"): the rows of the averaging
// window one array per column, the surface's node positions, the run's counters.
void CouplerRun::save(cosim::CheckpointWriter& out) const {
  means_.save(out, "coupler.window.");
  resistance_work_.save(out, "coupler.");
  surface_.save(out, "coupler.");
  out.put_value("coupler.time_s", sim_time_);
  out.put_value("coupler.decomposition_residual_max_N", residuals_.largest_residual_N);
  out.put_value("coupler.largest_force_N", residuals_.largest_force_N);
  payload_.save(out, "coupler.");
  out.put_value("coupler.coupling_window_s", window_.window_s);
  out.put_value("coupler.step", step_);
}

void CouplerRun::restore(const cosim::CheckpointReader& in) {
  means_.restore(in, "coupler.window.");
  resistance_work_.restore(in, "coupler.");
  surface_.restore(in, "coupler.");
  sim_time_ = in.get_value<double>("coupler.time_s");
  residuals_.largest_residual_N = in.get_value<double>("coupler.decomposition_residual_max_N");
  residuals_.largest_force_N = in.get_value<double>("coupler.largest_force_N");
  payload_.restore(in, "coupler.");
  const double window_s = in.get_value<double>("coupler.coupling_window_s");
  if (window_s != window_.window_s)
    throw cosim::Error(in.path() + ": the checkpoint's coupling window " + cosim::number_text(window_s) +
                       " s is not this run's " + cosim::number_text(window_.window_s) + " s");
  step_ = in.get_value<std::uint64_t>("coupler.step");
}

void CouplerRun::finalize(cosim::RunRecord& record) {
  nlohmann::json& summary = record.summary();
  nlohmann::json& results = record.results();
  for (const auto* f : {mesh_filter_.get(), tyre_filter_.get(), wheel_filter_.get(), terrain_filter_.get()})
    if (f) session_.count_rejections(*f);
  summary["rejected_samples"] = {{"other_run", session_.rejected_run_id()}, {"wrong_step", session_.rejected_step()}};
  if (!joined()) return;
  put_window_results(means_, results);
  resistance_work_.put_results(results);
  residuals_.put_results(results);
  const double wall = record.wall_s();
  const double steps = static_cast<double>(step_);
  summary["performance"] = {{"coupler_forwarding_s", payload_.forwarding_s},
                            {"steps_per_s", wall > 0 ? steps / wall : 0.0},
                            {"windows_per_s", wall > 0 ? steps / wall : 0.0},
                            {"coupling_window_s", window_.window_s}, {"tyre_substeps", window_.tyre_substeps}};
  summary["payload"] = payload_.per_exchange(step_);
  // Contact pressure of the last window, per contacted facet (a picture and its numbers).
  write_contact_pressure_map(record.path("contact_pressure.csv"), last_facets_);
}

}  // namespace

nlohmann::json run_hub(Session& session, const cosim::LoadedScene& loaded, const HubOptions& options) {
  cosim::RunRecord record(loaded, options.out_dir, "coupler", options.restart);
  if (options.restart_at) record.restart_at(*options.restart_at);
  CouplerRun run(session, loaded, options);
  return cosim::run_participant(run, record, "coupler", options.quiet);
}

}  // namespace coupler
