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

namespace {

// One step's sums of the per-particle powers [W] and increments [J].
struct StepSums {
  double stress = 0, viscous = 0, plastic = 0, plastic_cap = 0, boundary = 0;
  double artificial_viscous = 0, damping = 0, water_viscous = 0;
  void add(const StepPowers& powers, std::size_t i) {
    stress += powers.stress[i], viscous += powers.viscous[i], plastic += powers.plastic_increment[i];
    plastic_cap += powers.plastic_cap_increment[i];
    artificial_viscous += powers.artificial_viscous[i], damping += powers.damping[i];
    water_viscous += powers.water_viscous[i];
  }
};

}  // namespace

void update_energy(const Model& model, const ActiveDomain& domain, const StepPowers& powers, double time_s, double dt,
                   EnergyBalance& energy) {
  const Particles& p = model.particles;
  double ke = 0, el = 0, gw = 0, gravity = 0, walls = 0;
  const double* g = model.settings.gravity;
  // Resting particles (outside the active domain) have v = 0 and no stress
  // power this step; their entries of the per-step arrays are stale.
  StepSums sum;
  if (domain.on)
    for (std::uint32_t i : domain.force_list) sum.add(powers, i), sum.boundary += domain.boundary_power[i];
  for (std::size_t i = 0; i < p.n_real; ++i) {
    const double m = p.mass[i];
    ke += 0.5 * m * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    if (!domain.on) sum.add(powers, i);
    const double gravity_power = m * (g[0] * p.vx[i] + g[1] * p.vy[i] + g[2] * p.vz[i]);
    gw += gravity_power + powers.wall[i];
    gravity += gravity_power, walls += powers.wall[i];
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
  energy.internal += sum.stress * dt;
  energy.viscous_dissipation += sum.viscous * dt;
  energy.plastic_dissipation += sum.plastic;
  energy.external_work += (gw + body_work + sum.boundary) * dt;
  // The parts of the lumped terms above.
  energy.plastic_cap += sum.plastic_cap;
  energy.plastic_shear += sum.plastic - sum.plastic_cap;
  energy.artificial_viscous += sum.artificial_viscous * dt;
  energy.damping += sum.damping * dt;
  energy.water_viscous += sum.water_viscous * dt;
  energy.gravity_work += gravity * dt;
  energy.wall_work += walls * dt;
  energy.body_work += body_work * dt;
  energy.resting_terrain_work += sum.boundary * dt;
  // Zero without a COULOMB wall (ground_friction.cpp leaves the array at 0).
  for (std::size_t i = 0; i < p.n_real; ++i) energy.ground_friction_dissipation += powers.ground_friction_increment[i];
}

}  // namespace snow_sph
