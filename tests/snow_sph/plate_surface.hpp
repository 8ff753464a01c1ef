#pragma once
// The coupled surface of the terrain tests that strike test_sph_substeps's
// cube of snow: a rigid 0.4 m square plate played by the test as the surface's
// owner would, exchanged once per window.
#include "snow_sph/solver.hpp"
#include "snow_sph/surface_contact.hpp"

namespace snow_sph_test {

// The plate at height z, moving at vz, its underside facing the snow
// ((x2 - x0) x (x3 - x1) along -z), friction 0.3.
inline snow_sph::ContactSurface plate(double z, double vz) {
  snow_sph::ContactSurface s;
  const double xs[4] = {0.3, 0.3, 0.7, 0.7}, ys[4] = {0.3, 0.7, 0.7, 0.3};
  for (int a = 0; a < 4; ++a) {
    s.x.push_back(xs[a]), s.y.push_back(ys[a]), s.z.push_back(z);
    s.vx.push_back(0.0), s.vy.push_back(0.0), s.vz.push_back(vz);
  }
  s.facet_nodes = {0, 1, 2, 3};
  s.friction_coefficient = {0.3};
  return s;
}

// Couples `solver` to a surface with the scene's contact (particle radius half
// the spacing, the scene's stiffness) and prepares it; returns the contact.
inline snow_sph::SurfaceContactParameters couple_to_surface(snow_sph::Solver& solver, const snow_sph::Model& model) {
  snow_sph::SurfaceContactParameters contact;
  contact.particle_radius_m = 0.5 * model.settings.spacing;
  contact.stiffness_N_per_m = model.settings.contact_stiffness;
  solver.couple(contact);
  solver.prepare();
  return contact;
}

}  // namespace snow_sph_test
