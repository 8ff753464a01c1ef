// The terrain's state in a checkpoint (cosim/checkpoint.hpp, docs/reliability.md).
// Saved: every particle field of the real particles and their ghosts, the
// neighbour list with the positions it was built at (so that the restarted run
// rebuilds it at the same step as the uninterrupted one), the friction sticks,
// the rigid bodies, the energy balance and every counter a later step reads.
// Not saved: the per-step work arrays (rates, powers, pair factors), which each
// step computes before it reads them.
#include <algorithm>
#include <type_traits>
#include <utility>

#include "snow_sph/solver.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {
namespace {

// Named fields, as templates so that saving reads a const state through the
// same lists as restoring.
template <class T> using Named = std::vector<std::pair<const char*, T*>>;

template <class E> auto energy_fields(E& e) {
  using D = std::remove_reference_t<decltype((e.kinetic))>;
  return Named<D>{{"kinetic", &e.kinetic},
                  {"internal", &e.internal},
                  {"elastic", &e.elastic},
                  {"plastic_dissipation", &e.plastic_dissipation},
                  {"viscous_dissipation", &e.viscous_dissipation},
                  {"contact_dissipation", &e.contact_dissipation},
                  {"contact_elastic", &e.contact_elastic},
                  {"external_work", &e.external_work},
                  {"deactivated_kinetic", &e.deactivated_kinetic},
                  {"drained_kinetic", &e.drained_kinetic},
                  {"initial_total", &e.initial_total},
                  {"ground_friction_dissipation", &e.ground_friction_dissipation},
                  {"initial_kinetic", &e.initial_kinetic},
                  {"plastic_cap", &e.plastic_cap},
                  {"plastic_shear", &e.plastic_shear},
                  {"artificial_viscous", &e.artificial_viscous},
                  {"damping", &e.damping},
                  {"water_viscous", &e.water_viscous},
                  {"gravity_work", &e.gravity_work},
                  {"wall_work", &e.wall_work},
                  {"body_work", &e.body_work},
                  {"resting_terrain_work", &e.resting_terrain_work},
                  {"surface_work_on_particles", &e.surface_work_on_particles},
                  {"surface_friction", &e.surface_friction},
                  {"surface_damping", &e.surface_damping},
                  {"surface_contact_elastic", &e.surface_contact_elastic},
                  {"initial_surface_contact_elastic", &e.initial_surface_contact_elastic}};
}

// The moving state of a rigid body (its geometry and load come from the scene).
template <class B> auto body_fields(B& b) {
  using D = std::remove_reference_t<decltype((b.x))>;
  return Named<D>{{"x", &b.x}, {"y", &b.y}, {"z", &b.z}, {"vz", &b.vz}, {"az", &b.az},
                  {"slow_since_s", &b.slow_since_s}, {"contact_force_x", &b.contact_force_x_domain},
                  {"contact_force_y", &b.contact_force_y_domain}, {"contact_force_z", &b.contact_force_z_domain}};
}

}  // namespace

void Solver::save(cosim::CheckpointWriter& out) const {
  Particles& p = m_.particles;
  out.put_value<std::uint64_t>("sph.n_real", p.n_real);
  const auto names = Particles::real_field_names();
  const auto fields = p.real_fields();
  for (std::size_t k = 0; k < fields.size(); ++k) out.put(std::string("sph.particles.") + names[k], *fields[k]);
  out.put("sph.particles.material", p.material);
  out.put("sph.particles.id", p.id);
  out.put("sph.particles.neighbour_count", p.neighbour_count);
  out.put("sph.particles.active", p.active);
  out.put("sph.particles.moving", p.moving);
  out.put("sph.particles.ghost_source", p.ghost_source);
  out.put("sph.particles.ghost_planes", p.ghost_planes);
  out.put("sph.list.offsets", neighbours_.list.offsets);
  out.put("sph.list.index", neighbours_.list.index);
  out.put_value("sph.list.radius", neighbours_.list.radius);
  out.put("sph.list.ref_x", neighbours_.ref_x);
  out.put("sph.list.ref_y", neighbours_.ref_y);
  out.put("sph.list.ref_z", neighbours_.ref_z);
  out.put("sph.is_water", flags_.is_water);
  out.put("sph.water_viscosity", flags_.water_viscosity);
  save_sticks(out);
  // Per rigid body, one array per field over the bodies.
  const RigidBody none;
  for (std::size_t k = 0; k < body_fields(none).size(); ++k) {
    std::vector<double> values;
    for (const RigidBody& b : m_.bodies) values.push_back(*body_fields(b)[k].second);
    out.put(std::string("sph.bodies.") + body_fields(none)[k].first, values);
  }
  for (const auto& [name, value] : energy_fields(energy_)) out.put_value(std::string("sph.energy.") + name, *value);
  out.put_value("sph.clock.time_s", clock_.time);
  out.put_value("sph.clock.dt_prev_s", clock_.dt_prev);
  out.put_value("sph.clock.step_dt_s", clock_.step_dt);
  out.put_value("sph.clock.window_dt_s", clock_.window_dt);
  out.put_value("sph.clock.smallest_limit_dt_s", smallest_limit_dt_);
  out.put_value("sph.clock.coupling_window_s", m_.settings.coupling_window_s);
  out.put_value("sph.clock.steps", clock_.steps);
  out.put_value("sph.clock.interactions", clock_.interactions);
  out.put_value<std::uint64_t>("sph.clock.substepped_windows", clock_.substepped_windows);
  out.put_value<std::uint64_t>("sph.clock.most_substeps", clock_.most_substeps);
  out.put_value<std::uint64_t>("sph.list.rebuilds", neighbours_.rebuilds);
  out.put_value("sph.surface.held_load_limit_dt_s", surface_.held_load_limit_dt);
  out.put("sph.surface.force_N", std::vector<double>(surface_.force, surface_.force + 3));
  out.put("sph.surface.impulse_Ns", std::vector<double>(surface_.impulse, surface_.impulse + 3));
  out.put_value("sph.surface.window_kick_s", surface_.window_kick);
  out.put_value<std::uint8_t>("sph.surface.held", surface_.held ? 1 : 0);
  out.put_value("sph.removed.drained_mass_kg", removed_.drained_mass_kg);
  out.put_value<std::uint64_t>("sph.removed.drained_particles", removed_.drained_particles);
  out.put_value<std::uint64_t>("sph.removed.density_out_particles", removed_.density_out_particles);
  out.put_value("sph.domain.active_share_sum", domain_.active_share_sum);
  out.put_value("sph.domain.active_samples", domain_.active_samples);
}

// The friction sticks with the coupled surface, field by field.
void Solver::save_sticks(cosim::CheckpointWriter& out) const {
  const auto& sticks = surface_.friction_history.sticks;
  std::vector<std::uint32_t> facet(sticks.size());
  std::vector<float> normal(3 * sticks.size());
  std::vector<double> force(3 * sticks.size());
  for (std::size_t s = 0; s < sticks.size(); ++s) {
    facet[s] = sticks[s].facet;
    for (int c = 0; c < 3; ++c) normal[3 * s + c] = sticks[s].normal[c], force[3 * s + c] = sticks[s].force[c];
  }
  out.put("sph.sticks.begin", surface_.friction_history.begin);
  out.put("sph.sticks.facet", facet);
  out.put("sph.sticks.normal", normal);
  out.put("sph.sticks.force", force);
}

void Solver::restore_sticks(const cosim::CheckpointReader& in) {
  FrictionHistory& history = surface_.friction_history;
  history.begin = in.get<std::uint32_t>("sph.sticks.begin");
  const auto facet = in.get<std::uint32_t>("sph.sticks.facet");
  const auto normal = in.get<float>("sph.sticks.normal", 3 * facet.size());
  const auto force = in.get<double>("sph.sticks.force", 3 * facet.size());
  history.sticks.resize(facet.size());
  for (std::size_t s = 0; s < facet.size(); ++s) {
    auto& stick = history.sticks[s];
    stick.facet = facet[s];
    for (int c = 0; c < 3; ++c) stick.normal[c] = normal[3 * s + c], stick.force[c] = force[3 * s + c];
  }
}

void Solver::restore(const cosim::CheckpointReader& in) {
  Particles& p = m_.particles;
  const auto n_real = in.get_value<std::uint64_t>("sph.n_real");
  const std::size_t size = in.get<double>("sph.particles.x").size();
  if (n_real > size) throw cosim::Error(in.path() + ": sph.n_real exceeds the particles saved");
  // The scene's particles may have drained since; never more than the scene made.
  if (n_real > p.n_real)
    throw cosim::Error(in.path() + ": the checkpoint has " + std::to_string(n_real) + " particles, this scene " +
                       std::to_string(p.n_real) + " (another particle spacing?)");
  p.resize(size);
  p.n_real = n_real;
  const auto names = Particles::real_field_names();
  const auto fields = p.real_fields();
  for (std::size_t k = 0; k < fields.size(); ++k) *fields[k] = in.get<double>(std::string("sph.particles.") + names[k], size);
  p.material = in.get<std::uint16_t>("sph.particles.material", size);
  for (auto m : p.material)
    if (m >= m_.materials.size()) throw cosim::Error(in.path() + ": a particle's material is not in this scene");
  p.id = in.get<std::uint32_t>("sph.particles.id", size);
  p.neighbour_count = in.get<std::uint32_t>("sph.particles.neighbour_count", size);
  p.active = in.get<std::uint8_t>("sph.particles.active", size);
  p.moving = in.get<std::uint8_t>("sph.particles.moving", size);
  p.ghost_source = in.get<std::uint32_t>("sph.particles.ghost_source", size);
  p.ghost_planes = in.get<std::uint8_t>("sph.particles.ghost_planes", size);
  restore_neighbours(in, n_real, size);
  restore_sticks(in);
  const RigidBody none;
  for (std::size_t k = 0; k < body_fields(none).size(); ++k) {
    const char* name = body_fields(none)[k].first;
    const auto values = in.get<double>(std::string("sph.bodies.") + name, m_.bodies.size());
    for (std::size_t b = 0; b < m_.bodies.size(); ++b) *body_fields(m_.bodies[b])[k].second = values[b];
  }
  for (const auto& [name, value] : energy_fields(energy_)) *value = in.get_value<double>(std::string("sph.energy.") + name);
  clock_.time = in.get_value<double>("sph.clock.time_s");
  clock_.dt_prev = in.get_value<double>("sph.clock.dt_prev_s");
  clock_.step_dt = in.get_value<double>("sph.clock.step_dt_s");
  clock_.window_dt = in.get_value<double>("sph.clock.window_dt_s");
  smallest_limit_dt_ = in.get_value<double>("sph.clock.smallest_limit_dt_s");
  m_.settings.coupling_window_s = in.get_value<double>("sph.clock.coupling_window_s");
  clock_.steps = in.get_value<std::uint64_t>("sph.clock.steps");
  clock_.interactions = in.get_value<std::uint64_t>("sph.clock.interactions");
  clock_.substepped_windows = in.get_value<std::uint64_t>("sph.clock.substepped_windows");
  clock_.most_substeps = static_cast<std::uint32_t>(in.get_value<std::uint64_t>("sph.clock.most_substeps"));
  neighbours_.rebuilds = in.get_value<std::uint64_t>("sph.list.rebuilds");
  surface_.held_load_limit_dt = in.get_value<double>("sph.surface.held_load_limit_dt_s");
  const auto force = in.get<double>("sph.surface.force_N", 3), impulse = in.get<double>("sph.surface.impulse_Ns", 3);
  for (int c = 0; c < 3; ++c) surface_.force[c] = force[c], surface_.impulse[c] = impulse[c];
  surface_.window_kick = in.get_value<double>("sph.surface.window_kick_s");
  surface_.held = in.get_value<std::uint8_t>("sph.surface.held") != 0;
  removed_.drained_mass_kg = in.get_value<double>("sph.removed.drained_mass_kg");
  removed_.drained_particles = in.get_value<std::uint64_t>("sph.removed.drained_particles");
  removed_.density_out_particles = in.get_value<std::uint64_t>("sph.removed.density_out_particles");
  domain_.active_share_sum = in.get_value<double>("sph.domain.active_share_sum");
  domain_.active_samples = in.get_value<std::uint64_t>("sph.domain.active_samples");
  // Per-particle work arrays sized for the restored particles (each step fills them).
  size_work_arrays(n_real, size);
  if (domain_.on) rebuild_active_lists(m_.particles, domain_);
}

void Solver::restore_neighbours(const cosim::CheckpointReader& in, std::size_t n_real, std::size_t size) {
  NeighbourList& list = neighbours_.list;
  list.offsets = in.get<std::uint32_t>("sph.list.offsets", n_real + 1);
  list.index = in.get<std::uint32_t>("sph.list.index");
  if (!list.offsets.empty() && list.offsets.back() != list.index.size())
    throw cosim::Error(in.path() + ": the neighbour list's offsets do not match its index");
  for (std::uint32_t j : list.index)
    if (j >= size) throw cosim::Error(in.path() + ": the neighbour list names a particle beyond those saved");
  list.radius = in.get_value<double>("sph.list.radius");
  neighbours_.ref_x = in.get<double>("sph.list.ref_x", n_real);
  neighbours_.ref_y = in.get<double>("sph.list.ref_y", n_real);
  neighbours_.ref_z = in.get<double>("sph.list.ref_z", n_real);
  flags_.is_water = in.get<double>("sph.is_water");
  flags_.water_viscosity = in.get<double>("sph.water_viscosity");
}

}  // namespace snow_sph
