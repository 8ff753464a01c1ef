#include "snow_sph/scene.hpp"

#include <cmath>
#include <limits>
#include <sstream>

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

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
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

void validate_sph_scene(const cosim::LoadedScene& loaded, cosim::ValidationReport& r) {
  const sc::Scene& scene = loaded.message;
  const auto root = loaded.locator();
  if (scene.name().empty()) r.fail(root.where("name"), "a scene needs a name");
  const auto time = root.child("time");
  // A coupled terrain runs until the tyre ends the run (the tyre's stages set the time).
  if (scene.has_sph() && !cosim::has_fe_body(scene) && !(scene.time().end_time_s() > 0))
    r.fail(time.where("end_time_s"), "must be > 0 (got " + num(scene.time().end_time_s()) + ")");
  if (!(scene.time().cfl() > 0 && scene.time().cfl() <= 1.0))
    r.fail(time.where("cfl"), "must be in (0, 1] (got " + num(scene.time().cfl()) + ")");
  if (scene.time().fixed_dt_s() < 0) r.fail(time.where("fixed_dt_s"), "must be >= 0");
  if (scene.sph().cfl() < 0 || scene.sph().cfl() > 1.0)
    r.fail(root.child("sph").where("cfl"), "must be in (0, 1] (got " + num(scene.sph().cfl()) + ")");
  if (scene.output().vtk_interval_s() < 0)
    r.fail(root.child("output").where("vtk_interval_s"), "must be >= 0");
  if (!scene.has_sph()) return;

  const sc::SphTerrain& sph = scene.sph();
  const auto loc = root.child("sph");
  const double dx = sph.particle_spacing_m();
  if (sph.kernel() == sc::KERNEL_UNSET)
    r.fail(loc.where("kernel"), "choose CUBIC, QUADRATIC or QUINTIC");
  if (!(dx > 0)) r.fail(loc.where("particle_spacing_m"), "must be > 0 (got " + num(dx) + ")");
  if (!(sph.smoothing_length_ratio() >= 0.8 && sph.smoothing_length_ratio() <= 3.0))
    r.fail(loc.where("smoothing_length_ratio"),
           "h / spacing must be in [0.8, 3] (got " + num(sph.smoothing_length_ratio()) + ")");
  const auto& box = sph.container();
  const auto box_loc = loc.child("container");
  for (int a = 0; a < 3; ++a) {
    if (!(coordinate(box.max(), a) > coordinate(box.min(), a)))
      r.fail(box_loc.where("max"), std::string("container max must exceed min along ") + "xyz"[a]);
  }
  const double h = sph.smoothing_length_ratio() * dx;
  const double support = (sph.kernel() == sc::QUINTIC ? 3.0 : 2.0) * h;
  const double range = 1.1 * support;
  for (int i = 0; i < sph.symmetry_planes_size(); ++i) {
    if (sph.symmetry_planes(i) == sc::Z_MAX || sph.symmetry_planes(i) == sc::FACE_UNSET)
      r.fail(loc.where("symmetry_planes", i), "the open top (Z_MAX) cannot be a symmetry plane");
  }
  for (int a = 0; a < 3; ++a) {
    const double width = coordinate(box.max(), a) - coordinate(box.min(), a);
    if (dx > 0 && width < range)
      r.fail(box_loc.where("max"), std::string("container is narrower along ") + "xyz"[a] + " (" +
                                       num(width) + " m) than the neighbour range " + num(range) + " m");
  }
  if (sph.blocks_size() == 0) r.fail(loc.where("blocks"), "at least one particle block is needed");
  for (int b = 0; b < sph.blocks_size(); ++b) {
    const auto& block = sph.blocks(b);
    const auto bl = loc.child("blocks", b);
    const auto rl = bl.child("region");
    for (int a = 0; a < 3; ++a) {
      const double lo = coordinate(block.region().min(), a), hi = coordinate(block.region().max(), a);
      if (!(hi - lo >= dx))
        r.fail(rl.where("max"), std::string("block must be at least one spacing thick along ") + "xyz"[a]);
      if (lo < coordinate(box.min(), a) - 1e-12 || hi > coordinate(box.max(), a) + 1e-12)
        r.fail(rl.where(lo < coordinate(box.min(), a) ? "min" : "max"),
               std::string("block does not fit in the container along ") + "xyz"[a] + " (container " +
                   num(coordinate(box.min(), a)) + " .. " + num(coordinate(box.max(), a)) + " m)");
    }
    const auto ml = loaded.locator_at(sc::Material::descriptor(),
                                      "sph.blocks[" + std::to_string(b) + "].material");
    const auto& mat = block.material();
    if (mat.has_snow()) {
      const auto& s = mat.snow();
      const auto sl = ml.child("snow");
      if (!(s.density_kg_per_m3() > 0)) r.fail(sl.where("density_kg_per_m3"), "must be > 0 (got " + num(s.density_kg_per_m3()) + ")");
      if (!(s.youngs_modulus_pa() > 0)) r.fail(sl.where("youngs_modulus_Pa"), "must be > 0");
      if (!(s.poisson_ratio() >= 0 && s.poisson_ratio() < 0.5))
        r.fail(sl.where("poisson_ratio"), "must be in [0, 0.5) (got " + num(s.poisson_ratio()) + ")");
      if (!(s.cohesion_pa() >= 0)) r.fail(sl.where("cohesion_Pa"), "must be >= 0");
      if (!(s.friction_angle_deg() >= 0 && s.friction_angle_deg() < 90))
        r.fail(sl.where("friction_angle_deg"), "must be in [0, 90) degrees");
      if (!(s.cap_eccentricity() > 0)) r.fail(sl.where("cap_eccentricity"), "must be > 0");
      if (!(s.transition_surface_alpha() >= 0 && s.transition_surface_alpha() < 1))
        r.fail(sl.where("transition_surface_alpha"), "must be in [0, 1)");
      if (s.flow_stress_ratio_k() != 1.0)
        r.fail(sl.where("flow_stress_ratio_K"), "only K = 1 is supported (as in Abaqus/Explicit)");
      if (s.initial_cap_volumetric_plastic_strain() < 0)
        r.fail(sl.where("initial_cap_volumetric_plastic_strain"), "must be >= 0");
      if (s.cap_hardening_size() < 2) r.fail(sl.where("cap_hardening"), "needs at least two points");
      for (int k = 1; k < s.cap_hardening_size(); ++k) {
        if (!(s.cap_hardening(k).hydrostatic_pressure_pa() > s.cap_hardening(k - 1).hydrostatic_pressure_pa() &&
              s.cap_hardening(k).volumetric_plastic_strain() > s.cap_hardening(k - 1).volumetric_plastic_strain()))
          r.fail(sl.where("cap_hardening", k), "pressure and strain must both increase along the table");
      }
    } else if (mat.has_water()) {
      const auto& w = mat.water();
      const auto wl = ml.child("water");
      if (!(w.density_kg_per_m3() > 0)) r.fail(wl.where("density_kg_per_m3"), "must be > 0 (got " + num(w.density_kg_per_m3()) + ")");
      if (!(w.reference_sound_speed_m_per_s() > 0)) r.fail(wl.where("reference_sound_speed_m_per_s"), "must be > 0");
      if (w.sound_speed_override_m_per_s() < 0) r.fail(wl.where("sound_speed_override_m_per_s"), "must be >= 0");
      if (w.dynamic_viscosity_pa_s() < 0) r.fail(wl.where("dynamic_viscosity_Pa_s"), "must be >= 0");
      if (w.hugoniot_slope_s() < 0) r.fail(wl.where("hugoniot_slope_s"), "must be >= 0");
      if (!(w.tension_limit_pa() >= 0)) r.fail(wl.where("tension_limit_Pa"), "must be >= 0 (0: no limit)");
      if (!(w.valid_density_min_ratio() >= 0 && w.valid_density_min_ratio() < 1))
        r.fail(wl.where("valid_density_min_ratio"), "must be in [0, 1) (0: no bound; got " + num(w.valid_density_min_ratio()) + ")");
      if (!(w.valid_density_max_ratio() == 0 || w.valid_density_max_ratio() > 1))
        r.fail(wl.where("valid_density_max_ratio"), "must be > 1, or 0 for no bound (got " + num(w.valid_density_max_ratio()) + ")");
      if (w.gruneisen_ratio() != 0)
        r.fail(wl.where("gruneisen_ratio"), "only Gamma0 = 0 is supported (internal energy is not tracked)");
    } else {
      r.fail(bl.where("material"), "give snow { ... }, water { ... } or material_file");
    }
  }
  if (sph.quasi_static_damping_per_s() < 0)
    r.fail(loc.where("quasi_static_damping_per_s"), "must be >= 0");
  for (int k = 0; k < sph.rigid_bodies_size(); ++k) {
    const auto& b = sph.rigid_bodies(k);
    const auto l = loc.child("rigid_bodies", k);
    if (b.name().empty()) r.fail(l.where("name"), "a body needs a name");
    if (!(b.radius_m() > 0)) r.fail(l.where("radius_m"), "must be > 0");
    if (!(b.thickness_m() > 0)) r.fail(l.where("thickness_m"), "must be > 0");
    if (!(b.mass_kg() > 0)) r.fail(l.where("mass_kg"), "must be > 0");
    if (b.friction_coefficient() < 0) r.fail(l.where("friction_coefficient"), "must be >= 0");
    if (b.drive_case() == sc::RigidBody::DRIVE_NOT_SET)
      r.fail(l.where("name"), "give applied_force_z_N or prescribed_velocity_z_m_per_s");
    if (b.load_ramp_time_s() < 0) r.fail(l.where("load_ramp_time_s"), "must be >= 0");
    if (b.rest_speed_m_per_s() < 0) r.fail(l.where("rest_speed_m_per_s"), "must be >= 0");
    if (b.rest_hold_s() < 0) r.fail(l.where("rest_hold_s"), "must be >= 0");
    if (b.rest_speed_m_per_s() > 0 && b.drive_case() == sc::RigidBody::kPrescribedVelocityZMPerS)
      r.fail(l.where("rest_speed_m_per_s"), "a body driven at a prescribed speed never comes to rest; "
                                            "the rest criterion needs applied_force_z_N");
    const auto& c = b.initial_bottom_centre_m();
    bool inside = true;
    for (int a = 0; a < 2; ++a) {
      const double lo = coordinate(box.min(), a), hi = coordinate(box.max(), a);
      const double centre = coordinate(c, a);
      if (centre < lo - 1e-12 || centre > hi + 1e-12) inside = false;
    }
    if (!inside)
      r.fail(l.where("initial_bottom_centre_m"), "the body's axis lies outside the container");
  }
  // A fixed time step must be within the stable limit of the stiffest material.
  const double c = max_sound_speed(sph);
  if (scene.time().fixed_dt_s() > 0 && c > 0 && h > 0) {
    const double limit = h / c;
    if (scene.time().fixed_dt_s() > limit)
      r.fail(time.where("fixed_dt_s"), "time step " + num(scene.time().fixed_dt_s()) +
                                           " s is above the stable limit h / c = " + num(limit) +
                                           " s (h = " + num(h) + " m, c = " + num(c) + " m/s)");
  }
}

std::unique_ptr<cosim::LoadedScene> load_sph_scene(const std::string& path, const std::vector<std::string>& sets) {
  auto scene = cosim::load_scene(path, sets);
  cosim::ValidationReport report;
  validate_sph_scene(*scene, report);
  report.throw_if_failed();
  return scene;
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

Model build_model(const sc::Scene& scene) {
  const sc::SphTerrain& sph = scene.sph();
  Model model;
  model.name = scene.name();
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

  // Walls and symmetry planes.
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
    model.planes.push_back(plane);
  }

  // Particle blocks on a regular lattice, cell-centred in their region.
  Particles& p = model.particles;
  double max_modulus = 0.0;
  for (const auto& block : sph.blocks()) {
    model.materials.push_back(material_from_scene(block.material()));
    MaterialModel& mat = model.materials.back();
    const auto mat_index = static_cast<std::uint16_t>(model.materials.size() - 1);
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
    const double g = -st.gravity[2];
    if (mat.kind == MaterialModel::Kind::snow) {
      const double K = mat.mdpc.bulk_modulus_Pa(), G = mat.mdpc.shear_modulus_Pa();
      max_modulus = std::max(max_modulus, K + 4.0 * G / 3.0);
    } else {
      max_modulus = std::max(max_modulus, mat.density0 * mat.eos.c0 * mat.eos.c0);
    }
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
          double rho = mat.density0;
          if (mat.kind == MaterialModel::Kind::water) {
            double pr = 0.0;
            if (block.geostatic_initial_state()) {
              // Hydrostatic pressure of the column above, density from the EOS.
              pr = mat.density0 * g * depth;
              rho = mat.eos.density_for_pressure(pr);
            }
            p.sxx[q] = p.syy[q] = p.szz[q] = -pr;
            p.pressure[q] = pr;
          } else {
            p.eps_vol_pl[q] = mat.mdpc.initial_cap_volumetric_plastic_strain;
            if (block.geostatic_initial_state()) {
              const double sv = -mat.density0 * g * depth;
              const ConfinedLayerState k0 = confined_layer_state(mat.mdpc, sv);
              p.szz[q] = sv;
              p.sxx[q] = p.syy[q] = k0.horizontal_stress_Pa;
              p.eps_vol_pl[q] = k0.eps_vol_pl;
              p.pressure[q] = -(p.sxx[q] + p.syy[q] + p.szz[q]) / 3.0;
            }
          }
          p.density[q] = rho;
          p.mass[q] = rho * dx * dx * dx;
        }
  }
  st.contact_stiffness = max_modulus * dx;

  for (const auto& b : sph.rigid_bodies()) {
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
    model.bodies.push_back(body);
  }
  return model;
}

}  // namespace snow_sph
