#pragma once
// Where a particle's projection falls on a tread facet: the point in a
// triangle, and the bilinear weights with which a point force there is
// shared by the quad's four nodes (surface_contact.cpp).
#include <Eigen/Core>

namespace snow_sph {

// Bilinear shape functions of the quad x[4] at the point q of its surface.
void bilinear_weights(const Eigen::Vector3d& q, const Eigen::Vector3d x[4], double w[4]);

// Barycentric coordinates of q (in the plane of abc) in triangle abc; true if inside.
bool inside_triangle(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::Vector3d& c, double w[3]);

}  // namespace snow_sph
