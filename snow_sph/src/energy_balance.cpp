// The energy balance of the particles and bodies (docs/sph.md, "Energy
// balance"), booked at the end of each step from the stages' powers.
#include <algorithm>
#include <cmath>

#include "snow_sph/stages.hpp"

namespace snow_sph {

double EnergyBalance::relative_error() const {
  const double scale = std::max({std::abs(kinetic), std::abs(internal), std::abs(external_work),
                                 std::abs(viscous_dissipation), 1e-30});
  return std::abs(total() - initial_total) / scale;
}

void update_energy(const Model& model, const ActiveDomain& domain, const StepPowers& powers, double time_s, double dt,
                   EnergyBalance& energy) {
  const Particles& p = model.particles;
  double ke = 0, el = 0, ip = 0, vp = 0, pl = 0, gw = 0;
  const double* g = model.settings.gravity;
  // Resting particles (outside the active domain) have v = 0 and no stress
  // power this step; their entries of the per-step arrays are stale.
  double bp = 0.0;
  if (domain.on)
    for (std::uint32_t i : domain.force_list)
      ip += powers.stress[i], vp += powers.viscous[i], pl += powers.plastic_increment[i], bp += domain.boundary_power[i];
  for (std::size_t i = 0; i < p.n_real; ++i) {
    const double m = p.mass[i];
    ke += 0.5 * m * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    if (!domain.on) ip += powers.stress[i], vp += powers.viscous[i], pl += powers.plastic_increment[i];
    gw += m * (g[0] * p.vx[i] + g[1] * p.vy[i] + g[2] * p.vz[i]) + powers.wall[i];
    const MaterialModel& mat = model.materials[p.material[i]];
    if (mat.kind == MaterialModel::Kind::water) {
      el += m * mat.eos.energy_per_mass(p.density[i]);
    } else {
      // (1/2) sigma : C^-1 : sigma V, isotropic: p^2/(2K) + q^2/(6G)
      const double K = mat.mdpc.bulk_modulus_Pa(), G = mat.mdpc.shear_modulus_Pa();
      const double pr = p.pressure[i];
      const double dxx = p.sxx[i] + pr, dyy = p.syy[i] + pr, dzz = p.szz[i] + pr;
      const double j2 = 0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) + p.sxy[i] * p.sxy[i] +
                        p.syz[i] * p.syz[i] + p.sxz[i] * p.sxz[i];
      el += (pr * pr / (2.0 * K) + j2 / (2.0 * G)) * m / p.density[i];
    }
  }
  double body_work = 0.0;
  for (const auto& b : model.bodies) {
    ke += 0.5 * b.mass_domain * b.vz * b.vz;
    if (b.prescribed_velocity)
      body_work += -b.contact_force_z_domain * b.vz;  // the drive balances contact
    else
      body_work += b.applied_force_z_now(time_s) / b.symmetry_factor * b.vz;
  }
  energy.kinetic = ke;
  energy.elastic = el;
  energy.internal += ip * dt;
  energy.viscous_dissipation += vp * dt;
  energy.plastic_dissipation += pl;
  energy.external_work += (gw + body_work + bp) * dt;
  // Zero without a COULOMB wall (ground_friction.cpp leaves the array at 0).
  for (std::size_t i = 0; i < p.n_real; ++i) energy.ground_friction_dissipation += powers.ground_friction_increment[i];
}

}  // namespace snow_sph
