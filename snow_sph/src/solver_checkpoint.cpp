// The terrain's state in a checkpoint (cosim/checkpoint.hpp, docs/reliability.md).
// Saved: every particle field of the real particles and their ghosts, the
// neighbour list with the positions it was built at (so that the restarted run
// rebuilds it at the same step as the uninterrupted one), the friction sticks,
// the rigid bodies, the energy balance and every counter a later step reads.
// Not saved: the per-step work arrays (rates, powers, pair factors), which each
// step computes before it reads them.
#include <algorithm>

#include "snow_sph/solver.hpp"

namespace snow_sph {
namespace {

// Templates, so that saving reads a const state through the same lists as restoring.
template <class E> auto energy_fields(E& e) {
  return std::vector<decltype(&e.kinetic)>{&e.kinetic, &e.internal, &e.elastic, &e.plastic_dissipation,
                                           &e.viscous_dissipation, &e.contact_dissipation, &e.contact_elastic,
                                           &e.external_work, &e.deactivated_kinetic, &e.drained_kinetic,
                                           &e.initial_total};
}

// The moving state of a rigid body (its geometry and load come from the scene).
template <class B> auto body_fields(B& b) {
  return std::vector<decltype(&b.x)>{&b.x, &b.y, &b.z, &b.vz, &b.az, &b.slow_since_s, &b.contact_force_x_domain,
                                     &b.contact_force_y_domain, &b.contact_force_z_domain};
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
  out.put("sph.list.offsets", list_.offsets);
  out.put("sph.list.index", list_.index);
  out.put_value("sph.list.radius", list_.radius);
  out.put("sph.list.ref_x", ref_x_);
  out.put("sph.list.ref_y", ref_y_);
  out.put("sph.list.ref_z", ref_z_);
  out.put("sph.is_water", is_water_);
  out.put("sph.water_viscosity", water_viscosity_);
  // The friction sticks with the coupled surface, field by field.
  const auto& sticks = friction_history_.sticks;
  std::vector<std::uint32_t> facet(sticks.size());
  std::vector<float> normal(3 * sticks.size());
  std::vector<double> force(3 * sticks.size());
  for (std::size_t s = 0; s < sticks.size(); ++s) {
    facet[s] = sticks[s].facet;
    for (int c = 0; c < 3; ++c) normal[3 * s + c] = sticks[s].normal[c], force[3 * s + c] = sticks[s].force[c];
  }
  out.put("sph.sticks.begin", friction_history_.begin);
  out.put("sph.sticks.facet", facet);
  out.put("sph.sticks.normal", normal);
  out.put("sph.sticks.force", force);
  std::vector<double> bodies;
  for (const RigidBody& b : m_.bodies)
    for (const double* v : body_fields(b)) bodies.push_back(*v);
  out.put("sph.bodies", bodies);
  std::vector<double> e;
  for (const double* v : energy_fields(energy_)) e.push_back(*v);
  out.put("sph.energy", e);
  out.put("sph.doubles",
          std::vector<double>{time_, dt_prev_, step_dt_, smallest_limit_dt_, held_load_limit_dt_, surface_force_[0],
                              surface_force_[1], surface_force_[2], surface_impulse_[0], surface_impulse_[1],
                              surface_impulse_[2], window_surface_kick_, drained_mass_kg_, window_dt_,
                              active_share_sum_, m_.settings.coupling_window_s});
  out.put("sph.counters",
          std::vector<std::uint64_t>{steps_, interactions_, rebuilds_, drained_particles_, substepped_windows_,
                                     most_substeps_, active_samples_, surface_held_ ? 1u : 0u,
                                     density_out_particles_});
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
  list_.offsets = in.get<std::uint32_t>("sph.list.offsets", n_real + 1);
  list_.index = in.get<std::uint32_t>("sph.list.index");
  if (!list_.offsets.empty() && list_.offsets.back() != list_.index.size())
    throw cosim::Error(in.path() + ": the neighbour list's offsets do not match its index");
  for (std::uint32_t j : list_.index)
    if (j >= size) throw cosim::Error(in.path() + ": the neighbour list names a particle beyond those saved");
  list_.radius = in.get_value<double>("sph.list.radius");
  ref_x_ = in.get<double>("sph.list.ref_x", n_real);
  ref_y_ = in.get<double>("sph.list.ref_y", n_real);
  ref_z_ = in.get<double>("sph.list.ref_z", n_real);
  is_water_ = in.get<double>("sph.is_water");
  water_viscosity_ = in.get<double>("sph.water_viscosity");
  friction_history_.begin = in.get<std::uint32_t>("sph.sticks.begin");
  const auto facet = in.get<std::uint32_t>("sph.sticks.facet");
  const auto normal = in.get<float>("sph.sticks.normal", 3 * facet.size());
  const auto force = in.get<double>("sph.sticks.force", 3 * facet.size());
  friction_history_.sticks.resize(facet.size());
  for (std::size_t s = 0; s < facet.size(); ++s) {
    auto& stick = friction_history_.sticks[s];
    stick.facet = facet[s];
    for (int c = 0; c < 3; ++c) stick.normal[c] = normal[3 * s + c], stick.force[c] = force[3 * s + c];
  }
  std::size_t per_body = 0;
  if (!m_.bodies.empty()) per_body = body_fields(m_.bodies[0]).size();
  const auto bodies = in.get<double>("sph.bodies", per_body * m_.bodies.size());
  std::size_t k = 0;
  for (RigidBody& b : m_.bodies)
    for (double* v : body_fields(b)) *v = bodies[k++];
  const auto e = in.get<double>("sph.energy", energy_fields(energy_).size());
  k = 0;
  for (double* v : energy_fields(energy_)) *v = e[k++];
  const auto d = in.get<double>("sph.doubles", 16);
  time_ = d[0], dt_prev_ = d[1], step_dt_ = d[2], smallest_limit_dt_ = d[3], held_load_limit_dt_ = d[4];
  for (int c = 0; c < 3; ++c) surface_force_[c] = d[5 + c], surface_impulse_[c] = d[8 + c];
  window_surface_kick_ = d[11], drained_mass_kg_ = d[12], window_dt_ = d[13], active_share_sum_ = d[14];
  m_.settings.coupling_window_s = d[15];
  const auto c = in.get<std::uint64_t>("sph.counters", 9);
  steps_ = c[0], interactions_ = c[1], rebuilds_ = c[2], drained_particles_ = c[3], substepped_windows_ = c[4];
  most_substeps_ = static_cast<std::uint32_t>(c[5]), active_samples_ = c[6], surface_held_ = c[7] != 0;
  density_out_particles_ = c[8];
  // Per-particle work arrays sized for the restored particles (each step fills them).
  for (auto* v : {&lxx_, &lxy_, &lxz_, &lyx_, &lyy_, &lyz_, &lzx_, &lzy_, &lzz_, &stress_power_, &viscous_power_,
                  &contact_fx_, &contact_fy_, &contact_fz_, &contact_dissipation_, &plastic_increment_, &wall_power_})
    v->assign(n_real, 0.0);
  for (auto* v : {&rxx_, &ryy_, &rzz_, &rxy_, &ryz_, &rxz_}) v->assign(size, 0.0);
  if (domain_) rebuild_lists();
}

}  // namespace snow_sph
