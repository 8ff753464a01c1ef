#include "snow_sph/boundaries.hpp"

#include <cmath>

#include "cosim/parallel.hpp"

namespace snow_sph {
namespace {

double coordinate(const Particles& p, int axis, std::size_t i) {
  return axis == 0 ? p.x[i] : axis == 1 ? p.y[i] : p.z[i];
}

// Sign flips of the velocity and stress components under the mirrors of
// `mask`: a free-slip reflection over axis a flips every component with
// exactly one index a.
struct Flips {
  double vx = 1, vy = 1, vz = 1, sxy = 1, syz = 1, sxz = 1;
};

Flips flips_for(const Model& m, std::uint8_t mask) {
  Flips f;
  for (std::size_t k = 0; k < m.planes.size(); ++k) {
    if (!(mask & (1u << k))) continue;
    if (m.planes[k].contact == WallContactKind::no_slip) {
      // No slip (Morris, Fox & Zhu 1997): the image moves against its source,
      // so the velocity interpolates to zero at the wall, and the shear
      // stress, even in the distance from the wall, is kept: the pair forces
      // across the wall then carry the shear traction that holds the snow.
      f.vx = -f.vx, f.vy = -f.vy, f.vz = -f.vz;
      continue;
    }
    switch (m.planes[k].axis) {
      case 0: f.vx = -f.vx, f.sxy = -f.sxy, f.sxz = -f.sxz; break;
      case 1: f.vy = -f.vy, f.sxy = -f.sxy, f.syz = -f.syz; break;
      case 2: f.vz = -f.vz, f.syz = -f.syz, f.sxz = -f.sxz; break;
    }
  }
  return f;
}

double mirrored(const Model& m, std::uint8_t mask, int axis, double value) {
  for (std::size_t k = 0; k < m.planes.size(); ++k)
    if ((mask & (1u << k)) && m.planes[k].axis == axis) value = 2.0 * m.planes[k].position - value;
  return value;
}

}  // namespace

ShearFlips ghost_shear_flips(const Model& model, std::uint8_t mask) {
  const Flips f = flips_for(model, mask);
  return {f.sxy, f.syz, f.sxz};
}

void make_ghosts(Model& model, double range) {
  Particles& p = model.particles;
  p.resize(p.n_real);
  for (std::size_t k = 0; k < model.planes.size(); ++k) {
    const MirrorPlane& plane = model.planes[k];
    const std::size_t current = p.size();
    for (std::size_t i = 0; i < current; ++i) {
      const std::uint8_t mask = i < p.n_real ? 0 : p.ghost_planes[i];
      bool same_axis = false;  // at most one mirror per axis (validation keeps the box wide enough)
      for (std::size_t q = 0; q < model.planes.size(); ++q)
        if ((mask & (1u << q)) && model.planes[q].axis == plane.axis) same_axis = true;
      if (same_axis) continue;
      const double distance = plane.inside_sign * (coordinate(p, plane.axis, i) - plane.position);
      if (distance >= range) continue;
      const std::size_t g = p.size();
      p.resize(g + 1);
      p.ghost_source[g] = i < p.n_real ? static_cast<std::uint32_t>(i) : p.ghost_source[i];
      p.ghost_planes[g] = static_cast<std::uint8_t>(mask | (1u << k));
      const std::uint32_t s = p.ghost_source[g];
      p.material[g] = p.material[s];
      p.mass[g] = p.mass[s];
      p.id[g] = p.id[s];
      // Position now: later planes decide on images of images from it.
      p.x[g] = p.x[i], p.y[g] = p.y[i], p.z[g] = p.z[i];
      double& c = plane.axis == 0 ? p.x[g] : plane.axis == 1 ? p.y[g] : p.z[g];
      c = 2.0 * plane.position - c;
    }
  }
  refresh_ghost_kinematics(model);
  refresh_ghost_state(model);
}

void refresh_ghost_kinematics(Model& model) {
  Particles& p = model.particles;
  const std::size_t n_ghost = p.size() - p.n_real;
  cosim::parallel_for("ghosts.kinematics", n_ghost, [&](std::size_t k) {
    const std::size_t g = p.n_real + k;
    const std::uint32_t s = p.ghost_source[g];
    const std::uint8_t mask = p.ghost_planes[g];
    const Flips f = flips_for(model, mask);
    p.x[g] = mirrored(model, mask, 0, p.x[s]);
    p.y[g] = mirrored(model, mask, 1, p.y[s]);
    p.z[g] = mirrored(model, mask, 2, p.z[s]);
    p.vx[g] = f.vx * p.vx[s];
    p.vy[g] = f.vy * p.vy[s];
    p.vz[g] = f.vz * p.vz[s];
  });
}

void refresh_ghost_state(Model& model) {
  Particles& p = model.particles;
  const double* g = model.settings.gravity;
  const std::size_t n_ghost = p.size() - p.n_real;
  cosim::parallel_for("ghosts.state", n_ghost, [&](std::size_t k) {
    const std::size_t i = p.n_real + k;
    const std::uint32_t s = p.ghost_source[i];
    const Flips f = flips_for(model, p.ghost_planes[i]);
    // Hydrostatic increment between the image and its source.
    const double dp = p.density[s] * (g[0] * (p.x[i] - p.x[s]) + g[1] * (p.y[i] - p.y[s]) +
                                      g[2] * (p.z[i] - p.z[s]));
    const MaterialModel& mat = model.materials[p.material[s]];
    p.sxx[i] = p.sxx[s] - dp;
    p.syy[i] = p.syy[s] - dp;
    p.szz[i] = p.szz[s] - dp;
    p.sxy[i] = f.sxy * p.sxy[s];
    p.syz[i] = f.syz * p.syz[s];
    p.sxz[i] = f.sxz * p.sxz[s];
    p.pressure[i] = p.pressure[s] + dp;
    p.density[i] = mat.kind == MaterialModel::Kind::water
                       ? p.density[s] + dp / (mat.eos.c0 * mat.eos.c0)
                       : p.density[s];
    p.sound_speed[i] = p.sound_speed[s];
  });
}

void wall_repulsion(const Model& model, double* ax, double* ay, double* az, double* power) {
  const Particles& p = model.particles;
  const double reach = model.particle_radius_m();
  cosim::parallel_for("walls.repulsion", p.n_real, [&](std::size_t i) {
    // A particle at rest outside the active domain gets no force pass that would
    // reset its acceleration: adding the wall's push to it every step piled up
    // 1.3e9 m/s^2 on a splash resting against a side wall in a hydroplaning run.
    if (!p.active[i]) {
      power[i] = 0.0;  // at rest: the wall does no work on it
      return;
    }
    double a[3] = {0, 0, 0};
    for (const MirrorPlane& plane : model.planes) {
      if (plane.symmetry) continue;
      const double d = plane.inside_sign * (coordinate(p, plane.axis, i) - plane.position);
      if (d >= reach) continue;
      const double s = (reach - std::max(d, 0.0)) / reach;
      const double c = p.sound_speed[i];
      a[plane.axis] += plane.inside_sign * c * c / reach * s * s;
    }
    ax[i] += a[0], ay[i] += a[1], az[i] += a[2];
    power[i] = p.mass[i] * (a[0] * p.vx[i] + a[1] * p.vy[i] + a[2] * p.vz[i]);
  });
}

std::size_t clamp_to_walls(Model& model) {
  Particles& p = model.particles;
  std::size_t clamped = 0;
  for (const MirrorPlane& plane : model.planes) {
    double* c = plane.axis == 0 ? p.x.data() : plane.axis == 1 ? p.y.data() : p.z.data();
    double* v = plane.axis == 0 ? p.vx.data() : plane.axis == 1 ? p.vy.data() : p.vz.data();
    for (std::size_t i = 0; i < p.n_real; ++i) {
      if (plane.inside_sign * (c[i] - plane.position) < 0.0) {
        c[i] = 2.0 * plane.position - c[i];  // reflect back inside
        if (plane.inside_sign * v[i] < 0.0) v[i] = 0.0;
        ++clamped;
      }
    }
  }
  return clamped;
}

}  // namespace snow_sph
