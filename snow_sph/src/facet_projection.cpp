// Projections of a particle onto a tread facet (facet_projection.hpp) and the
// closest point on a triangle (surface_contact.hpp).
#include "snow_sph/facet_projection.hpp"

#include <algorithm>

#include <Eigen/Geometry>

#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

using V3 = Eigen::Vector3d;

// Bilinear shape functions of the quad at the point q of its surface (inverse
// isoparametric map by Gauss-Newton from the centre; exact for a parallelogram
// after one iteration): the weights with which a point force at q is shared by
// the four nodes, consistent with the tyre's bilinear facet.
void bilinear_weights(const V3& q, const V3 x[4], double w[4]) {
  static const double xi_a[4] = {-1, 1, 1, -1}, eta_a[4] = {-1, -1, 1, 1};
  double xi = 0.0, eta = 0.0;
  for (int it = 0; it < 4; ++it) {
    V3 r = -q, dxi = V3::Zero(), deta = V3::Zero();
    for (int a = 0; a < 4; ++a) {
      r += 0.25 * (1 + xi_a[a] * xi) * (1 + eta_a[a] * eta) * x[a];
      dxi += 0.25 * xi_a[a] * (1 + eta_a[a] * eta) * x[a];
      deta += 0.25 * eta_a[a] * (1 + xi_a[a] * xi) * x[a];
    }
    const double a11 = dxi.dot(dxi), a12 = dxi.dot(deta), a22 = deta.dot(deta);
    const double b1 = -dxi.dot(r), b2 = -deta.dot(r), det = a11 * a22 - a12 * a12;
    if (!(det > 0)) break;
    xi += (a22 * b1 - a12 * b2) / det, eta += (a11 * b2 - a12 * b1) / det;
  }
  xi = std::clamp(xi, -1.0, 1.0), eta = std::clamp(eta, -1.0, 1.0);
  for (int a = 0; a < 4; ++a) w[a] = 0.25 * (1 + xi_a[a] * xi) * (1 + eta_a[a] * eta);
}

// Barycentric coordinates of q (in the plane of abc) in triangle abc; true if inside.
bool inside_triangle(const V3& q, const V3& a, const V3& b, const V3& c, double w[3]) {
  const V3 v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return false;
  const double v = (d11 * d20 - d01 * d21) / den, t = (d00 * d21 - d01 * d20) / den;
  w[0] = 1.0 - v - t, w[1] = v, w[2] = t;
  return w[0] >= 0 && v >= 0 && t >= 0;
}

// Closest point to p on triangle abc and its barycentric weights (Ericson,
// Real-Time Collision Detection, 2005, 5.1.5: Voronoi regions of the vertices,
// edges and face).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, double w[3]) {
  using V3 = Eigen::Vector3d;
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return w[0] = 1, w[1] = 0, w[2] = 0, a;
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return w[0] = 0, w[1] = 1, w[2] = 0, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return w[0] = 1 - v, w[1] = v, w[2] = 0, V3(a + v * ab);
  }
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return w[0] = 0, w[1] = 0, w[2] = 1, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return w[0] = 1 - t, w[1] = 0, w[2] = t, V3(a + t * ac);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return w[0] = 0, w[1] = 1 - t, w[2] = t, V3(b + t * (c - b));
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, t = vc * denom;
  return w[0] = 1 - v - t, w[1] = v, w[2] = t, V3(a + ab * v + ac * t);
}

}  // namespace snow_sph
