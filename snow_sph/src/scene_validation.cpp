// Validation of a scene's SPH terrain (scene.hpp): every field's range and the
// cross-field rules, each problem reported with its file:line:field.
#include <cmath>
#include <sstream>

#include "snow_sph/scene.hpp"

namespace snow_sph {
namespace sc = cosim::scene;
namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

double coordinate(const sc::Vec3& v, int axis) { return axis == 0 ? v.x() : axis == 1 ? v.y() : v.z(); }

// The scene's name, its time control and output: checked for every scene, with
// or without a terrain.
void validate_time_and_output(const sc::Scene& scene, const cosim::FieldLocator& root, cosim::ValidationReport& r) {
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
}

// The snow's contact with a kind of the container's faces: a Coulomb
// coefficient with COULOMB only, finite and > 0.
void validate_wall_contact(const sc::WallContact& c, const cosim::FieldLocator& l, cosim::ValidationReport& r) {
  const double mu = c.friction_coefficient();
  if (c.kind() == sc::WallContact::COULOMB) {
    if (!(mu > 0 && std::isfinite(mu)))
      r.fail(l.where("friction_coefficient"),
             "COULOMB needs a finite coefficient > 0 (got " + num(mu) + "); FRICTIONLESS is the free-slip box");
  } else if (mu != 0) {
    r.fail(l.where("friction_coefficient"), "only kind COULOMB takes a friction coefficient (got " + num(mu) +
                                                " with kind " + sc::WallContact::Kind_Name(c.kind()) + ")");
  }
}

// The smoothing length h of the scene's kernel [m].
double smoothing_length_m(const sc::SphTerrain& sph) { return sph.smoothing_length_ratio() * sph.particle_spacing_m(); }

// The lattice (kernel, spacing, h) and the container: a box no narrower than
// the neighbour range, with symmetry planes on its closed faces only.
void validate_lattice_and_container(const sc::SphTerrain& sph, const cosim::FieldLocator& loc,
                                    cosim::ValidationReport& r) {
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
  validate_wall_contact(box.floor(), box_loc.child("floor"), r);
  validate_wall_contact(box.side_walls(), box_loc.child("side_walls"), r);
  const double h = smoothing_length_m(sph);
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
}

// A block's region: at least one spacing thick and inside the container.
void validate_block_region(const sc::ParticleBlock& block, const sc::Container& box, double dx,
                           const cosim::FieldLocator& rl, cosim::ValidationReport& r) {
  for (int a = 0; a < 3; ++a) {
    const double lo = coordinate(block.region().min(), a), hi = coordinate(block.region().max(), a);
    if (!(hi - lo >= dx))
      r.fail(rl.where("max"), std::string("block must be at least one spacing thick along ") + "xyz"[a]);
    if (lo < coordinate(box.min(), a) - 1e-12 || hi > coordinate(box.max(), a) + 1e-12)
      r.fail(rl.where(lo < coordinate(box.min(), a) ? "min" : "max"),
             std::string("block does not fit in the container along ") + "xyz"[a] + " (container " +
                 num(coordinate(box.min(), a)) + " .. " + num(coordinate(box.max(), a)) + " m)");
  }
}

// The snow's modified Drucker-Prager cap parameters (mdpc.hpp), in the ranges
// the return mapping supports.
void validate_snow(const sc::SnowMaterial& s, const cosim::FieldLocator& sl, cosim::ValidationReport& r) {
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
}

// The water's equation of state (water_eos.hpp) and viscosity.
void validate_water(const sc::WaterMaterial& w, const cosim::FieldLocator& wl, cosim::ValidationReport& r) {
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
}

// The particle blocks: each one's region and material. A material read from a
// material_file is located in that file (locator_at).
void validate_blocks(const cosim::LoadedScene& loaded, const cosim::FieldLocator& loc, cosim::ValidationReport& r) {
  const sc::SphTerrain& sph = loaded.message.sph();
  if (sph.blocks_size() == 0) r.fail(loc.where("blocks"), "at least one particle block is needed");
  for (int b = 0; b < sph.blocks_size(); ++b) {
    const auto& block = sph.blocks(b);
    const auto bl = loc.child("blocks", b);
    validate_block_region(block, sph.container(), sph.particle_spacing_m(), bl.child("region"), r);
    const auto ml = loaded.locator_at(sc::Material::descriptor(),
                                      "sph.blocks[" + std::to_string(b) + "].material");
    const auto& mat = block.material();
    if (mat.has_snow()) {
      validate_snow(mat.snow(), ml.child("snow"), r);
    } else if (mat.has_water()) {
      validate_water(mat.water(), ml.child("water"), r);
    } else {
      r.fail(bl.where("material"), "give snow { ... }, water { ... } or material_file");
    }
  }
}

// A rigid body: its size, mass and drive, a rest criterion only under an
// applied force, and its axis inside the container.
void validate_rigid_body(const sc::RigidBody& b, const sc::Container& box, const cosim::FieldLocator& l,
                         cosim::ValidationReport& r) {
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
  // The body's disc must reach into the container's plan; its axis may lie
  // outside (a disc of large radius whose rim crosses a thin slab is a straight
  // strip footing: configs/scenes/strip_bearing.textproto).
  const auto& c = b.initial_bottom_centre_m();
  double gap2 = 0.0;  // squared distance in plan from the axis to the container
  for (int a = 0; a < 2; ++a) {
    const double lo = coordinate(box.min(), a), hi = coordinate(box.max(), a);
    const double centre = coordinate(c, a);
    const double gap = centre < lo ? lo - centre : (centre > hi ? centre - hi : 0.0);
    gap2 += gap * gap;
  }
  if (!(std::sqrt(gap2) < b.radius_m()))
    r.fail(l.where("initial_bottom_centre_m"), "the body's disc does not reach into the container");
}

// A fixed time step must be within the stable limit of the stiffest material.
void validate_fixed_step(const sc::Scene& scene, const cosim::FieldLocator& time, double h,
                         cosim::ValidationReport& r) {
  const double c = max_sound_speed(scene.sph());
  if (scene.time().fixed_dt_s() > 0 && c > 0 && h > 0) {
    const double limit = h / c;
    if (scene.time().fixed_dt_s() > limit)
      r.fail(time.where("fixed_dt_s"), "time step " + num(scene.time().fixed_dt_s()) +
                                           " s is above the stable limit h / c = " + num(limit) +
                                           " s (h = " + num(h) + " m, c = " + num(c) + " m/s)");
  }
}

}  // namespace

void validate_sph_scene(const cosim::LoadedScene& loaded, cosim::ValidationReport& r) {
  const sc::Scene& scene = loaded.message;
  const auto root = loaded.locator();
  validate_time_and_output(scene, root, r);
  if (!scene.has_sph()) return;
  const sc::SphTerrain& sph = scene.sph();
  const auto loc = root.child("sph");
  validate_lattice_and_container(sph, loc, r);
  validate_blocks(loaded, loc, r);
  if (sph.quasi_static_damping_per_s() < 0)
    r.fail(loc.where("quasi_static_damping_per_s"), "must be >= 0");
  for (int k = 0; k < sph.rigid_bodies_size(); ++k)
    validate_rigid_body(sph.rigid_bodies(k), sph.container(), loc.child("rigid_bodies", k), r);
  validate_fixed_step(scene, root.child("time"), smoothing_length_m(sph), r);
}

std::unique_ptr<cosim::LoadedScene> load_sph_scene(const std::string& path, const std::vector<std::string>& sets) {
  auto scene = cosim::load_scene(path, sets);
  cosim::ValidationReport report;
  validate_sph_scene(*scene, report);
  report.throw_if_failed();
  return scene;
}

}  // namespace snow_sph
