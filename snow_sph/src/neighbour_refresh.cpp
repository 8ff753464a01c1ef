// Boundaries and ghosts before the pair loops: the mirror ghosts of walls and
// symmetry planes (boundaries.hpp) and the neighbour list (neighbours.hpp),
// rebuilt together with a skin (Verlet list). This is the point of a step
// where everything the pair loops read about other particles is made current:
// a decomposed terrain's halo exchange goes here.
#include "snow_sph/boundaries.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {

bool refresh_ghosts_and_neighbours(Model& m, NeighbourState& neighbours, MaterialFlags& flags, bool force) {
  Particles& p = m.particles;
  const double half_skin = 0.5 * m.settings.skin;
  bool rebuild = force || neighbours.ref_x.size() != p.n_real;
  if (!rebuild) {
    const double limit2 = half_skin * half_skin;
    for (std::size_t i = 0; i < p.n_real && !rebuild; ++i) {
      const double dx = p.x[i] - neighbours.ref_x[i], dy = p.y[i] - neighbours.ref_y[i],
                   dz = p.z[i] - neighbours.ref_z[i];
      rebuild = dx * dx + dy * dy + dz * dz > limit2;
    }
  }
  if (!rebuild) {
    refresh_ghost_kinematics(m);
    return false;
  }
  const double radius = m.kernel.support + m.settings.skin;
  p.resize(p.n_real);
  p.permute_real(cell_order(p.x.data(), p.y.data(), p.z.data(), p.n_real, radius));
  make_ghosts(m, radius);
  if (flags.any_water) {
    // Particles change order and ghosts only here, so their material flags do too.
    flags.is_water.resize(p.size());
    flags.water_viscosity.resize(p.size());
    for (std::size_t j = 0; j < p.size(); ++j) {
      const MaterialModel& mj = m.materials[p.material[j]];
      const bool water = mj.kind == MaterialModel::Kind::water;
      flags.is_water[j] = water ? 1.0 : 0.0;
      flags.water_viscosity[j] = water ? mj.viscosity : 0.0;
    }
  }
  build_neighbour_list(p.x.data(), p.y.data(), p.z.data(), p.n_real, p.size(), radius, neighbours.list);
  neighbours.ref_x.assign(p.x.begin(), p.x.begin() + p.n_real);
  neighbours.ref_y.assign(p.y.begin(), p.y.begin() + p.n_real);
  neighbours.ref_z.assign(p.z.begin(), p.z.begin() + p.n_real);
  ++neighbours.rebuilds;
  return true;
}

}  // namespace snow_sph
