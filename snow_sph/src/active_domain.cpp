// Active terrain domain (as Chrono's CRM "active domains"; docs/coupling.md):
// with a coupled surface, only particles near it (or still moving fast) are
// computed and moved; the others rest and act as a resting boundary.
#include <algorithm>

#include "snow_sph/stages.hpp"

namespace snow_sph {

void rebuild_active_lists(const Particles& p, ActiveDomain& domain) {
  domain.force_list.clear(), domain.move_list.clear();
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (p.active[i]) domain.force_list.push_back(static_cast<std::uint32_t>(i));
    if (p.moving[i]) domain.move_list.push_back(static_cast<std::uint32_t>(i));
  }
  domain.frozen.resize(p.size());
  domain.boundary_power.resize(p.n_real, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    domain.frozen[i] = p.active[i < p.n_real ? i : p.ghost_source[i]] ? 0.0 : 1.0;
}

double update_activity(Particles& p, const ContactSurface* surface, ActiveDomain& domain) {
  // The box of the surface near the terrain, grown by the margin (x and y).
  double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
  if (surface)
    for (std::size_t k = 0; k < surface->x.size(); ++k) {
      const double c[3] = {surface->x[k], surface->y[k], surface->z[k]};
      for (int a = 0; a < 3; ++a)
        lo[a] = std::min(lo[a], c[a] - domain.margin_m), hi[a] = std::max(hi[a], c[a] + domain.margin_m);
    }
  const double wake2 = domain.wake_speed * domain.wake_speed;
  // A moving particle stays active within the wake limit (grown beyond the margin), if there is one.
  const double w = domain.wake_limit_m - domain.margin_m;
  const double near_lo[2] = {lo[0] - w, lo[1] - w}, near_hi[2] = {hi[0] + w, hi[1] + w};
  double removed = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    const double v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i];
    // In plan only: the load of the surface spreads down through the whole
    // depth below it (a margin in depth froze the snow under a loaded tyre and
    // made the layer stiffer: +26 % vertical force on the coarse indentation).
    const bool inside = p.x[i] >= lo[0] && p.x[i] <= hi[0] && p.y[i] >= lo[1] && p.y[i] <= hi[1];
    const bool near = domain.wake_limit_m <= 0.0 || (p.x[i] >= near_lo[0] && p.x[i] <= near_hi[0] &&
                                                     p.y[i] >= near_lo[1] && p.y[i] <= near_hi[1]);
    const bool next = inside || (p.active[i] && v2 > wake2 && near);
    if (p.active[i] && !next) {
      // Comes to rest where it is: its kinetic energy leaves the balance as a loss.
      removed += 0.5 * p.mass[i] * v2;
      p.vx[i] = p.vy[i] = p.vz[i] = 0.0;
    }
    // A particle coming in moves from the step after its first force pass.
    p.moving[i] = p.active[i] && next;
    p.active[i] = next;
  }
  rebuild_active_lists(p, domain);
  domain.active_share_sum += p.n_real ? double(domain.force_list.size()) / double(p.n_real) : 1.0;
  ++domain.active_samples;
  return removed;
}

}  // namespace snow_sph
