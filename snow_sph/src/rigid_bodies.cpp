// Rigid bodies: cylinders moving along z (a plate, a pressure-sinkage
// indenter), driven or loaded, in penalty contact with the particles.
#include <algorithm>
#include <cmath>

#include "cosim/parallel.hpp"
#include "cosim/penalty_contact.hpp"
#include "cosim/ramp.hpp"
#include "snow_sph/cylinder_contact.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {

double RigidBody::applied_force_z_now(double t) const {
  return cosim::ramp(cosim::RampCurve::smootherstep, t, ramp_time, applied_force_z_full);
}

void move_bodies(Model& m, double time_s, double kick, double dt) {
  for (auto& b : m.bodies) {
    if (b.prescribed_velocity) {
      b.vz = b.prescribed_vz;
    } else {
      const double force = b.applied_force_z_now(time_s) / b.symmetry_factor + b.contact_force_z_domain;
      b.az = force / b.mass_domain;
      b.vz += kick * b.az;
    }
    b.z += dt * b.vz;
  }
}

// The rigid bodies' normal damper: a fraction of critical, approaching and
// separating (cosim::penalty::Damping::both_ways).
constexpr double kBodyContactDampingRatio = 0.2;

// Penalty contact of particles (spheres of radius dx/2) with rigid
// cylinders, Coulomb friction regularised so that sticking stops the relative
// sliding within one step.
void body_contact(Model& model, double dt, BodyContactWork& work, EnergyBalance& energy) {
  Particles& p = model.particles;
  const double k_n = model.settings.contact_stiffness;
  const double rc = model.particle_radius_m();
  double stored = 0.0;
  for (auto& b : model.bodies) {
    std::fill(work.fx.begin(), work.fx.end(), 0.0);
    std::fill(work.fy.begin(), work.fy.end(), 0.0);
    std::fill(work.fz.begin(), work.fz.end(), 0.0);
    std::fill(work.dissipation.begin(), work.dissipation.end(), 0.0);
    cosim::parallel_for("sph.contact", p.n_real, [&](std::size_t i) {
      const CylinderContact c = cylinder_contact(p.x[i] - b.x, p.y[i] - b.y, p.z[i], b.radius, b.z, b.z + b.thickness, rc);
      if (!(c.depth > 0.0)) return;
      const double nx = c.nx, ny = c.ny, nz = c.nz, depth = c.depth;
      const double m = p.mass[i];
      const double wx = p.vx[i], wy = p.vy[i], wz = p.vz[i] - b.vz;  // relative velocity
      const double vn = wx * nx + wy * ny + wz * nz;
      const double damping = cosim::penalty::damping_coefficient(kBodyContactDampingRatio, k_n, m);
      const cosim::penalty::NormalForce normal =
          cosim::penalty::normal_force(k_n, depth, vn, damping, cosim::penalty::Damping::both_ways);
      const double fn = normal.force_N;
      const double tx = wx - vn * nx, ty = wy - vn * ny, tz = wz - vn * nz;
      const double vt = std::sqrt(tx * tx + ty * ty + tz * tz);
      double ft = 0.0;
      if (vt > 0.0) ft = cosim::penalty::velocity_stop_friction(b.friction * fn, m, vt, dt);
      const double fx = fn * nx - (vt > 0 ? ft * tx / vt : 0.0);
      const double fy = fn * ny - (vt > 0 ? ft * ty / vt : 0.0);
      const double fz = fn * nz - (vt > 0 ? ft * tz / vt : 0.0);
      p.ax[i] += fx / m, p.ay[i] += fy / m, p.az[i] += fz / m;
      work.fx[i] = fx, work.fy[i] = fy, work.fz[i] = fz;
      work.dissipation[i] = (ft * vt + cosim::penalty::approach_damping_power(normal, vn)) * dt;
    });
    double fx = 0, fy = 0, fz = 0, dissipated = 0;
    for (std::size_t i = 0; i < p.n_real; ++i) {
      fx -= work.fx[i], fy -= work.fy[i], fz -= work.fz[i];
      dissipated += work.dissipation[i];
      if (work.fx[i] != 0 || work.fy[i] != 0 || work.fz[i] != 0) {
        const double fn = std::sqrt(work.fx[i] * work.fx[i] + work.fy[i] * work.fy[i] +
                                    work.fz[i] * work.fz[i]);
        stored += 0.5 * fn * fn / k_n;
      }
    }
    b.contact_force_x_domain = fx, b.contact_force_y_domain = fy, b.contact_force_z_domain = fz;
    energy.contact_dissipation += dissipated;
  }
  energy.contact_elastic = stored;
}

}  // namespace snow_sph
