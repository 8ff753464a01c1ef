#include "tyre_fe/tread_block.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cosim/error.hpp"
#include "cosim/ramp.hpp"
#include "tyre_fe/scene.hpp"

namespace tyre_fe {
namespace sc = cosim::scene;

double PushPath::end_s() const { return total_m / speed_m_per_s + ramp_s; }

double push_displacement_m(const PushPath& p, double t) {
  const double v = p.speed_m_per_s, T = p.ramp_s, end = p.end_s();
  if (t <= 0.0) return 0.0;
  if (t >= end) return p.total_m;
  // Integral of the smoothstep 3u^2 - 2u^3 from 0 to u, times v T.
  if (T <= 0.0) return v * t;
  auto ramped = [&](double tau) {
    const double u = tau / T;
    return v * T * (u * u * u - 0.5 * u * u * u * u);
  };
  if (t <= T) return ramped(t);
  if (t >= end - T) return p.total_m - ramped(end - t);
  return v * (t - 0.5 * T);
}

void validate_tread_block_scene(const cosim::LoadedScene& loaded, cosim::ValidationReport& r) {
  const sc::Scene& scene = loaded.message;
  if (!scene.has_tread_block()) return;
  const auto& b = scene.tread_block();
  const auto loc = loaded.locator().child("tread_block");
  if (scene.has_tyre()) r.fail(loc.where("length_x_m"), "a scene has a `tyre` or a `tread_block`, not both");
  if (!scene.has_sph() || scene.coupling().terrain().empty() || scene.coupling().terrain() == "rigid_road")
    r.fail(loaded.locator().child("coupling").where("terrain"),
           "a tread block is pushed into an SPH terrain: give an `sph` section and coupling.terrain (a material file)");
  const bool sliding = b.load_n() > 0.0;
  std::vector<const char*> positive{"length_x_m", "width_y_m", "base_thickness_m", "element_size_m"};
  positive.push_back(sliding ? "slide_s" : "push_speed_m_per_s");
  for (const char* f : positive) {
    const double v = b.GetReflection()->GetDouble(b, b.GetDescriptor()->FindFieldByName(f));
    if (!(v > 0) || !std::isfinite(v)) r.fail(loc.where(f), "must be > 0, got " + cosim::number_text(v));
  }
  for (const char* f : {"groove_depth_m", "groove_width_m", "initial_gap_m", "push_depth_m", "push_ramp_time_s",
                        "hold_s", "reference_node_mass_kg", "load_N", "slide_speed_m_per_s", "slide_ramp_time_s",
                        "average_last_s"}) {
    const double v = b.GetReflection()->GetDouble(b, b.GetDescriptor()->FindFieldByName(f));
    if (!(v >= 0) || !std::isfinite(v)) r.fail(loc.where(f), "must be >= 0, got " + cosim::number_text(v));
  }
  for (int i = 0; i < b.groove_x_m_size(); ++i) {
    const double c = b.groove_x_m(i);
    if (!(std::fabs(c) + 0.5 * b.groove_width_m() < 0.5 * b.length_x_m()))
      r.fail(loc.where("groove_x_m"), "groove " + std::to_string(i) + " at x = " + cosim::number_text(c) +
                                          " m does not lie inside the block (length_x_m)");
  }
  if (b.groove_x_m_size() > 0 && !(b.groove_depth_m() > 0 && b.groove_width_m() > 0))
    r.fail(loc.where("groove_depth_m"), "grooves need groove_depth_m > 0 and groove_width_m > 0");
  if (sliding) {
    if (b.slide_ramp_time_s() > b.slide_s())
      r.fail(loc.where("slide_ramp_time_s"), "the slide's speed ramp (" + cosim::number_text(b.slide_ramp_time_s()) +
                                                 " s) is longer than the slide (slide_s " +
                                                 cosim::number_text(b.slide_s()) + " s)");
    if (b.average_last_s() > b.slide_s() - b.slide_ramp_time_s())
      r.fail(loc.where("average_last_s"), "the results' window reaches into the slide's speed ramp");
    if (!(b.road().friction_coefficient() >= 0 && b.road().friction_coefficient() <= 2))
      r.fail(loc.child("road").where("friction_coefficient"), "must be in [0, 2]");
  }
  const double total = b.initial_gap_m() + b.push_depth_m();
  if (!sliding && b.push_speed_m_per_s() > 0 && b.push_ramp_time_s() * b.push_speed_m_per_s() > total)
    r.fail(loc.where("push_ramp_time_s"), "the speed ramps in and out over " +
                                              cosim::number_text(b.push_ramp_time_s()) + " s each, which at " +
                                              cosim::number_text(b.push_speed_m_per_s()) +
                                              " m/s travels more than the gap plus the depth");
  if (b.has_elastic()) {
    const auto e = loc.child("elastic");
    if (!(b.elastic().density_kg_per_m3() > 0)) r.fail(e.where("density_kg_per_m3"), "must be > 0");
    if (!(b.elastic().youngs_modulus_pa() > 0)) r.fail(e.where("youngs_modulus_Pa"), "must be > 0");
    if (!(b.elastic().poisson_ratio() >= 0 && b.elastic().poisson_ratio() < 0.5))
      r.fail(e.where("poisson_ratio"), "must be in [0, 0.5)");
  } else if (b.has_rubber()) {
    const auto e = loc.child("rubber");
    if (!(b.rubber().density_kg_per_m3() > 0)) r.fail(e.where("density_kg_per_m3"), "must be > 0");
    if (!(b.rubber().c10_pa() > 0)) r.fail(e.where("C10_Pa"), "must be > 0");
  } else {
    r.fail(loc.where("elastic"), "the block needs a material: `elastic { ... }` or `rubber { ... }`");
  }
  if (scene.has_sph()) {
    bool x_symmetric = false;
    for (int f : scene.sph().symmetry_planes()) x_symmetric = x_symmetric || f == sc::X_MIN || f == sc::X_MAX;
    if (x_symmetric) r.fail(loc.where("length_x_m"), "the terrain may be cut by symmetry planes in y only");
  }
}

TreadBlockSetup tread_block_setup(const cosim::LoadedScene& loaded) {
  const auto& b = loaded.message.tread_block();
  TreadBlockSetup s;
  auto& g = s.geometry;
  g.length_x_m = b.length_x_m(), g.width_y_m = b.width_y_m();
  g.base_thickness_m = b.base_thickness_m(), g.groove_depth_m = b.groove_depth_m();
  g.groove_x_m.assign(b.groove_x_m().begin(), b.groove_x_m().end());
  g.groove_width_m = b.groove_width_m(), g.element_size_m = b.element_size_m();
  g.slice_in_y = b.slice_in_y();
  SolidMaterial& m = s.materials.solid[static_cast<int>(Region::tread)];
  if (b.has_elastic()) {
    m.kind = SolidMaterial::Kind::elastic;
    m.elastic.youngs_modulus_Pa = b.elastic().youngs_modulus_pa();
    m.elastic.poisson_ratio = b.elastic().poisson_ratio();
    m.elastic.density_kg_per_m3 = b.elastic().density_kg_per_m3();
  } else {
    m.kind = SolidMaterial::Kind::yeoh;
    m.yeoh.C10_Pa = b.rubber().c10_pa(), m.yeoh.C20_Pa = b.rubber().c20_pa(), m.yeoh.C30_Pa = b.rubber().c30_pa();
    m.yeoh.density_kg_per_m3 = b.rubber().density_kg_per_m3();
    const double ratio = rubber_bulk_to_shear_ratio(b.rubber(), b.bulk_to_shear_ratio());
    m.yeoh.bulk_modulus_Pa = ratio * 2.0 * m.yeoh.C10_Pa;
  }
  s.materials.hourglass_coefficient = b.hourglass_coefficient();
  s.initial_gap_m = b.initial_gap_m(), s.push_depth_m = b.push_depth_m(), s.hold_s = b.hold_s();
  s.path = {b.initial_gap_m() + b.push_depth_m(), b.push_speed_m_per_s(), b.push_ramp_time_s()};
  s.reference_node_mass_kg = b.reference_node_mass_kg();
  s.slide = {b.load_n(), b.push_ramp_time_s(), b.hold_s(), b.slide_speed_m_per_s(), b.slide_ramp_time_s(), b.slide_s(),
             b.average_last_s() > 0.0 ? b.average_last_s() : 0.5 * b.slide_s()};
  return s;
}

}  // namespace tyre_fe
