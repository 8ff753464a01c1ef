#include "hub.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <memory>
#include <sstream>
#include <optional>

#include "coupler/facet_geometry.hpp"
#include "cosim/coupling_window.hpp"
#include "coupler/forces.hpp"
#include "coupler/friction.hpp"
#include "coupler/scene_checks.hpp"
#include "coupler/wire.hpp"
#include "cosim/outputs.hpp"
#include "cosim/participant.hpp"
#include "cosim/signal.hpp"
#include "cosim/surface_exchange.hpp"
#include "cosim_coupling/exchange_topics.hpp"

namespace coupler {
namespace {

using Clock = std::chrono::steady_clock;
namespace sc = cosim::scene;

// The terrain the tyre meets, from its material (the scene's blocks, filled by coupling.terrain).
TerrainKind terrain_kind(const sc::Scene& scene) {
  bool hard = false;
  for (const auto& b : scene.sph().blocks()) {
    if (b.material().has_water()) return TerrainKind::water;
    hard = hard || b.material().snow().snow_class() == sc::HARD_SNOW;
  }
  return hard ? TerrainKind::snow_hard : TerrainKind::snow_soft;
}

FrictionRules friction_rules(const cosim::LoadedScene& loaded) {
  const auto& c = loaded.message.coupling();
  FrictionRules rules;
  rules.base_mu = c.base_friction_coefficient();
  rules.sipe_equivalent_mu = c.sipe_equivalent_friction_coefficient();
  for (int i = 0; i < c.tag_friction_size(); ++i) {
    try {
      add_tag_override(rules, c.tag_friction(i).tag(), c.tag_friction(i).friction_coefficient());
    } catch (const cosim::Error& e) {
      throw cosim::Error(loaded.locator().child("coupling").where("tag_friction") + ": " + e.what());
    }
  }
  validate(rules);
  return rules;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The coupler under the run skeleton (cosim/participant.hpp). One window reads:
//   tyre's surface in -> friction per facet -> surface out to the terrain ->
//   wheel state in -> terrain's loads in -> loads out to the tyre -> decomposition.
class CouplerRun final : public cosim::Participant {
 public:
  static constexpr std::uint64_t kPaceEvery = 20;
  CouplerRun(Session& session, const cosim::LoadedScene& loaded, const HubOptions& options)
      : session_(session), loaded_(loaded), scene_(loaded.message), options_(options) {}

  double initialize(cosim::RunRecord& record) override;
  bool advance() override;
  double time_s() const override { return sim_time_; }
  std::uint64_t steps() const override { return step_; }
  void output(cosim::RunRecord&) override {}
  void finalize(cosim::RunRecord& record) override;
  void abort(const std::string& reason) noexcept override {
    try {
      session_.send_failure(step_, std::string("coupler: ") + reason);
    } catch (const std::exception&) {
    }
  }
  void plots(cosim::RunRecord& record) override;

  // Checkpoints between windows (docs/reliability.md, "Coupled runs").
  bool can_checkpoint() const override { return true; }
  bool coupled() const override { return true; }
  std::optional<std::uint64_t> exchanges_completed() const override {
    return joined_ ? std::optional<std::uint64_t>(step_) : std::nullopt;
  }
  double coupling_window_s() const override { return window_s_; }
  bool request_checkpoint_stop() override {
    session_.request_checkpoint_stop();
    return true;
  }
  std::uint64_t checkpoint_stop_exchange() const override { return session_.checkpoint_stop_exchange(); }
  void save(cosim::CheckpointWriter& out) const override;
  void restore(const cosim::CheckpointReader& in) override;

 private:
  struct Row {
    double t;
    ForceDecomposition d;
    double rim_longitudinal_force_N;  // the tyre's force on the rim, forward +
    double contact_force_x_N;         // the terrain's force on the tyre (F2 + F3 - F1)
  };
  Session& session_;
  const cosim::LoadedScene& loaded_;
  const sc::Scene& scene_;
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
  std::vector<double> mu_all_, x_, y_, z_;
  tp::SurfaceMesh mesh_;
  cosim::SurfaceTopology topology_;     // the mesh, checked (its tags, its facets' nodes)
  cosim::SurfaceState checked_state_;   // scratch of the samples' checks
  cosim::SurfaceLoads checked_loads_;
  tp::SurfaceKinematics k_;
  tp::WheelState wheel_;
  tp::ContactLoads loads_;
  // The rows of the last averaging_window_s_ of the run (all of them if it is
  // 0): what the steady means need; memory stays flat over a long run.
  std::deque<Row> rows_;
  double averaging_window_s_ = 0.0;
  double largest_residual_N_ = 0.0, largest_force_N_ = 0.0;  // of the decomposition, over the steps
  FacetLoads last_facets_;
  DecompositionOptions decomposition_;
  double rolling_radius_ = 0.36, window_s_ = 0.0;
  int substeps_ = 1;
  std::uint64_t step_ = 0;
  double sim_time_ = 0.0;
  double exchange_s_ = 0.0, nodes_sent_ = 0.0, facets_sent_ = 0.0, loaded_nodes_ = 0.0;
  bool joined_ = false;
};

double CouplerRun::initialize(cosim::RunRecord& record) {
  record_ = &record;
  const auto& c = scene_.coupling();
  nlohmann::json& summary = record.summary();
  const FrictionRules rules = friction_rules(loaded_);
  const TerrainKind terrain = terrain_kind(scene_);
  // The thesis's sipes (BLOCK_SIPES) are the equivalent coefficient on the tread
  // top; sipes cut into the mesh (BLOCK_SIPES_MESHED) never get it on top of the slits.
  const auto variant = scene_.tyre().tread().variant();
  const bool sipes = variant == sc::BLOCK_SIPES;
  auto& p = session_.participant();
  mesh_in_ = p.create_reader<tp::SurfaceMesh>();
  tyre_kinematics_in_ = p.create_reader<tp::SurfaceKinematics>(channel_qos<tp::SurfaceKinematics>(kTyreChannel));
  wheel_in_ = p.create_reader<tp::WheelState>();
  terrain_kinematics_out_ = p.create_writer<tp::SurfaceKinematics>(channel_qos<tp::SurfaceKinematics>(kTerrainChannel));
  terrain_loads_in_ = p.create_reader<tp::ContactLoads>(channel_qos<tp::ContactLoads>(kTerrainChannel));
  tyre_loads_out_ = p.create_writer<tp::ContactLoads>(channel_qos<tp::ContactLoads>(kTyreChannel));
  summary_out_ = p.create_writer<tp::ForceSummary>();
  if (!options_.quiet)
    std::fprintf(stderr, "[coupler] waiting for the tyre and the terrain (run %016llx)\n",
                 static_cast<unsigned long long>(session_.run_id()));
  const tp::HandshakeResult joined =
      session_.join({tp::Role::tyre, tp::Role::terrain}, 0.0,
                    {mesh_in_.get(), tyre_kinematics_in_.get(), wheel_in_.get(), terrain_kinematics_out_.get(),
                     terrain_loads_in_.get(), tyre_loads_out_.get()},
                    record.resume_step());
  // The coupling window (docs/coupling.md): the terrain's stable step, the
  // tyre sub-cycling inside it (multi-rate), or the smaller of the two steps
  // for both (the common-step reference).
  const double tyre_dt = joined.peer_time_step_s[0], terrain_dt = joined.peer_time_step_s[1];
  if (!(tyre_dt > 0) || !(terrain_dt > 0))
    throw cosim::Error("the tyre (" + cosim::number_text(tyre_dt) + " s) and the terrain (" +
                       cosim::number_text(terrain_dt) + " s) must both propose a stable step");
  const bool common_step = c.scheme() == sc::COMMON_STEP;
  window_s_ = common_step ? std::min(tyre_dt, terrain_dt) : terrain_dt;
  substeps_ = cosim::substeps_per_window(window_s_, tyre_dt);
  session_.announce_start(window_s_, common_step ? "common step: the smaller stable step"
                                                 : "multi-rate: the terrain's step, the tyre sub-cycles");
  summary["time_step"] = {{"agreed_dt_s", window_s_}, {"coupling_window_s", window_s_}, {"tyre_substeps", substeps_},
                          {"tyre_proposed_dt_s", tyre_dt}, {"terrain_proposed_dt_s", terrain_dt},
                          {"scheme", common_step ? "common step: one step for both, every step exchanged"
                                                 : "multi-rate: one exchange per terrain step, the tyre sub-cycles "
                                                   "with the terrain's loads held"}};
  summary["friction"] = {{"terrain", terrain_kind_name(terrain)}, {"tread_has_sipes", sipes},
                         {"sipe_treatment", sipes ? "equivalent coefficient on the tread top (thesis 6.1)"
                                            : variant == sc::BLOCK_SIPES_MESHED ? "slits in the mesh, base coefficient"
                                                                                : "none"},
                         {"base", rules.base_mu}, {"sipe_equivalent_on_tread_top", rules.sipe_equivalent_mu}};
  if (!options_.quiet)
    std::fprintf(stderr, "[coupler] started: window %.4g s, %d tyre sub-steps (tyre %.4g s, terrain %.4g s)\n",
                 window_s_, substeps_, tyre_dt, terrain_dt);
  joined_ = true;
  mesh_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
  tyre_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
  wheel_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
  terrain_filter_ = std::make_unique<tp::SampleFilter>(session_.run_id());
  if (!session_.wait_step(*mesh_in_, *mesh_filter_, 0, mesh_, "SurfaceMesh", tp::Role::tyre))
    throw cosim::Error("stopped before the first step");
  if (record.resume_step() > 0 && !options_.quiet)
    std::fprintf(stderr, "[coupler] continuing from exchange %llu\n", static_cast<unsigned long long>(record.resume_step()));
  // What the peers send is checked before it is used as an index (lengths, node
  // and facet numbers, finite values): a bad sample ends the run naming its field.
  cosim::coupling::from_topic(mesh_, topology_);
  cosim::check_surface_topology(topology_, "SurfaceMesh");
  fill_facet_friction(topology_.facet_tags, sipes, terrain, rules, mu_all_);
  x_ = topology_.x_m, y_ = topology_.y_m, z_ = topology_.z_m;
  // Steady means over the last average_last_s of the run (thesis 6.1: results
  // "taken at the steady state region").
  // The FE body's own window where the coupling names none: the tyre's stages' or the block's.
  const double body_window = scene_.has_tread_block() ? scene_.tread_block().average_last_s()
                                                      : scene_.tyre().stages().average_last_s();
  averaging_window_s_ = c.average_last_s() > 0 ? c.average_last_s() : body_window;
  rolling_radius_ = c.rolling_radius_m();
  record.results()["rolling_radius_for_F5_m"] = rolling_radius_;
  record.results()["rolling_radius_source"] = c.rolling_radius_source().empty() ? "scene" : c.rolling_radius_source();
  // Sinkage below the top of the terrain's particles, not the region's (they
  // differ when the spacing does not divide the block's height).
  decomposition_.terrain_surface_z_m = terrain_surface_z_m(scene_);
  record.results()["terrain_surface_z_m"] = decomposition_.terrain_surface_z_m;
  csv_ = &record.series("forces.csv",
                        {"time_s", "step", "traction_force_N", "motion_resistance_N", "groove_force_N",
                         "vertical_pressure_force_N", "rolling_resistance_moment_Nm", "rolling_resistance_force_N",
                         "drawbar_pull_N", "net_longitudinal_pressure_force_N", "traction_minus_rrf_N", "sinkage_m",
                         "contact_area_m2", "rim_x_m", "rim_z_m", "spin_rate_rad_per_s", "applied_torque_Nm",
                         "rm2_Nm", "contact_force_x_N", "contact_force_z_N", "rim_longitudinal_force_N",
                         "vertical_pressure_force_tread_top_N", "vertical_pressure_force_groove_N"});
  // The pace of the coupled run: wall time against simulated time, every
  // kPaceEvery windows (bench/coupled_bench.sh measures the speed in contact from it).
  pace_csv_ = &record.series("pace.csv", {"time_s", "windows", "wall_time_s"});
  return cosim::planned_end_time_s(scene_);  // the FE body's stages: the coupled run's end
}

bool CouplerRun::advance() {
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
  // Friction per listed facet: the coupler's decision (thesis 4.3, 4.4, 6.1).
  // Sipe walls are not handed on: a sipe is a slit (0.6 mm) that no particle
  // enters, and its effect on the snow is the tread top's equivalent
  // coefficient (thesis 4.4, 6.1); particles would otherwise be caught
  // between its two coincident walls.
  std::size_t kept = 0;
  k_.friction_coefficient.resize(k_.facets.size());
  for (std::size_t i = 0; i < k_.facets.size(); ++i) {
    const auto f = k_.facets[i];
    if (f >= mu_all_.size())
      throw cosim::Error("SurfaceKinematics of step " + std::to_string(step_) + ": facet " + std::to_string(f) +
                         " is not in the surface mesh");
    if (topology_.facet_tags[f] == FacetTag::sipe_wall) continue;
    k_.facets[kept] = f, k_.friction_coefficient[kept] = mu_all_[f], ++kept;
  }
  k_.facets.resize(kept), k_.friction_coefficient.resize(kept);
  terrain_kinematics_out_->write(k_);  // exchange, out: the surface with its friction, to the terrain
  exchange_s_ += seconds_since(t0);
  nodes_sent_ += k_.nodes.size(), facets_sent_ += k_.facets.size();
  // Exchange, in: the wheel and the terrain's loads of this window; out: the loads to the tyre.
  if (!session_.wait_step(*wheel_in_, *wheel_filter_, step_, wheel_, "WheelState", tp::Role::tyre)) return false;
  check_wheel_state(wheel_, "WheelState of step " + std::to_string(step_));
  if (!session_.wait_step(*terrain_loads_in_, *terrain_filter_, step_, loads_, "ContactLoads", tp::Role::terrain))
    return false;
  cosim::coupling::from_topic(loads_, checked_loads_);
  cosim::check_surface_loads(checked_loads_, topology_, "ContactLoads of step " + std::to_string(step_));
  const auto t1 = Clock::now();
  tyre_loads_out_->write(loads_);
  exchange_s_ += seconds_since(t1);
  loaded_nodes_ += loads_.nodes.size();
  sim_time_ = k_.header.sim_time_s;
  // The decomposition (thesis ch. 2), from the current facet geometry.
  for (std::size_t j = 0; j < k_.nodes.size(); ++j) {
    const auto n = k_.nodes[j];
    x_[n] = k_.x_m[j], y_[n] = k_.y_m[j], z_[n] = k_.z_m[j];
  }
  const FacetGeometry geometry = quad_facet_geometry(x_, y_, z_, topology_.facet_nodes);
  const FacetLoads facet_loads = facet_loads_from_contact(loads_, topology_.facet_tags, geometry);
  const ForceDecomposition d = decompose_forces(facet_loads, wheel_input(wheel_, rolling_radius_), decomposition_);
  summary_out_->write(force_summary(d, k_.header));
  double fx = 0.0, fy = 0.0, fz = 0.0;
  for (std::size_t j = 0; j < loads_.nodes.size(); ++j) fx += loads_.fx_N[j], fy += loads_.fy_N[j], fz += loads_.fz_N[j];
  // Every step: the facets' pressure and friction parts add up to the force on the tyre.
  largest_residual_N_ = std::max(largest_residual_N_, decomposition_residual_N(facet_loads, fx, fy, fz));
  largest_force_N_ = std::max(largest_force_N_, std::sqrt(fx * fx + fy * fy + fz * fz));
  csv_->row({sim_time_, double(step_), d.traction_force_N, d.motion_resistance_N, d.groove_force_N,
             d.vertical_pressure_force_N, d.rolling_resistance_moment_Nm, d.rolling_resistance_force_N,
             d.drawbar_pull_N, d.net_longitudinal_pressure_force_N, d.traction_minus_rrf_N, d.sinkage_m,
             d.contact_area_m2, wheel_.rim_x_m, wheel_.rim_z_m, wheel_.spin_rate_radps, wheel_.applied_torque_Nm,
             wheel_.reaction_moment_y_Nm, fx, fz, wheel_.rim_longitudinal_force_N,
             d.vertical_pressure_force_tread_top_N, d.vertical_pressure_force_groove_N});
  rows_.push_back({sim_time_, d, wheel_.rim_longitudinal_force_N, fx});
  if (averaging_window_s_ > 0)  // the means read the rows of t >= the last t - window (finalize)
    while (rows_.front().t < rows_.back().t - averaging_window_s_) rows_.pop_front();
  last_facets_ = facet_loads;
  ++step_;
  if (step_ % kPaceEvery == 0) pace_csv_->row({sim_time_, double(step_), record_->wall_s()});
  return true;
}

// Columns time_s and F3, F1, F2, F5, drawbar pull (0-based 0, 2, 3, 4, 7, 8) of
// forces.csv, streamed (a long run's file has a row per window); false if unreadable.
bool read_force_columns(const std::string& path, std::vector<double>& t, std::vector<std::vector<double>>& forces) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line, cell;
  std::getline(in, line);  // header
  const int wanted[5] = {2, 3, 4, 7, 8};
  while (std::getline(in, line)) {
    std::stringstream row(line);
    double v[9];
    int k = 0;
    for (; k < 9 && std::getline(row, cell, ','); ++k) v[k] = std::strtod(cell.c_str(), nullptr);
    if (k < 9) return false;
    t.push_back(v[0]);
    for (int j = 0; j < 5; ++j) forces[j].push_back(v[wanted[j]]);
  }
  return true;
}

// The rows kept for the steady means, flattened (kRowValues each).
constexpr std::size_t kRowValues = 15;

void CouplerRun::save(cosim::CheckpointWriter& out) const {
  std::vector<double> rows;
  rows.reserve(kRowValues * rows_.size());
  for (const Row& r : rows_) {
    const ForceDecomposition& d = r.d;
    rows.insert(rows.end(), {r.t, d.traction_force_N, d.motion_resistance_N, d.groove_force_N,
                             d.vertical_pressure_force_N, d.rolling_resistance_moment_Nm, d.pressure_centre_offset_m,
                             d.rolling_resistance_force_N, d.drawbar_pull_N, d.net_longitudinal_pressure_force_N,
                             d.traction_minus_rrf_N, d.sinkage_m, d.contact_area_m2, r.rim_longitudinal_force_N,
                             r.contact_force_x_N});
  }
  out.put("coupler.rows", rows);
  out.put("coupler.x_m", x_);
  out.put("coupler.y_m", y_);
  out.put("coupler.z_m", z_);
  out.put("coupler.doubles", std::vector<double>{sim_time_, largest_residual_N_, largest_force_N_, exchange_s_,
                                                 nodes_sent_, facets_sent_, loaded_nodes_, window_s_});
  out.put("coupler.step", std::vector<std::uint64_t>{step_});
}

void CouplerRun::restore(const cosim::CheckpointReader& in) {
  const auto rows = in.get<double>("coupler.rows");
  if (rows.size() % kRowValues != 0)
    throw cosim::Error(in.path() + ": coupler.rows: " + std::to_string(rows.size()) + " values are not rows of " +
                       std::to_string(kRowValues));
  rows_.clear();
  for (std::size_t k = 0; k < rows.size(); k += kRowValues) {
    const double* v = &rows[k];
    Row r{};
    r.t = v[0];
    ForceDecomposition& d = r.d;
    d.traction_force_N = v[1], d.motion_resistance_N = v[2], d.groove_force_N = v[3];
    d.vertical_pressure_force_N = v[4], d.rolling_resistance_moment_Nm = v[5], d.pressure_centre_offset_m = v[6];
    d.rolling_resistance_force_N = v[7], d.drawbar_pull_N = v[8], d.net_longitudinal_pressure_force_N = v[9];
    d.traction_minus_rrf_N = v[10], d.sinkage_m = v[11], d.contact_area_m2 = v[12];
    r.rim_longitudinal_force_N = v[13], r.contact_force_x_N = v[14];
    rows_.push_back(r);
  }
  x_ = in.get<double>("coupler.x_m", x_.size());
  y_ = in.get<double>("coupler.y_m", y_.size());
  z_ = in.get<double>("coupler.z_m", z_.size());
  const auto d = in.get<double>("coupler.doubles", 8);
  sim_time_ = d[0], largest_residual_N_ = d[1], largest_force_N_ = d[2], exchange_s_ = d[3];
  nodes_sent_ = d[4], facets_sent_ = d[5], loaded_nodes_ = d[6];
  if (d[7] != window_s_)
    throw cosim::Error(in.path() + ": the checkpoint's coupling window " + cosim::number_text(d[7]) +
                       " s is not this run's " + cosim::number_text(window_s_) + " s");
  step_ = in.get<std::uint64_t>("coupler.step", 1)[0];
}

void CouplerRun::finalize(cosim::RunRecord& record) {
  nlohmann::json& summary = record.summary();
  nlohmann::json& results = record.results();
  for (const auto* f : {mesh_filter_.get(), tyre_filter_.get(), wheel_filter_.get(), terrain_filter_.get()})
    if (f) session_.count_rejections(*f);
  summary["rejected_samples"] = {{"other_run", session_.rejected_run_id()}, {"wrong_step", session_.rejected_step()}};
  if (!joined_) return;
  const double window = averaging_window_s_;
  const double from = rows_.empty() ? 0.0 : rows_.back().t - window;
  ForceDecomposition mean;
  double rim_fx = 0.0, contact_fx = 0.0;
  long n = 0;
  for (const auto& r : rows_) {
    if (window > 0 && r.t < from) continue;
    const auto& d = r.d;
    mean.traction_force_N += d.traction_force_N, mean.motion_resistance_N += d.motion_resistance_N;
    mean.groove_force_N += d.groove_force_N, mean.rolling_resistance_force_N += d.rolling_resistance_force_N;
    mean.drawbar_pull_N += d.drawbar_pull_N;
    mean.net_longitudinal_pressure_force_N += d.net_longitudinal_pressure_force_N;
    mean.traction_minus_rrf_N += d.traction_minus_rrf_N, mean.sinkage_m += d.sinkage_m;
    mean.rolling_resistance_moment_Nm += d.rolling_resistance_moment_Nm;
    mean.contact_area_m2 += d.contact_area_m2, mean.vertical_pressure_force_N += d.vertical_pressure_force_N;
    rim_fx += r.rim_longitudinal_force_N, contact_fx += r.contact_force_x_N;
    ++n;
  }
  auto avg = [&](double v) { return n ? v / n : 0.0; };
  results["averaging_window_s"] = window;
  if (n) {
    for (const auto& r : rows_)
      if (!(window > 0 && r.t < from)) {
        results["averaging_window_start_s"] = r.t;
        break;
      }
    results["averaging_window_end_s"] = rows_.back().t;
  }
  results["averaged_steps"] = n;
  results["traction_force_N"] = avg(mean.traction_force_N);
  results["motion_resistance_N"] = avg(mean.motion_resistance_N);
  results["groove_force_N"] = avg(mean.groove_force_N);
  results["rolling_resistance_moment_Nm"] = avg(mean.rolling_resistance_moment_Nm);
  results["rolling_resistance_force_N"] = avg(mean.rolling_resistance_force_N);
  results["drawbar_pull_N"] = avg(mean.drawbar_pull_N);
  // Beside it, what a test rig would measure: the tyre's longitudinal force on
  // the rim, and the terrain's on the tyre (F2 + F3 - F1); the drawbar pull is the
  // latter less F5 (docs/force_decomposition.md, "Drawbar pull and the rim's force").
  results["rim_longitudinal_force_N"] = avg(rim_fx);
  results["terrain_longitudinal_force_N"] = avg(contact_fx);
  results["net_longitudinal_pressure_force_N"] = avg(mean.net_longitudinal_pressure_force_N);
  results["traction_minus_rrf_N"] = avg(mean.traction_minus_rrf_N);
  results["vertical_pressure_force_N"] = avg(mean.vertical_pressure_force_N);
  results["sinkage_m"] = avg(mean.sinkage_m);
  results["contact_area_m2"] = avg(mean.contact_area_m2);
  // How steady the window is: each mean over its second half less that over its
  // first half (a steady state gives the noise only; a transient, a trend).
  if (n >= 2) {
    const double mid = 0.5 * ((window > 0 ? from : rows_.front().t) + rows_.back().t);
    double first[6] = {0}, second[6] = {0};
    long n1 = 0, n2 = 0;
    for (const auto& r : rows_) {
      if (window > 0 && r.t < from) continue;
      const double v[6] = {r.d.traction_force_N, r.d.motion_resistance_N, r.d.groove_force_N,
                           r.d.rolling_resistance_force_N, r.d.drawbar_pull_N, r.d.sinkage_m};
      double* half = r.t < mid ? first : second;
      for (int k = 0; k < 6; ++k) half[k] += v[k];
      ++(r.t < mid ? n1 : n2);
    }
    const char* names[6] = {"traction_force_N", "motion_resistance_N", "groove_force_N", "rolling_resistance_force_N",
                            "drawbar_pull_N", "sinkage_m"};
    nlohmann::json drift;
    for (int k = 0; k < 6; ++k) drift[names[k]] = n1 && n2 ? second[k] / n2 - first[k] / n1 : 0.0;
    results["window_drift"] = drift;
  }
  results["decomposition_residual_max_N"] = largest_residual_N_;
  results["decomposition_residual_relative"] = largest_force_N_ > 0 ? largest_residual_N_ / largest_force_N_ : 0.0;
  if (!rows_.empty()) {
    results["final_contact_area_m2"] = rows_.back().d.contact_area_m2;
    results["final_sinkage_m"] = rows_.back().d.sinkage_m;
  }
  const double wall = record.wall_s();
  const double steps = static_cast<double>(step_);
  summary["performance"] = {{"coupler_forwarding_s", exchange_s_}, {"steps_per_s", wall > 0 ? steps / wall : 0.0},
                            {"windows_per_s", wall > 0 ? steps / wall : 0.0},
                            {"coupling_window_s", window_s_}, {"tyre_substeps", substeps_}};
  summary["payload"] = {{"mean_surface_nodes_per_step", step_ ? nodes_sent_ / steps : 0.0},
                        {"mean_surface_facets_per_step", step_ ? facets_sent_ / steps : 0.0},
                        {"mean_loaded_nodes_per_step", step_ ? loaded_nodes_ / steps : 0.0}};
  // Contact pressure of the last window, per contacted facet (a picture and its numbers).
  cosim::CsvWriter map(record.path("contact_pressure.csv"),
                       {"centroid_x_m", "centroid_y_m", "centroid_z_m", "contact_pressure_Pa", "contact_area_m2"});
  for (std::size_t i = 0; i < last_facets_.size(); ++i) {
    const double a = last_facets_.contact_area_m2[i];
    const double pn = std::sqrt(last_facets_.pressure_x_N[i] * last_facets_.pressure_x_N[i] +
                                last_facets_.pressure_y_N[i] * last_facets_.pressure_y_N[i] +
                                last_facets_.pressure_z_N[i] * last_facets_.pressure_z_N[i]);
    map.row({last_facets_.centroid_x_m[i], last_facets_.centroid_y_m[i], last_facets_.centroid_z_m[i],
             a > 0 ? pn / a : 0.0, a});
  }
}

void CouplerRun::plots(cosim::RunRecord& record) {
  if (!joined_) return;
  const std::string name = scene_.name();
  record.plot_map("contact_pressure.csv", "contact_pressure.png", 1, 2, 4,
                  name + ": contact pressure on the tyre (last step, seen from above)", "x [m]", "y [m]",
                  "pressure [Pa]");
  // The raw per-step forces swing by +-1000 N on a coarse scene as particles
  // enter and leave contact: a centred moving mean is drawn over them, and the
  // averaging window of the results is shaded. Read back from forces.csv (the
  // run keeps only its averaging window's rows): time and F3, F1, F2, F5, drawbar pull.
  const double filter_s = scene_.coupling().force_plot_filter_s();
  std::vector<double> t;
  std::vector<std::vector<double>> raw(5);
  if (!read_force_columns(record.path("forces.csv"), t, raw) || t.empty()) return;
  std::vector<std::vector<double>> filtered;
  for (const auto& series : raw) filtered.push_back(cosim::centred_moving_mean(t, series, filter_s));
  {
    cosim::CsvWriter out(record.path("forces_filtered.csv"),
                         {"time_s", "traction_force_N", "motion_resistance_N", "groove_force_N",
                          "rolling_resistance_force_N", "drawbar_pull_N"});
    for (std::size_t i = 0; i < t.size(); ++i)
      out.row({t[i], filtered[0][i], filtered[1][i], filtered[2][i], filtered[3][i], filtered[4][i]});
  }
  cosim::PlotOptions o;
  char filter_ms[32];
  std::snprintf(filter_ms, sizeof filter_ms, "%g", filter_s * 1e3);
  o.title = name + ": force decomposition (faint: per step; bold: " + filter_ms + " ms centred mean)";
  o.x_label = "time [s]", o.y_label = "force [N]";
  const auto& results = record.results();
  if (results.contains("averaging_window_start_s"))
    o.extra_commands = "set object 1 rect from " + std::to_string(results["averaging_window_start_s"].get<double>()) +
                       ", graph 0 to " + std::to_string(results["averaging_window_end_s"].get<double>()) +
                       ", graph 1 behind fc rgb '#eeeeee' fs solid noborder\n";
  // forces.csv columns of F3, F1, F2, F5, drawbar pull; forces_filtered.csv columns 2-6.
  const int raw_column[5] = {3, 4, 5, 8, 9};
  const char* names[5] = {"traction F3", "motion resistance F1", "groove F2", "F5", "drawbar pull"};
  const char* colours[5] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#000000"};
  std::vector<cosim::PlotCurve> curves;
  for (int k = 0; k < 5; ++k)
    curves.push_back({record.path("forces.csv"), "1:" + std::to_string(raw_column[k]),
                      std::string("lines lw 1 lc rgb '#b0") + (colours[k] + 1) + "'", ""});
  for (int k = 0; k < 5; ++k)
    curves.push_back({record.path("forces_filtered.csv"), "1:" + std::to_string(k + 2),
                      std::string("lines lw 3 lc rgb '") + colours[k] + "'", names[k]});
  if (cosim::plot_png(record.path("forces.png"), o, curves)) record.summary()["plots"].push_back("forces.png");
}

}  // namespace

nlohmann::json run_hub(Session& session, const cosim::LoadedScene& loaded, const HubOptions& options) {
  cosim::RunRecord record(loaded, options.out_dir, "coupler", options.restart);
  if (options.restart_at) record.restart_at(*options.restart_at);
  CouplerRun run(session, loaded, options);
  return cosim::run_participant(run, record, "coupler", options.quiet);
}

}  // namespace coupler
