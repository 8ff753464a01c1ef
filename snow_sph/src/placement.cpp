#include "snow_sph/placement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <Eigen/Core>

namespace snow_sph {

namespace {

// Twice the signed area of (a, b, p) in plan: > 0 if p is left of a -> b.
double orient(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

}  // namespace

std::vector<std::uint32_t> particles_in_body(const ContactSurface& surface, std::size_t n, const double* x,
                                             const double* y, const double* z, double clearance_m) {
  std::vector<std::uint32_t> inside;
  if (n == 0 || surface.facet_count() == 0) return inside;
  // The particles in plan, binned on a square grid the size of a mean facet.
  double lo_x = x[0], lo_y = y[0];
  for (std::size_t i = 1; i < n; ++i)
    lo_x = std::min(lo_x, x[i]), lo_y = std::min(lo_y, y[i]);
  double edge_sum = 0.0;
  const std::uint32_t* fn = surface.facet_nodes.data();
  for (std::size_t f = 0; f < surface.facet_count(); ++f)
    edge_sum += std::hypot(surface.x[fn[4 * f + 2]] - surface.x[fn[4 * f]],
                           surface.y[fn[4 * f + 2]] - surface.y[fn[4 * f]]);
  const double cell = std::max(edge_sum / surface.facet_count(), 1e-6);
  auto key = [](long ix, long iy) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(ix) << 32) ^ static_cast<std::uint32_t>(iy));
  };
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> bins;
  for (std::size_t i = 0; i < n; ++i)
    bins[key(std::lround(std::floor((x[i] - lo_x) / cell)), std::lround(std::floor((y[i] - lo_y) / cell)))].push_back(
        static_cast<std::uint32_t>(i));

  const double off_x = 1e-7 * std::sqrt(2.0), off_y = 1e-7 * std::sqrt(3.0);
  std::vector<std::uint8_t> crossings(n, 0), near(n, 0);
  const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (std::size_t f = 0; f < surface.facet_count(); ++f) {
    if (!surface.closed_slit.empty() && surface.closed_slit[f]) continue;
    for (const auto& t : tri) {
      double px[3], py[3], pz[3];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = fn[4 * f + t[k]];
        px[k] = surface.x[v], py[k] = surface.y[v], pz[k] = surface.z[v];
      }
      const double area2 = orient(px[0], py[0], px[1], py[1], px[2], py[2]);
      // Edge-on from above (area2 = 0): no crossing, but a particle can be near it.
      const double c = clearance_m;
      const long ix0 = std::lround(std::floor((std::min({px[0], px[1], px[2]}) - c - lo_x) / cell));
      const long ix1 = std::lround(std::floor((std::max({px[0], px[1], px[2]}) + c - lo_x) / cell));
      const long iy0 = std::lround(std::floor((std::min({py[0], py[1], py[2]}) - c - lo_y) / cell));
      const long iy1 = std::lround(std::floor((std::max({py[0], py[1], py[2]}) + c - lo_y) / cell));
      const Eigen::Vector3d a(px[0], py[0], pz[0]), b(px[1], py[1], pz[1]), cc(px[2], py[2], pz[2]);
      for (long ix = ix0; ix <= ix1; ++ix)
        for (long iy = iy0; iy <= iy1; ++iy) {
          const auto it = bins.find(key(ix, iy));
          if (it == bins.end()) continue;
          for (std::uint32_t i : it->second) {
            if (clearance_m > 0.0 && !near[i]) {
              double w[3];
              const Eigen::Vector3d p(x[i], y[i], z[i]);
              near[i] = (closest_on_triangle(p, a, b, cc, w) - p).squaredNorm() < clearance_m * clearance_m;
            }
            if (area2 == 0.0) continue;
            const double qx = x[i] + off_x, qy = y[i] + off_y;
            // Barycentric weights of the ray's foot in the triangle's plan.
            const double w0 = orient(px[1], py[1], px[2], py[2], qx, qy) / area2;
            const double w1 = orient(px[2], py[2], px[0], py[0], qx, qy) / area2;
            const double w2 = 1.0 - w0 - w1;
            if (!(w0 > 0.0 && w1 > 0.0 && w2 > 0.0)) continue;
            if (w0 * pz[0] + w1 * pz[1] + w2 * pz[2] < z[i]) crossings[i] ^= 1u;
          }
        }
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (crossings[i] || near[i]) inside.push_back(static_cast<std::uint32_t>(i));
  return inside;
}

}  // namespace snow_sph
