// Contact of SPH particles with a rigid cylinder (snow_sph/cylinder_contact.hpp),
// the plate of the plate-sinkage test: the overlap of the particle's sphere
// (radius rc = dx/2) with the cylinder, checked against plain geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "snow_sph/cylinder_contact.hpp"

namespace {

using snow_sph::cylinder_contact;

constexpr double kPi = 3.14159265358979323846;
constexpr double R = 0.115, zb = 0.5, zt = 0.55;  // the plate of the plate-sinkage scene
// Positions of 0.5 m carry rounding of about 1e-16 m; an overlap of a few mm and a
// unit normal computed from them are good to about 1e-13. 1e-12 (m, or for the
// normal's components) is far below any overlap checked here (1e-3 m).
constexpr double kRounding = 1e-12;

TEST(CylinderContact, FacesGiveThePlaneOverlap) {
  const double rc = 0.005;
  auto c = cylinder_contact(0.03, 0.04, zb - 0.002, R, zb, zt, rc);  // under the bottom face
  EXPECT_NEAR(c.depth, 0.003, kRounding);
  EXPECT_EQ(c.nz, -1.0);
  c = cylinder_contact(0.0, 0.0, zt + 0.004, R, zb, zt, rc);  // on the top face
  EXPECT_NEAR(c.depth, 0.001, kRounding);
  EXPECT_EQ(c.nz, 1.0);
  c = cylinder_contact(0.0, R + 0.001, 0.52, R, zb, zt, rc);  // beside the side face
  EXPECT_NEAR(c.depth, 0.004, kRounding);
  EXPECT_NEAR(c.ny, 1.0, kRounding);
  EXPECT_LE(cylinder_contact(0.0, 0.0, zb - rc, R, zb, zt, rc).depth, 0.0);  // just touching
}

// Beyond the rim edge the overlap is rc minus the distance to the edge, along the
// line from the edge to the centre; the depth is continuous across the edge.
TEST(CylinderContact, BeyondTheRimEdgeTheOverlapIsWithTheEdge) {
  const double rc = 0.005, out = 0.003, below = 0.002;
  const double angle = 0.7;
  const double r = R + out;
  const auto c = cylinder_contact(r * std::cos(angle), r * std::sin(angle), zb - below, R, zb, zt, rc);
  const double gap = std::hypot(out, below);
  EXPECT_NEAR(c.depth, rc - gap, kRounding);
  EXPECT_NEAR(std::hypot(std::hypot(c.nx, c.ny), c.nz), 1.0, kRounding);
  EXPECT_NEAR(c.nz, -below / gap, kRounding);
  EXPECT_NEAR(c.nx, out / gap * std::cos(angle), kRounding);
  // Farther than rc from the edge: no contact, although under the old rule
  // (centre within R + rc and below the face by less than rc) it was pushed down.
  EXPECT_LE(cylinder_contact(R + 0.004, 0.0, zb - 0.004, R, zb, zt, rc).depth, 0.0);
  // Continuity at the edge.
  const double inside = cylinder_contact(R - 1e-9, 0.0, zb - below, R, zb, zt, rc).depth;
  const double beyond = cylinder_contact(R + 1e-9, 0.0, zb - below, R, zb, zt, rc).depth;
  EXPECT_NEAR(inside, beyond, 1e-8);
}

// A layer of particles pressed evenly into the bottom face by delta: the plate's
// vertical penalty force, k sum(depth |nz|), is k delta times the number of particles
// under the plate's own area, pi R^2 / dx^2. On a 2.5 mm grid (R = 46 dx) the count
// of grid points in the circle differs from its area by about (perimeter / dx)^(2/3)
// points (Gauss's circle problem), 0.7 % here; 1.2 % allows that and still fails
// the former rule, which pushed every centre within R + rc down: 1.9 % more on
// this grid ((1 + rc / R)^2 = 1.022 in the limit).
TEST(CylinderContact, ThePlateLoadsItsOwnArea) {
  const double dx = 0.0025, rc = 0.5 * dx, delta = 1e-5;
  double sum = 0.0;
  const int n = static_cast<int>(0.2 / dx);
  for (int i = -n; i < n; ++i)
    for (int j = -n; j < n; ++j) {
      const auto c = cylinder_contact((i + 0.5) * dx, (j + 0.5) * dx, zb - rc + delta, R, zb, zt, rc);
      if (c.depth > 0.0) sum += c.depth * std::fabs(c.nz);
    }
  const double particles_under_plate = kPi * R * R / (dx * dx);
  EXPECT_NEAR(sum / delta / particles_under_plate, 1.0, 0.012);
}

}  // namespace
