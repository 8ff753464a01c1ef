#pragma once
// Contact geometry of an SPH particle with a rigid cylinder (the plate of the
// plate-sinkage test): the particle is a sphere of radius rc = dx/2 about its
// centre, and the contact is where that sphere overlaps the cylinder.
#include <cmath>

namespace snow_sph {

// Where a particle (a sphere of radius rc about its centre) meets a rigid
// cylinder (radius R, from zb to zt): the depth and the outward normal of the
// cylinder at the contact, or depth <= 0 without contact. Beside a face the
// normal is the face's; beyond a rim edge (rr > R above or below the
// cylinder) it points from the edge to the centre, so that the plate loads
// the particles under its own area, and those just outside it only through
// their overlap with its edge.
struct CylinderContact {
  double depth = 0.0, nx = 0.0, ny = 0.0, nz = 0.0;
};
inline CylinderContact cylinder_contact(double dx, double dy, double z, double radius, double zb, double zt, double rc) {
  CylinderContact c;
  const double rr = std::sqrt(dx * dx + dy * dy);
  const double below = zb - z, above = z - zt, outside = rr - radius;  // > 0: beyond that face
  if (outside > 0.0 && (below > 0.0 || above > 0.0)) {  // beyond a rim edge
    const double vertical = below > 0.0 ? -below : above;
    const double gap = std::sqrt(outside * outside + vertical * vertical);
    if (gap >= rc) return c;
    c.depth = rc - gap;
    c.nx = outside / gap * dx / rr, c.ny = outside / gap * dy / rr, c.nz = vertical / gap;
    return c;
  }
  if (outside >= rc || below >= rc || above >= rc) return c;
  // Beside a face or inside: the face the centre is nearest to leaving through.
  const double d_bottom = rc - below, d_top = rc - above, d_side = rc - outside;
  c.nz = -1.0, c.depth = d_bottom;
  if (d_top < c.depth) c.nz = 1.0, c.depth = d_top;
  if (d_side < c.depth && rr > 0) c.nx = dx / rr, c.ny = dy / rr, c.nz = 0.0, c.depth = d_side;
  return c;
}

}  // namespace snow_sph
