// From a validated scene to the SPH terrain's runtime model (scene.hpp): the
// materials, the kernel and settings, the walls, the particle lattices and the
// rigid bodies. Validation is in scene_validation.cpp.
#include "snow_sph/scene.hpp"

#include <cmath>
#include <limits>

#include "cosim/error.hpp"
#include "cosim/particle_lattice.hpp"

namespace snow_sph {
namespace sc = cosim::scene;
namespace {

constexpr double kPi = 3.14159265358979323846;

KernelType kernel_type(sc::Kernel k) {
  switch (k) {
    case sc::QUADRATIC: return KernelType::quadratic;
    case sc::QUINTIC: return KernelType::quintic;
    default: return KernelType::cubic;
  }
}

double snow_wave_speed(const sc::SnowMaterial& s) {
  const double E = s.youngs_modulus_pa(), nu = s.poisson_ratio();
  const double M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  return std::sqrt(M / s.density_kg_per_m3());
}

double water_sound_speed(const sc::WaterMaterial& w) {
  return w.sound_speed_override_m_per_s() > 0 ? w.sound_speed_override_m_per_s()
                                              : w.reference_sound_speed_m_per_s();
}

double coordinate(const sc::Vec3& v, int axis) { return axis == 0 ? v.x() : axis == 1 ? v.y() : v.z(); }

}  // namespace

double max_sound_speed(const sc::SphTerrain& sph) {
  double c = 0.0;
  for (const auto& b : sph.blocks()) {
    if (b.material().has_snow() && b.material().snow().density_kg_per_m3() > 0 &&
        b.material().snow().poisson_ratio() < 0.5)
      c = std::max(c, snow_wave_speed(b.material().snow()));
    if (b.material().has_water()) c = std::max(c, water_sound_speed(b.material().water()));
  }
  return c;
}

MaterialModel material_from_scene(const sc::Material& material) {
  MaterialModel m;
  if (material.has_snow()) {
    const auto& s = material.snow();
    m.kind = MaterialModel::Kind::snow;
    m.name = "snow";
    m.density0 = s.density_kg_per_m3();
    MdpcParameters& p = m.mdpc;
    p.youngs_modulus_Pa = s.youngs_modulus_pa();
    p.poisson_ratio = s.poisson_ratio();
    p.cohesion_Pa = s.cohesion_pa();
    p.friction_angle_rad = s.friction_angle_deg() * kPi / 180.0;
    p.cap_eccentricity = s.cap_eccentricity();
    p.initial_cap_volumetric_plastic_strain = s.initial_cap_volumetric_plastic_strain();
    p.transition_alpha = s.transition_surface_alpha();
    p.flow_stress_ratio_K = s.flow_stress_ratio_k();
    for (const auto& pt : s.cap_hardening()) {
      p.hardening_pressure_Pa.push_back(pt.hydrostatic_pressure_pa());
      p.hardening_volumetric_plastic_strain.push_back(pt.volumetric_plastic_strain());
    }
    try {
      check_parameters(p);
    } catch (const std::exception& e) {
      throw cosim::Error(std::string("snow material: ") + e.what());
    }
  } else {
    const auto& w = material.water();
    m.kind = MaterialModel::Kind::water;
    m.name = "water";
    m.density0 = w.density_kg_per_m3();
    m.reference_sound_speed = w.reference_sound_speed_m_per_s();
    m.sound_speed_lowered = w.sound_speed_override_m_per_s() > 0;
    m.eos.rho0 = w.density_kg_per_m3();
    m.eos.c0 = water_sound_speed(w);
    m.eos.s = w.hugoniot_slope_s();
    m.eos.tension_limit = w.tension_limit_pa();
    m.valid_density_min = w.valid_density_min_ratio() * w.density_kg_per_m3();
    m.valid_density_max = w.valid_density_max_ratio() * w.density_kg_per_m3();
    m.viscosity = w.dynamic_viscosity_pa_s();
  }
  return m;
}

namespace {

// The step's settings and the kernel, from the scene's time and sph sections
// (sph.cfl, when set, before time.cfl).
void set_settings_and_kernel(const sc::Scene& scene, Model& model) {
  const sc::SphTerrain& sph = scene.sph();
  Settings& st = model.settings;
  st.cfl = sph.cfl() > 0 ? sph.cfl() : scene.time().cfl();
  st.fixed_dt = scene.time().fixed_dt_s();
  st.end_time = scene.time().end_time_s();
  st.max_steps = scene.time().max_steps();
  st.av_alpha = sph.artificial_viscosity().alpha();
  st.av_beta = sph.artificial_viscosity().beta();
  st.artificial_stress_epsilon = sph.artificial_stress_epsilon();
  st.density_diffusion_delta = sph.density_diffusion_delta();
  st.damping_per_s = sph.quasi_static_damping_per_s();
  st.kernel_gradient_correction = sph.kernel_gradient_correction();
  st.gravity[0] = sph.gravity_m_per_s2().x();
  st.gravity[1] = sph.gravity_m_per_s2().y();
  st.gravity[2] = sph.gravity_m_per_s2().z();
  const double dx = sph.particle_spacing_m();
  st.spacing = dx;
  model.kernel = Kernel::make(kernel_type(sph.kernel()), sph.smoothing_length_ratio() * dx);
  st.skin = 0.1 * model.kernel.support;
}

WallContactKind wall_contact_kind(sc::WallContact::Kind kind) {
  switch (kind) {
    case sc::WallContact::COULOMB: return WallContactKind::coulomb;
    case sc::WallContact::NO_SLIP: return WallContactKind::no_slip;
    default: return WallContactKind::frictionless;
  }
}

// Walls and symmetry planes: the container's five closed faces (the top is open).
void add_container_planes(const sc::SphTerrain& sph, Model& model) {
  const sc::Face faces[5] = {sc::X_MIN, sc::X_MAX, sc::Y_MIN, sc::Y_MAX, sc::Z_MIN};
  const char* names[5] = {"X_MIN", "X_MAX", "Y_MIN", "Y_MAX", "Z_MIN"};
  for (int a = 0; a < 3; ++a) {
    model.container_min[a] = coordinate(sph.container().min(), a);
    model.container_max[a] = coordinate(sph.container().max(), a);
  }
  for (int f = 0; f < 5; ++f) {
    MirrorPlane plane;
    plane.axis = f / 2;
    const bool is_min = f % 2 == 0;
    plane.position = is_min ? model.container_min[plane.axis] : model.container_max[plane.axis];
    plane.inside_sign = is_min ? 1 : -1;
    plane.face = names[f];
    for (int s : sph.symmetry_planes()) plane.symmetry = plane.symmetry || s == faces[f];
    if (plane.symmetry) model.symmetry_factor *= 2.0;
    const sc::WallContact& contact = plane.axis == 2 ? sph.container().floor() : sph.container().side_walls();
    if (!plane.symmetry) {
      plane.contact = wall_contact_kind(contact.kind());
      plane.friction_coefficient = contact.friction_coefficient();
    }
    model.planes.push_back(plane);
  }
}

// The material's P-wave modulus at rest [Pa]: the stiffest block's sets the
// particles' contact stiffness with the bodies.
double p_wave_modulus_Pa(const MaterialModel& mat) {
  if (mat.kind == MaterialModel::Kind::snow) {
    const double K = mat.mdpc.bulk_modulus_Pa(), G = mat.mdpc.shear_modulus_Pa();
    return K + 4.0 * G / 3.0;
  }
  return mat.density0 * mat.eos.c0 * mat.eos.c0;
}

// The stress of particle q at `depth` [m] below its block's top, under gravity
// g [m/s^2] when the block starts geostatic (else at rest unstressed); returns
// its density.
double set_initial_state(Particles& p, std::size_t q, const MaterialModel& mat, bool geostatic, double g,
                         double depth) {
  double rho = mat.density0;
  if (mat.kind == MaterialModel::Kind::water) {
    double pr = 0.0;
    if (geostatic) {
      // Hydrostatic pressure of the column above, density from the EOS.
      pr = mat.density0 * g * depth;
      rho = mat.eos.density_for_pressure(pr);
    }
    p.sxx[q] = p.syy[q] = p.szz[q] = -pr;
    p.pressure[q] = pr;
  } else {
    p.eps_vol_pl[q] = mat.mdpc.initial_cap_volumetric_plastic_strain;
    if (geostatic) {
      const double sv = -mat.density0 * g * depth;
      const ConfinedLayerState k0 = confined_layer_state(mat.mdpc, sv);
      p.szz[q] = sv;
      p.sxx[q] = p.syy[q] = k0.horizontal_stress_Pa;
      p.eps_vol_pl[q] = k0.eps_vol_pl;
      p.pressure[q] = -(p.sxx[q] + p.syy[q] + p.szz[q]) / 3.0;
    }
  }
  return rho;
}

// A particle block on a regular lattice, cell-centred in its region: whole
// layers of dx from the region's min corner (BlockLattice).
void add_block_particles(const sc::ParticleBlock& block, std::uint16_t mat_index, Model& model) {
  const double dx = model.settings.spacing;
  const MaterialModel& mat = model.materials[mat_index];
  Particles& p = model.particles;
  long n[3];
  double lo[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = coordinate(block.region().min(), a);
    n[a] = cosim::lattice_cells(lo[a], coordinate(block.region().max(), a), dx);
  }
  const double top = lo[2] + n[2] * dx;
  BlockLattice& lattice = model.block_lattices.emplace_back();
  for (int a = 0; a < 3; ++a) {
    lattice.region_min[a] = lo[a];
    lattice.region_max[a] = coordinate(block.region().max(), a);
    lattice.filled_max[a] = lo[a] + n[a] * dx;
  }
  const double g = -model.settings.gravity[2];
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        const std::size_t q = p.n_real++;
        p.resize(p.n_real);
        p.x[q] = lo[0] + (i + 0.5) * dx;
        p.y[q] = lo[1] + (j + 0.5) * dx;
        p.z[q] = lo[2] + (k + 0.5) * dx;
        p.material[q] = mat_index;
        p.id[q] = static_cast<std::uint32_t>(q);
        const double depth = top - p.z[q];
        const double rho = set_initial_state(p, q, mat, block.geostatic_initial_state(), g, depth);
        p.density[q] = rho;
        p.mass[q] = rho * dx * dx * dx;
      }
}

// A rigid body of the scene, its mass that of the simulated part of a symmetric
// model. Sinkage is measured from the lattice's top under its centre (RigidBody::surface_z).
RigidBody body_from_scene(const sc::RigidBody& b, const Model& model) {
  RigidBody body;
  body.name = b.name();
  body.radius = b.radius_m();
  body.thickness = b.thickness_m();
  body.x = b.initial_bottom_centre_m().x();
  body.y = b.initial_bottom_centre_m().y();
  body.z = body.z0 = b.initial_bottom_centre_m().z();
  body.surface_z = std::numeric_limits<double>::quiet_NaN();
  for (const BlockLattice& l : model.block_lattices)
    if (body.x >= l.region_min[0] && body.x <= l.filled_max[0] && body.y >= l.region_min[1] &&
        body.y <= l.filled_max[1] && !(l.filled_max[2] <= body.surface_z))  // the highest (NaN compares false)
      body.surface_z = l.filled_max[2];
  body.friction = b.friction_coefficient();
  for (const MirrorPlane& plane : model.planes) {
    if (!plane.symmetry) continue;
    const double c = plane.axis == 0 ? body.x : body.y;
    if (plane.axis < 2 && std::abs(c - plane.position) < 1e-9) body.symmetry_factor *= 2.0;
  }
  body.mass_domain = b.mass_kg() / body.symmetry_factor;
  if (b.drive_case() == sc::RigidBody::kPrescribedVelocityZMPerS) {
    body.prescribed_velocity = true;
    body.prescribed_vz = b.prescribed_velocity_z_m_per_s();
    body.vz = body.prescribed_vz;
  } else {
    body.applied_force_z_full = b.applied_force_z_n();
    body.ramp_time = b.load_ramp_time_s();
    body.vz = b.initial_velocity_z_m_per_s();
    body.rest_speed = b.rest_speed_m_per_s();
    body.rest_hold = b.rest_hold_s();
  }
  return body;
}

}  // namespace

Model build_model(const sc::Scene& scene) {
  const sc::SphTerrain& sph = scene.sph();
  Model model;
  model.name = scene.name();
  set_settings_and_kernel(scene, model);
  add_container_planes(sph, model);
  double max_modulus = 0.0;
  for (const auto& block : sph.blocks()) {
    model.materials.push_back(material_from_scene(block.material()));
    max_modulus = std::max(max_modulus, p_wave_modulus_Pa(model.materials.back()));
    add_block_particles(block, static_cast<std::uint16_t>(model.materials.size() - 1), model);
  }
  model.settings.contact_stiffness = max_modulus * model.settings.spacing;
  for (const auto& b : sph.rigid_bodies()) model.bodies.push_back(body_from_scene(b, model));
  return model;
}

}  // namespace snow_sph
