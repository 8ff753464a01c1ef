#pragma once
// Geometry of a quadrilateral facet p0 p1 p2 p3 (nodes in order round the
// facet, counter-clockwise seen from the side its normal points to): the one
// definition of the area vector, unit normal and centroid used by the tyre's
// mesh and pressure load, the coupler's force decomposition and the SPH
// particle-facet contact.
//
// Area vector a = (p2 - p0) x (p3 - p1) / 2, half the cross product of the
// diagonals: for a planar quad its length is the area exactly (the two
// triangles on either diagonal); for a warped (bilinear) quad it is the area
// vector of the surface, i.e. the integral of n dA over it, which depends only
// on its boundary.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cosim {

inline Eigen::Vector3d quad_area_vector(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                        const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  return 0.5 * (p2 - p0).cross(p3 - p1);
}

// The same from the diagonals d1 = p2 - p0 and d2 = p3 - p1, for callers that
// form them from their own arrays (a separate entry, not a call of the one above,
// so that each caller's compiled rounding stayed what it was).
inline Eigen::Vector3d quad_area_vector_from_diagonals(const Eigen::Vector3d& d1, const Eigen::Vector3d& d2) {
  return 0.5 * d1.cross(d2);
}

// Mean of the four nodes (the centroid of a parallelogram; the bilinear
// surface's point at its centre in general).
inline Eigen::Vector3d quad_centroid(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                     const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  return 0.25 * (p0 + p1 + p2 + p3);
}

// Unit normal from an area vector; zero for a degenerate (zero-area) facet.
inline Eigen::Vector3d unit_normal(const Eigen::Vector3d& area_vector) {
  const double area = area_vector.norm();
  return area > 0.0 ? Eigen::Vector3d(area_vector / area) : Eigen::Vector3d::Zero();
}

struct QuadFacet {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit; zero if area == 0
  double area = 0.0;
};

inline QuadFacet quad_facet(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                            const Eigen::Vector3d& p3) {
  QuadFacet f;
  const Eigen::Vector3d a = quad_area_vector(p0, p1, p2, p3);
  f.centroid = quad_centroid(p0, p1, p2, p3);
  f.area = a.norm();
  f.normal = f.area > 0.0 ? Eigen::Vector3d(a / f.area) : Eigen::Vector3d::Zero();
  return f;
}

}  // namespace cosim
