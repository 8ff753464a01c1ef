// The step size and the coupled window: the stable limit, and the window's
// sub-steps up to the exchange (docs/coupling.md, "The terrain sub-steps").
#include <algorithm>
#include <cmath>

#include "cosim/error.hpp"
#include "snow_sph/solver.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {

// Particles outside the active domain are not integrated: they rest, and their
// accelerations are those of their last active step (particle_stability_limit_dt()).
double Solver::stability_limit_dt() const {
  double limit = particle_stability_limit_dt(m_);
  if (surface_.coupled) limit = std::min(limit, surface_contact_limit_dt());
  return limit;
}

std::string Solver::limit_cause() const { return stability_limit_cause(m_); }

double Solver::stable_dt() const {
  const double limit = stability_limit_dt();
  smallest_limit_dt_ = std::min(smallest_limit_dt_, limit);
  const double imposed = m_.settings.imposed_dt_s();
  if (imposed > 0.0) {
    if (imposed > limit)
      throw cosim::Error((m_.settings.coupling_window_s > 0.0 ? "the coupling window " : "time.fixed_dt_s = ") +
                         cosim::number_text(imposed) + " s exceeds the stable limit " + cosim::number_text(limit) +
                         " s at t = " + cosim::number_text(clock_.time) + " s (" + limit_cause() + ")");
    return imposed;
  }
  return m_.settings.cfl * limit;
}

StepStats Solver::advance_to_exchange() {
  const double window = m_.settings.coupling_window_s;
  if (!surface_.coupled || !(window > 0.0)) return advance_by(stable_dt());
  // Coupled: one step per window while the terrain's Courant number stays at or
  // below 1 (as the window was agreed); beyond, k equal sub-steps at the CFL
  // factor, re-planned for what is left if the limit falls further inside.
  StepStats stats;
  stats.dt = window;
  stats.substeps = 0;
  double left = window;
  std::uint64_t pieces = 0;  // sub-steps left, this one included
  double h = window;
  for (;;) {
    const double limit = stability_limit_dt();
    smallest_limit_dt_ = std::min(smallest_limit_dt_, limit);
    if (pieces == 0 || h > limit) {
      pieces = left > limit ? static_cast<std::uint64_t>(std::ceil(left / (m_.settings.cfl * limit))) : 1;
      if (stats.substeps + pieces > kMaxSubsteps)
        throw cosim::Error("the terrain's stable limit " + cosim::number_text(limit) + " s at t = " +
                           cosim::number_text(clock_.time) + " s (" + limit_cause() + ") would take more than " +
                           std::to_string(kMaxSubsteps) + " sub-steps in the coupling window " +
                           cosim::number_text(window) + " s");
      h = left / static_cast<double>(pieces);
    }
    const bool last = pieces == 1;
    const StepStats sub = advance_by(last ? left : h);  // the last closes the window
    stats.clamped += sub.clamped;
    stats.rebuilt = stats.rebuilt || sub.rebuilt;
    ++stats.substeps;
    if (last) break;
    if (surface_.held) hold_surface_force(m_.particles, domain_);
    finish_step();
    left -= h;
    --pieces;
  }
  clock_.window_dt = window;
  if (stats.substeps > 1) ++clock_.substepped_windows;
  clock_.most_substeps = std::max(clock_.most_substeps, stats.substeps);
  return stats;
}

void Solver::finish_window() { finish_step(); }

StepStats Solver::step() {
  const StepStats stats = advance_to_exchange();
  finish_window();
  return stats;
}

}  // namespace snow_sph
