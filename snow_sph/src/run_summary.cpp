// What the SPH terrain's run says in summary.json (sph_run.hpp,
// docs/outputs.md): its set-up (particles, kernel, materials, blocks) when it
// starts, and at its end the time steps, energy balance, performance and
// results (the rut, the bodies' sinkage, the probes).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cosim/error.hpp"
#include "snow_sph/energy_split.hpp"
#include "snow_sph/scene.hpp"
#include "sph_run.hpp"

namespace snow_sph {
namespace {

const char* kernel_name(KernelType k) {
  return k == KernelType::cubic ? "cubic" : k == KernelType::quadratic ? "quadratic" : "quintic";
}

nlohmann::json energy_json(const EnergyBalance& e) {
  nlohmann::json j = {{"kinetic_J", e.kinetic},
                      {"internal_J", e.internal},
                      {"elastic_stored_J", e.elastic},
                      {"plastic_dissipation_J", e.plastic_dissipation},
                      {"viscous_dissipation_J", e.viscous_dissipation},
                      {"contact_dissipation_J", e.contact_dissipation},
                      {"contact_elastic_J", e.contact_elastic},
                      {"external_work_J", e.external_work},
                      {"deactivated_kinetic_J", e.deactivated_kinetic},
                      {"drained_kinetic_J", e.drained_kinetic},
                      {"balance_J", e.total() - e.initial_total},
                      {"relative_error", e.relative_error()},
                      {"note",
                       "energies of the simulated particles and bodies; balance = KE + IE + VD + FD + "
                       "contact - W (Abaqus ETOTAL), relative to max(KE, IE, VD, W)"}};
  for (const auto& [key, value] : energy_split(e)) j[key] = value;
  return j;
}

nlohmann::json materials_json(const Model& model) {
  nlohmann::json materials = nlohmann::json::array();
  for (const auto& mat : model.materials) {
    if (mat.kind == MaterialModel::Kind::water) {
      materials.push_back({{"kind", "water"},
                           {"reference_sound_speed_m_per_s", mat.reference_sound_speed},
                           {"sound_speed_used_m_per_s", mat.eos.c0},
                           {"sound_speed_lowered", mat.sound_speed_lowered},
                           {"tension_limit_Pa", mat.eos.tension_limit},  // 0: none
                           {"valid_density_kg_per_m3", {mat.valid_density_min, mat.valid_density_max}},  // 0: none
                           {"note", mat.sound_speed_lowered
                                        ? "artificial compressibility: sound speed lowered for speed"
                                        : "physical sound speed"}});
    } else {
      materials.push_back({{"kind", "snow"},
                           {"cohesion_Pa", mat.mdpc.cohesion_Pa},
                           {"cap_eccentricity", mat.mdpc.cap_eccentricity}});
    }
  }
  return materials;
}

// A region that is not a whole number of particles is filled short of its
// max faces: a gap between the snow and a wall unconfines it, and a body
// started at the region's top falls through the gap (sinkage is measured
// from the particles' top: RigidBody::surface_z).
nlohmann::json blocks_json(const Model& model, const std::string& scene_name) {
  nlohmann::json blocks = nlohmann::json::array();
  for (std::size_t k = 0; k < model.block_lattices.size(); ++k) {
    const BlockLattice& l = model.block_lattices[k];
    const double* a = l.region_max;
    const double* f = l.filled_max;
    blocks.push_back({{"region_max_m", {a[0], a[1], a[2]}}, {"particles_fill_to_m", {f[0], f[1], f[2]}}});
    if (std::max({a[0] - f[0], a[1] - f[1], a[2] - f[2]}) > 1e-9)
      std::fprintf(stderr,
                   "[%s] sph.blocks[%zu]: %s m particles fill the region to (%s, %s, %s) m, short of its max corner "
                   "(%s, %s, %s) m: a spacing that divides the region fills it\n",
                   scene_name.c_str(), k, cosim::number_text(model.settings.spacing).c_str(),
                   cosim::number_text(f[0]).c_str(), cosim::number_text(f[1]).c_str(), cosim::number_text(f[2]).c_str(),
                   cosim::number_text(a[0]).c_str(), cosim::number_text(a[1]).c_str(), cosim::number_text(a[2]).c_str());
  }
  return blocks;
}

}  // namespace

void SphRun::describe_setup(cosim::RunRecord& record) const {
  const Model& model = *model_;
  nlohmann::json& summary = record.summary();
  summary["particles"] = model.particles.n_real;
  summary["kernel"] = kernel_name(model.kernel.type);
  summary["particle_spacing_m"] = model.settings.spacing;
  summary["smoothing_length_m"] = model.kernel.h;
  summary["symmetry_planes"] = nlohmann::json::array();
  for (const auto& plane : model.planes)
    if (plane.symmetry) summary["symmetry_planes"].push_back(plane.face);
  summary["materials"] = materials_json(model);
  summary["blocks"] = blocks_json(model, scene_.name());
}

void SphRun::finalize(cosim::RunRecord& record) {
  if (!solver_) return;  // the model was never built
  record_rows(true);
  if (vtk_ && vtk_->frames() > 0 && next_vtk_ - vtk_interval_ < solver_->time() - 1e-12) write_frame();
  const double wall = record.wall_s();
  summarise_steps(record, wall);
  if (surface_port_) summarise_coupling(record, wall);
  if (surface_port_ && particle_radius_m_ > 0.0) coupled_results(record);
  body_results(record);
  probe_results(record);
}

void SphRun::summarise_steps(cosim::RunRecord& record, double wall) const {
  const Solver& solver = *solver_;
  const Particles& p = model_->particles;
  nlohmann::json& summary = record.summary();
  const auto steps = solver.steps();
  summary["dt_s"] = {{"min", windows_ ? dt_min_ : 0.0}, {"mean", windows_ ? dt_sum_ / windows_ : 0.0}, {"max", dt_max_},
                     {"smallest_stability_limit", solver.smallest_limit_dt()}};
  summary["energy"] = energy_json(solver.energy());
  // Only a COULOMB wall (scene WallContact) dissipates by friction: the frictionless box's summary stays as it was.
  if (solver.energy().ground_friction_dissipation != 0.0)
    summary["energy"]["ground_friction_dissipation_J"] = solver.energy().ground_friction_dissipation;
  summary["wall_clamps"] = clamped_;
  summary["neighbour_list_rebuilds"] = solver.rebuilds();
  const double inter = static_cast<double>(solver.interactions());
  summary["performance"] = {
      {"particle_steps_per_s", wall > 0 ? p.n_real * static_cast<double>(steps) / wall : 0.0},
      {"mean_neighbours", steps && p.n_real ? inter / (static_cast<double>(steps) * p.n_real) : 0.0},
      {"interactions_per_s", wall > 0 ? inter / wall : 0.0},
      {"note", "interactions: neighbour pairs within the support per step, counted from both "
               "sides as DualSPHysics counts them (each is visited twice a step: rates, forces)"}};
}

void SphRun::summarise_coupling(cosim::RunRecord& record, double wall) const {
  const Solver& solver = *solver_;
  nlohmann::json& summary = record.summary();
  // Stepping only (model building and the start handshake excluded).
  const double compute = wall - wall_at_coupling_s_ - exchange_wait_s_;
  auto& perf = summary["performance"];
  perf["coupled_wall_s"] = wall - wall_at_coupling_s_;
  perf["exchange_wait_s"] = exchange_wait_s_;
  perf["compute_s"] = compute;
  perf["compute_s_per_step"] = windows_ ? compute / windows_ : 0.0;  // per window
  perf["coupling_window_s"] = summary["coupled_dt_s"];
  // Windows in which the terrain's own limit fell below the window (docs/coupling.md).
  perf["terrain_substepped_windows"] = solver.substepped_windows();
  perf["terrain_most_substeps_per_window"] = solver.most_substeps();
  if (!substeps_cause_.empty()) perf["terrain_most_substeps_cause"] = substeps_cause_;
  perf["active_particle_share"] = solver.mean_active_share();
  perf["held_load_window_limit_s"] = solver.held_load_limit_dt();
  perf["smallest_terrain_stability_limit_s"] = solver.smallest_limit_dt();
  perf["active_domain_margin_m"] = scene_.coupling().active_domain_margin_m();
  perf["active_domain_wake_limit_m"] = scene_.coupling().active_domain_wake_limit_m();
  const double* impulse = solver.surface_impulse_Ns();
  summary["surface_impulse_on_particles_Ns"] = {impulse[0], impulse[1], impulse[2]};
}

// The rut and the deepest penetration (docs/outputs.md), for every coupled run.
void SphRun::coupled_results(cosim::RunRecord& record) const {
  const Model& model = *model_;
  const Solver& solver = *solver_;
  const Particles& p = model.particles;
  nlohmann::json& results = record.results();
  const RutSurface rut = rut_surface(rut_grid_, p.n_real, p.x.data(), p.y.data(), p.z.data());
  write_rut_csv(record.path("rut_surface.csv"), rut_grid_, rut);
  results["rut_depth_m"] = rut.rut_depth_m;
  results["max_penetration_m"] = max_penetration_m_;
  if (deepest_.facet >= 0)  // where a particle went deepest (terrain_contact.csv: at each row's exchange)
    results["deepest_contact"] = {{"time_s", deepest_.time_s}, {"particle_x_m", deepest_.particle_x_m},
                                  {"particle_y_m", deepest_.particle_y_m}, {"particle_z_m", deepest_.particle_z_m},
                                  {"facet", static_cast<std::int64_t>(deepest_.facet)}};
  results["particle_radius_m"] = particle_radius_m_;
  // Water squeezed into films thinner than half a particle (docs/water.md).
  double water_kg = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (model.materials[p.material[i]].kind == MaterialModel::Kind::water) water_kg += p.mass[i];
  if (water_kg > 0.0 || solver.drained_particles() > 0) {
    results["drained_water_particles"] = solver.drained_particles();
    results["drained_water_mass_kg"] = solver.drained_mass_kg();
    results["drained_water_share"] = solver.drained_mass_kg() / (water_kg + solver.drained_mass_kg());
    results["water_density_out_of_range_particles"] = solver.density_out_particles();  // among the drained
  }
  if (scene_.coupling().place_terrain_around_loaded_tyre()) {  // where the tyre stood when the terrain was placed
    results["particles_removed_inside_the_tyre"] = solver.displaced_particles();
    results["mass_removed_inside_the_tyre_kg"] = solver.displaced_mass_kg();
  }
}

void SphRun::body_results(cosim::RunRecord& record) const {
  const double t = solver_->time();
  nlohmann::json& results = record.results();
  for (const auto& b : model_->bodies) {
    results[b.name + "_displacement_m"] = b.z0 - b.z;
    if (std::isfinite(b.surface_z)) {
      results[b.name + "_sinkage_m"] = b.surface_z - b.z;  // below the snow's surface at the start
      results[b.name + "_snow_surface_z_m"] = b.surface_z;
    }
    results[b.name + "_velocity_z_m_per_s"] = b.vz;
    results[b.name + "_contact_force_z_N"] = b.contact_force_z_domain * b.symmetry_factor;
    results[b.name + "_applied_force_z_N"] = b.applied_force_z_now(t);
    if (b.rest_speed > 0.0) {
      const bool rested = b.at_rest(t);
      results[b.name + "_at_rest"] = rested;
      results[b.name + "_rest_speed_criterion_m_per_s"] = b.rest_speed;
      if (rested) results[b.name + "_came_to_rest_at_s"] = b.slow_since_s;
    }
  }
}

void SphRun::probe_results(cosim::RunRecord& record) const {
  const Model& model = *model_;
  const Particles& p = model.particles;
  nlohmann::json& results = record.results();
  const auto& sph = scene_.sph();
  if (sph.probes().floor_pressure()) {
    double weight = 0.0;
    for (std::size_t i = 0; i < p.n_real; ++i) weight += p.mass[i];
    weight *= std::abs(model.settings.gravity[2]);
    const double area = (model.container_max[0] - model.container_min[0]) *
                        (model.container_max[1] - model.container_min[1]);
    const double hydro = weight / area;
    const double bottom = probe_time_ > 0 ? probe_sum_ / probe_time_ : 0.0;
    results["bottom_pressure_Pa"] = bottom;
    results["hydrostatic_pressure_Pa"] = hydro;
    results["bottom_pressure_relative_error"] = (bottom - hydro) / hydro;
    results["note_hydrostatic"] = "rho g H as the column's weight per floor area";
  }
  if (sph.probes().surge_front()) {
    const auto& region = sph.blocks(0).region();
    results["column_width_m"] = region.max().x() - region.min().x();
    results["column_height_m"] = region.max().z() - region.min().z();
    results["final_front_m"] = surge_front(model);
  }
}

}  // namespace snow_sph
