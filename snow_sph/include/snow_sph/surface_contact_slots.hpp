#pragma once
// The contacts of each particle with the coupled surface's facets, as the
// contact stage leaves them (surface_contact.cpp) for the serial scatter stage
// (surface_scatter.cpp): per particle, so that the sums are serial and
// independent of the thread count.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

// The contacts of one particle (at most kMaxContacts facets).
constexpr int kMaxContacts = 6;
struct Contact {
  std::int32_t facet = -1;
  std::uint32_t facet_id = 0;  // in the owner's numbering (the history's key)
  double normal[3] = {0, 0, 0};
  double spring[3] = {0, 0, 0};  // elastic tangential force on the particle after this call
  double w[4] = {0, 0, 0, 0};
  double f[3] = {0, 0, 0};  // force on the particle
  double fn = 0.0, ft[3] = {0, 0, 0};
  double penetration_m = 0.0;  // radius - signed distance, before the cap at one radius
  double friction_J = 0.0, damping_J = 0.0, elastic_J = 0.0;
};
struct ParticleContacts {
  int count = 0;
  bool drained = false;
  Contact c[kMaxContacts];
};

// Serial sums in particle order: the reaction on the facet nodes and facets.
void scatter_loads(const ContactSurface& s, const SurfaceContactParameters& params, std::size_t n_particles,
                   const double* x, const double* y, const double* z, const std::vector<ParticleContacts>& contacts,
                   SurfaceContactResult& loads);

// The sticks of this call, the history of the next, grouped by particle id
// (particle_id null: the index is the id).
FrictionHistory next_history(std::size_t n_particles, const std::vector<ParticleContacts>& contacts,
                             const std::uint32_t* particle_id);

// The touched part of each facet and its mean pressure.
void facet_contact_areas(double radius, std::size_t n_particles, const std::vector<ParticleContacts>& contacts,
                         const std::vector<double>& area, SurfaceContactResult& loads);

}  // namespace snow_sph
