#include "coupler/scene_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "coupler/friction.hpp"
#include "cosim/error.hpp"
#include "cosim/particle_lattice.hpp"

namespace coupler {

namespace {
std::string num(double v) { return cosim::number_text(v); }
}  // namespace

void validate_coupling_scene(const cosim::LoadedScene& loaded, cosim::ValidationReport& r) {
  const auto& scene = loaded.message;
  if (!scene.has_coupling()) return;
  const auto& c = scene.coupling();
  const auto loc = loaded.locator().child("coupling");
  if (c.terrain().empty())
    r.fail(loc.where("terrain"), "name the terrain: a material file (e.g. \"../materials/snow_soft.textproto\") or \"rigid_road\"");
  if (!cosim::has_fe_body(scene)) r.fail(loc.where("terrain"), "a coupled scene needs a `tyre` or a `tread_block`");
  if (c.terrain() != "rigid_road" && !c.terrain().empty() && !scene.has_sph())
    r.fail(loc.where("terrain"), "terrain '" + c.terrain() + "' needs an `sph` section with the terrain's blocks");
  for (const char* f : {"contact_band_m", "initial_gap_m", "step_timeout_s", "start_timeout_s", "rolling_radius_m",
                        "base_friction_coefficient", "sipe_equivalent_friction_coefficient",
                        "contact_stiffness_scale", "average_last_s"}) {
    const auto* field = c.GetDescriptor()->FindFieldByName(f);
    const double v = c.GetReflection()->GetDouble(c, field);
    if (!(v >= 0) || !std::isfinite(v)) r.fail(loc.where(f), "must be >= 0 (0: the default), got " + num(v));
  }
  if (c.step_timeout_s() > 5.0)
    r.fail(loc.where("step_timeout_s"), "must be at most 5 s (a dead process must end the run within 5 s), got " +
                                            num(c.step_timeout_s()));
  if (c.domain_id() < 0 || c.domain_id() > 232) r.fail(loc.where("domain_id"), "must be in 0..232");
  if (c.active_domain_wake_limit_m() != 0.0 &&
      !(c.active_domain_wake_limit_m() >= c.active_domain_margin_m() && c.active_domain_margin_m() > 0.0))
    r.fail(loc.where("active_domain_wake_limit_m"),
           "must be 0 (no limit) or at least active_domain_margin_m (" + num(c.active_domain_margin_m()) +
               ", which must be > 0), got " + num(c.active_domain_wake_limit_m()));
  for (int i = 0; i < c.tag_friction_size(); ++i) {
    try {
      facet_tag_from_name(c.tag_friction(i).tag());
    } catch (const cosim::Error& e) {
      r.fail(loc.child("tag_friction", i).where("tag"), e.what());
    }
    if (!(c.tag_friction(i).friction_coefficient() >= 0))
      r.fail(loc.child("tag_friction", i).where("friction_coefficient"), "must be >= 0");
  }
  if (c.terrain() == "rigid_road" || !scene.has_sph()) return;
  // The terrain's undisturbed surface is the plane z = 0 (docs/coupling.md).
  double top = -1e30;
  for (const auto& b : scene.sph().blocks()) top = std::max(top, b.region().max().z());
  if (std::fabs(top) > 1e-9)
    r.fail(loaded.locator().child("sph").child("blocks", 0).child("region").child("max").where("z"),
           "the terrain surface of a coupled scene is the plane z = 0: the highest block must end at z = 0 (got " +
               num(top) + ")");
  if (c.rigid_road_under_terrain()) {
    if (!cosim::has_fe_body(scene))
      r.fail(loc.where("rigid_road_under_terrain"),
             "the road under the terrain is the FE body's: the scene needs a `tyre` or a `tread_block`");
    if (!(scene.sph().container().min().z() < 0.0))
      r.fail(loc.where("rigid_road_under_terrain"),
             "the road lies at the terrain's floor (sph.container.min.z), which must be below its surface z = 0 (got " +
                 num(scene.sph().container().min().z()) + ")");
  }
  if (c.place_terrain_around_loaded_tyre() && !(c.rigid_road_under_terrain() && scene.has_tyre()))
    r.fail(loc.where("place_terrain_around_loaded_tyre"),
           "the tyre is loaded on its own road before the terrain is placed around it: the scene needs a `tyre` "
           "and coupling.rigid_road_under_terrain: true");
  if (scene.has_tyre() && scene.tyre().stages().loading_s() <= 0)
    r.fail(loaded.locator().child("tyre").child("stages").where("loading_s"),
           "a coupled run loads the tyre onto the terrain: give loading_s > 0");
}

double terrain_surface_z_m(const cosim::scene::Scene& scene) {
  if (!scene.has_sph() || scene.sph().blocks_size() == 0) return 0.0;
  const double dx = scene.sph().particle_spacing_m();
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& b : scene.sph().blocks())
    top = std::max(top, cosim::lattice_filled_max(b.region().min().z(), b.region().max().z(), dx));
  return top;
}

}  // namespace coupler
