#pragma once
// Particle state as one contiguous array per named field (structure of
// arrays). Indices [0, n_real) are the simulated particles; [n_real, size())
// are mirror ghosts created at walls and symmetry planes (boundaries.hpp).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace snow_sph {

struct Particles {
  std::size_t n_real = 0;

  // Kinematics (velocity is the half-step velocity of the central difference).
  std::vector<double> x, y, z, vx, vy, vz, ax, ay, az;
  std::vector<double> mass, density, density_rate;
  // Cauchy stress, tension positive (water: -p I).
  std::vector<double> sxx, syy, szz, sxy, syz, sxz;
  std::vector<double> pressure;            // -trace(stress)/3
  std::vector<double> sound_speed;         // current elastic wave speed
  std::vector<double> eps_vol_pl;          // snow: volumetric plastic strain (compaction +)
  std::vector<double> plastic_work;        // snow: accumulated plastic work [J]
  // Force of a coupled surface on the particle [N], from the last exchange and
  // held over the coupling window (solver.hpp); zero when not coupled.
  std::vector<double> surface_fx, surface_fy, surface_fz;
  std::vector<std::uint16_t> material;     // index into Model::materials
  std::vector<std::uint32_t> id;           // stable particle id (output)
  std::vector<std::uint32_t> neighbour_count;
  // Active terrain domain (solver.hpp): 1 if the particle's forces and state are
  // computed this step; 1 in `moving` if it is also moved (kick and drift).
  std::vector<std::uint8_t> active, moving;

  // Ghost bookkeeping: source particle and which planes it is mirrored over.
  std::vector<std::uint32_t> ghost_source;
  std::vector<std::uint8_t> ghost_planes;  // bit k set: mirrored over boundary plane k

  std::size_t size() const { return x.size(); }

  void resize(std::size_t n) {
    for (auto* f : real_fields()) f->resize(n, 0.0);
    material.resize(n, 0);
    id.resize(n, 0);
    neighbour_count.resize(n, 0);
    active.resize(n, 1);
    moving.resize(n, 1);
    ghost_source.resize(n, 0);
    ghost_planes.resize(n, 0);
  }

  std::vector<std::vector<double>*> real_fields() {
    return {&x, &y, &z, &vx, &vy, &vz, &ax, &ay, &az, &mass, &density, &density_rate,
            &sxx, &syy, &szz, &sxy, &syz, &sxz, &pressure, &sound_speed, &eps_vol_pl,
            &plastic_work, &surface_fx, &surface_fy, &surface_fz};
  }

  // The names of real_fields(), in its order (checkpoint records).
  static std::vector<const char*> real_field_names() {
    return {"x", "y", "z", "vx", "vy", "vz", "ax", "ay", "az", "mass", "density", "density_rate",
            "sxx", "syy", "szz", "sxy", "syz", "sxz", "pressure", "sound_speed", "eps_vol_pl",
            "plastic_work", "surface_fx", "surface_fy", "surface_fz"};
  }

  // Reorders the real particles by `order` (order[k] = old index of new k).
  void permute_real(const std::vector<std::uint32_t>& order);
};

// Von Mises equivalent stress q = sqrt(3/2 s:s) of particle i (s the deviator).
double von_mises_stress_Pa(const Particles& p, std::size_t i);

}  // namespace snow_sph
