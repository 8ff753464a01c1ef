#pragma once
// The runtime model of an SPH terrain: particles, materials, kernel,
// boundary planes and rigid bodies, built once from a scene (build.cpp) and
// then advanced by the stages in solver.hpp.
#include <string>
#include <vector>

#include "snow_sph/kernels.hpp"
#include "snow_sph/mdpc.hpp"
#include "snow_sph/neighbours.hpp"
#include "snow_sph/particles.hpp"
#include "snow_sph/water_eos.hpp"

namespace snow_sph {

struct MaterialModel {
  enum class Kind { snow, water } kind = Kind::snow;
  std::string name;
  double density0 = 0.0;
  // Snow.
  MdpcParameters mdpc;
  // Water.
  WaterEos eos;
  double reference_sound_speed = 0.0;  // c0 of the material data
  double viscosity = 0.0;              // dynamic viscosity [Pa s]
  bool sound_speed_lowered = false;
  // A water particle whose density leaves [valid_density_min, valid_density_max]
  // (kg/m^3; 0: no bound) leaves the terrain (WaterMaterial.valid_density_*_ratio).
  double valid_density_min = 0.0;
  double valid_density_max = 0.0;
  bool density_valid(double rho) const {
    return !(valid_density_min > 0.0 && rho < valid_density_min) && !(valid_density_max > 0.0 && rho > valid_density_max);
  }
};

// An axis-aligned mirror plane: a rigid free-slip wall or a symmetry plane.
// The domain lies on the side given by `inside_sign` (+1: coordinate >= position).
// A wall's contact with the snow (scene WallContact; ground_friction.hpp).
enum class WallContactKind { frictionless, coulomb, no_slip };

struct MirrorPlane {
  int axis = 0;
  double position = 0.0;
  int inside_sign = 1;
  bool symmetry = false;
  std::string face;
  WallContactKind contact = WallContactKind::frictionless;  // a symmetry plane's is frictionless
  double friction_coefficient = 0.0;                        // with contact == coulomb
};

// A rigid cylinder moving along z only, in contact with the particles.
struct RigidBody {
  std::string name;
  double radius = 0.0, thickness = 0.0;
  double mass_domain = 0.0;         // mass carried in the simulated part of a symmetric model
  double symmetry_factor = 1.0;     // full model / simulated part
  double x = 0.0, y = 0.0, z = 0.0;  // bottom centre
  double z0 = 0.0;
  // The snow's surface under the body's centre at the start: the top of the
  // particle lattice there (its block's min z plus whole layers of dx, which is
  // below the region's top when dx does not divide its height). Sinkage is
  // measured from it, as the laboratory measured the plate's (thesis 3.2).
  // NaN: no block under the body.
  double surface_z = 0.0;
  double vz = 0.0, az = 0.0;
  double friction = 0.0;
  bool prescribed_velocity = false;
  double prescribed_vz = 0.0;
  double applied_force_z_full = 0.0;  // full-model force
  double ramp_time = 0.0;
  // Rest criterion (scene RigidBody.rest_speed_m_per_s): 0 = none. slow_since_s is
  // when the speed last fell below rest_speed after the ramp (-1: not below now).
  double rest_speed = 0.0, rest_hold = 0.0, slow_since_s = -1.0;
  // The criterion is set and has been met at time t.
  bool at_rest(double t) const { return rest_speed > 0.0 && slow_since_s >= 0.0 && t - slow_since_s >= rest_hold; }
  double contact_force_z_domain = 0.0;  // last step, simulated part
  double contact_force_x_domain = 0.0, contact_force_y_domain = 0.0;
  double applied_force_z_now(double t) const;
};

struct Settings {
  double cfl = 0.3;
  double fixed_dt = 0.0;  // the scene's fixed step (time.fixed_dt_s; 0: the CFL step)
  // Coupled: the window agreed with the peers, which each step spans (its
  // sub-steps inside it); 0 on its own.
  double coupling_window_s = 0.0;
  // The step the solver is held to: the coupling window when coupled, else
  // the scene's fixed step (0: none, the CFL step).
  double imposed_dt_s() const { return coupling_window_s > 0.0 ? coupling_window_s : fixed_dt; }
  double end_time = 0.0;
  unsigned long long max_steps = 0;
  double av_alpha = 1.0, av_beta = 1.0;
  double artificial_stress_epsilon = 0.0;
  double density_diffusion_delta = 0.0;
  double damping_per_s = 0.0;
  bool kernel_gradient_correction = false;  // scene sph.kernel_gradient_correction
  double gravity[3] = {0.0, 0.0, -9.81};
  double spacing = 0.0;
  double contact_stiffness = 0.0;  // per particle [N/m]
  double skin = 0.0;
};

// What a particle block fills: its region holds whole layers of dx from the
// region's min corner (snow_sph/scene.cpp), so the particles end at
// filled_max, short of region_max when dx does not divide the region.
struct BlockLattice {
  double region_min[3] = {0, 0, 0}, region_max[3] = {0, 0, 0};
  double filled_max[3] = {0, 0, 0};
};

struct Model {
  std::string name;
  std::vector<BlockLattice> block_lattices;  // one per scene block, in order
  Particles particles;
  std::vector<MaterialModel> materials;
  Kernel kernel;
  Settings settings;
  std::vector<MirrorPlane> planes;
  std::vector<RigidBody> bodies;
  double container_min[3] = {0, 0, 0}, container_max[3] = {0, 0, 0};
  // Symmetry factor of the whole particle model (for reporting full-model values).
  double symmetry_factor = 1.0;
  // A particle as a sphere of half a spacing: its contact radius with rigid
  // bodies, walls and a coupled surface.
  double particle_radius_m() const { return 0.5 * settings.spacing; }
};

}  // namespace snow_sph
