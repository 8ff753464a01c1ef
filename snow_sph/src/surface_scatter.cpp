// The scatter stage of the surface contact (surface_contact_slots.hpp): the
// particles' contacts summed serially, in particle order, onto the facet nodes
// and facets; the friction sticks kept for the next call; the contact areas.
#include <algorithm>

#include "snow_sph/surface_contact_slots.hpp"

namespace snow_sph {

void scatter_loads(const ContactSurface& s, const SurfaceContactParameters& params, std::size_t n_particles,
                   const double* x, const double* y, const double* z, const std::vector<ParticleContacts>& contacts,
                   SurfaceContactResult& loads) {
  for (std::size_t i = 0; i < n_particles; ++i) {
    if (contacts[i].drained) loads.drained.push_back(static_cast<std::uint32_t>(i));
    bool behind = false;
    for (int k2 = 0; k2 < contacts[i].count; ++k2) {
      const Contact& ct = contacts[i].c[k2];
      const std::uint32_t* q = &s.facet_nodes[4 * ct.facet];
      for (int a = 0; a < 4; ++a) {
        loads.node_fx[q[a]] -= ct.w[a] * ct.f[0];
        loads.node_fy[q[a]] -= ct.w[a] * ct.f[1];
        loads.node_fz[q[a]] -= ct.w[a] * ct.f[2];
      }
      loads.facet_normal_force_N[ct.facet] += ct.fn;
      loads.facet_pressure_x_N[ct.facet] -= ct.fn * ct.normal[0];
      loads.facet_pressure_y_N[ct.facet] -= ct.fn * ct.normal[1];
      loads.facet_pressure_z_N[ct.facet] -= ct.fn * ct.normal[2];
      loads.facet_tangential_x_N[ct.facet] -= ct.ft[0];
      loads.facet_tangential_y_N[ct.facet] -= ct.ft[1];
      loads.facet_tangential_z_N[ct.facet] -= ct.ft[2];
      ++loads.particles_in_contact[ct.facet];
      loads.total_fx_N -= ct.f[0], loads.total_fy_N -= ct.f[1], loads.total_fz_N -= ct.f[2];
      loads.friction_dissipation_J += ct.friction_J;
      loads.damping_dissipation_J += ct.damping_J;
      loads.elastic_energy_J += ct.elastic_J;
      // The deepest contact as a max in this serial loop: the same for any thread count.
      behind = behind || ct.penetration_m > params.particle_radius_m;
      if (ct.penetration_m > loads.max_penetration_m) {
        loads.max_penetration_m = ct.penetration_m;
        loads.deepest_x_m = x[i], loads.deepest_y_m = y[i], loads.deepest_z_m = z[i];
        loads.deepest_facet = ct.facet_id;
      }
    }
    if (behind) ++loads.particles_behind_surface;
  }
}

FrictionHistory next_history(std::size_t n_particles, const std::vector<ParticleContacts>& contacts,
                             const std::uint32_t* particle_id) {
  auto id_of = [&](std::size_t i) { return particle_id ? particle_id[i] : static_cast<std::uint32_t>(i); };
  std::uint32_t max_id = 0;
  for (std::size_t i = 0; i < n_particles; ++i) max_id = std::max(max_id, id_of(i));
  FrictionHistory next;
  next.begin.assign(static_cast<std::size_t>(max_id) + 2, 0);
  for (std::size_t i = 0; i < n_particles; ++i) next.begin[id_of(i) + 1] = static_cast<std::uint32_t>(contacts[i].count);
  for (std::size_t k2 = 0; k2 + 1 < next.begin.size(); ++k2) next.begin[k2 + 1] += next.begin[k2];
  next.sticks.resize(next.begin.back());
  for (std::size_t i = 0; i < n_particles; ++i) {
    FrictionHistory::Stick* out = next.sticks.data() + next.begin[id_of(i)];
    for (int k2 = 0; k2 < contacts[i].count; ++k2) {
      const Contact& ct = contacts[i].c[k2];
      out[k2].facet = ct.facet_id;
      for (int a = 0; a < 3; ++a)
        out[k2].normal[a] = static_cast<float>(ct.normal[a]), out[k2].force[a] = ct.spring[a];
    }
  }
  return next;
}

// The touched part of each facet: a surface particle stands for the (2 r)^2 = dx^2
// of terrain surface around it (particles on a lattice of spacing dx), shared
// equally between the facets it touches, up to the facet's own area.
void facet_contact_areas(double radius, std::size_t n_particles, const std::vector<ParticleContacts>& contacts,
                         const std::vector<double>& area, SurfaceContactResult& loads) {
  const double patch = 4.0 * radius * radius;
  for (std::size_t i = 0; i < n_particles; ++i)
    for (int k2 = 0; k2 < contacts[i].count; ++k2)
      loads.facet_contact_area_m2[contacts[i].c[k2].facet] += patch / contacts[i].count;
  for (std::size_t f = 0; f < area.size(); ++f) {
    if (loads.particles_in_contact[f] == 0) continue;
    const double touched = std::min(loads.facet_contact_area_m2[f], area[f]);
    loads.facet_contact_area_m2[f] = touched;
    loads.facet_pressure_Pa[f] = touched > 0 ? loads.facet_normal_force_N[f] / touched : 0.0;
  }
}

}  // namespace snow_sph
