#pragma once
// A terrain placed around a body that is already there (thesis 4.2: the tyre
// loaded on the road, then the water layer placed on the road around it): the
// particles the body occupies are not part of the terrain.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "snow_sph/surface_contact.hpp"

namespace snow_sph {

// The particles (ascending indices) in the body whose surface this is: those
// inside it, and those outside whose centre is nearer than clearance_m to it.
// Inside is the crossing-number test along a vertical ray downwards from each
// particle's centre: an odd number of crossings of the surface (O'Rourke,
// Computational Geometry in C, 2nd ed., 1998, sec. 7.4). It needs the body's
// whole underside below each particle in the surface, which the coupled surface
// is (every facet below the contact band; the terrain lies below the band). So
// a particle in the tyre's rubber or its cavity is inside, and one in a groove
// open to the road, or beside or ahead of the tyre, is not. Each quad counts
// as its two triangles (0, 1, 2) and (0, 2, 3); faces seen edge-on from above
// (groove and sipe walls) have no inside. The ray starts a tenth of a
// micrometre off the particle (irrational in x and y), so that it passes through
// no facet edge or corner of the surface. With clearance_m the particle's
// radius, what is left is a terrain filled as against a wall: no particle
// overlaps the body (a particle overlapping it would meet the surface's
// penalty at once; 107 kN on the hydroplaning tyre at 10 mm, docs/water.md).
// Faces of closed slits (ContactSurface::closed_slit) lie inside the rubber and count for neither.
std::vector<std::uint32_t> particles_in_body(const ContactSurface& surface, std::size_t n, const double* x,
                                             const double* y, const double* z, double clearance_m);

}  // namespace snow_sph
