#include "tyre_fe/tread_block.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cosim/error.hpp"
#include "cosim/ramp.hpp"

namespace tyre_fe {
namespace sc = cosim::scene;
namespace {

// The grid lines of [a, b]: the breaks inside it, each interval cut into equal
// pieces no longer than h.
std::vector<double> grid_lines(double a, double b, std::vector<double> breaks, double h) {
  breaks.push_back(a), breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> lines{a};
  for (std::size_t k = 1; k < breaks.size(); ++k) {
    const double lo = breaks[k - 1], hi = breaks[k];
    if (hi - lo < 1e-12) continue;
    const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / h - 1e-9)));
    for (int i = 1; i <= n; ++i) lines.push_back(lo + (hi - lo) * i / n);
  }
  return lines;
}

}  // namespace

Mesh3D make_tread_block_mesh(const TreadBlockGeometry& g, double face_z_m) {
  const double hx = 0.5 * g.length_x_m, hy = 0.5 * g.width_y_m, h = g.element_size_m;
  std::vector<double> edges;
  for (double c : g.groove_x_m) edges.push_back(c - 0.5 * g.groove_width_m), edges.push_back(c + 0.5 * g.groove_width_m);
  const auto X = grid_lines(-hx, hx, edges, h), Y = grid_lines(-hy, hy, {}, h);
  const auto Z = grid_lines(face_z_m, face_z_m + g.groove_depth_m + g.base_thickness_m,
                            {face_z_m + g.groove_depth_m}, h);
  const int nx = static_cast<int>(X.size()) - 1, ny = static_cast<int>(Y.size()) - 1,
            nz = static_cast<int>(Z.size()) - 1;
  int rib_layers = 0;  // cell layers below the groove floor
  while (rib_layers < nz && Z[rib_layers + 1] <= face_z_m + g.groove_depth_m + 1e-12) ++rib_layers;
  auto in_groove = [&](int i) {
    const double xc = 0.5 * (X[i] + X[i + 1]);
    for (double c : g.groove_x_m)
      if (std::fabs(xc - c) < 0.5 * g.groove_width_m) return true;
    return false;
  };
  auto solid = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz && (k >= rib_layers || !in_groove(i));
  };
  Mesh3D m;
  std::vector<int> node_of((nx + 1) * (ny + 1) * (nz + 1), -1);
  auto node = [&](int i, int j, int k) {
    int& id = node_of[(k * (ny + 1) + j) * (nx + 1) + i];
    if (id < 0) {
      id = static_cast<int>(m.nodes.size());
      m.nodes.emplace_back(X[i], Y[j], Z[k]);
      m.node_source.push_back(-1), m.node_angle_rad.push_back(0.0);
      if (k == nz) m.rim_nodes.push_back(id);
    }
    return id;
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!solid(i, j, k)) continue;
        // VTK_HEXAHEDRON order: the face at k counter-clockwise seen from +z, then the face at k + 1.
        const std::array<int, 8> c{node(i, j, k),         node(i + 1, j, k),     node(i + 1, j + 1, k),
                                   node(i, j + 1, k),     node(i, j, k + 1),     node(i + 1, j, k + 1),
                                   node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        const int e = static_cast<int>(m.hexes.size());
        m.hexes.push_back(c);
        m.hex_region.push_back(Region::tread);
        m.hex_source_quad.push_back(-1);
        m.hex_angle_rad.push_back(0.0);
        // Boundary faces, ordered so that the right-hand normal points out of the block.
        auto face = [&](bool boundary, std::array<int, 4> q, SurfaceTag tag) {
          if (boundary) m.facets.push_back({{c[q[0]], c[q[1]], c[q[2]], c[q[3]]}, tag, e});
        };
        face(!solid(i, j, k - 1), {0, 3, 2, 1}, k == 0 ? SurfaceTag::tread_top : SurfaceTag::groove_bottom);
        face(k == nz - 1, {4, 5, 6, 7}, SurfaceTag::rim_contact);
        face(!solid(i - 1, j, k), {0, 4, 7, 3}, i == 0 ? SurfaceTag::shoulder : SurfaceTag::groove_wall);
        face(!solid(i + 1, j, k), {1, 2, 6, 5}, i == nx - 1 ? SurfaceTag::shoulder : SurfaceTag::groove_wall);
        face(!g.slice_in_y && j == 0, {0, 1, 5, 4}, SurfaceTag::other);
        face(!g.slice_in_y && j == ny - 1, {3, 7, 6, 2}, SurfaceTag::other);
      }
  std::sort(m.rim_nodes.begin(), m.rim_nodes.end());
  return m;
}

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
    const double ratio = b.rubber().bulk_to_shear_ratio() > 0 ? b.rubber().bulk_to_shear_ratio() : b.bulk_to_shear_ratio();
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
