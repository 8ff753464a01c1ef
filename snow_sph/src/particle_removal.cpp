// Particles leaving the terrain: water drained from films it cannot resolve,
// spray and water out of its valid density (docs/water.md), and particles
// inside a body the terrain was placed around (placement.hpp).
#include "snow_sph/stages.hpp"

namespace snow_sph {

std::pair<double, double> take_out_particles(Particles& p, const std::vector<std::uint32_t>& gone) {
  std::vector<std::uint32_t> keep;
  keep.reserve(p.n_real - gone.size());
  std::size_t next = 0;
  double mass = 0.0, kinetic = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (next < gone.size() && gone[next] == i) {
      kinetic += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      mass += p.mass[i];
      ++next;
      continue;
    }
    keep.push_back(static_cast<std::uint32_t>(i));
  }
  p.resize(p.n_real);
  p.permute_real(keep);
  p.n_real = keep.size();
  p.resize(p.n_real);
  return {mass, kinetic};
}

// Spray that has left the open-top box: the walls are planes that go on
// above the box, and a splash falling back along one of them is not a flow
// the box models (docs/water.md, "Films thinner than a particle"). And water
// whose density has left its valid range: a splash stretched until its
// continuity density says it is a third empty, or water crushed in a pinch,
// is no longer a flow the particles resolve (DualSPHysics's RhopOut).
std::vector<std::uint32_t> water_leaving_flow(const Model& m, std::size_t& density_out) {
  const Particles& p = m.particles;
  std::vector<std::uint32_t> spray;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    const MaterialModel& mat = m.materials[p.material[i]];
    if (mat.kind != MaterialModel::Kind::water) continue;
    const bool out_of_range = !mat.density_valid(p.density[i]);
    if (out_of_range) ++density_out;
    if (out_of_range || p.z[i] > m.container_max[2]) spray.push_back(static_cast<std::uint32_t>(i));
  }
  return spray;
}

}  // namespace snow_sph
