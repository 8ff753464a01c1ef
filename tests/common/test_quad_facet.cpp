// The shared quad-facet geometry (common/include/cosim/quad_facet.hpp) against
// areas worked by hand (shoelace formula), a rotated trapezoid, and the area
// vector of a warped quad integrated over its bilinear surface.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "cosim/quad_facet.hpp"

namespace {

using V3 = Eigen::Vector3d;

// Tolerance for results that are exact but for a few roundings of O(1) numbers.
constexpr double kRounding = 1e-14;

TEST(QuadFacet, UnitSquare) {
  const cosim::QuadFacet f = cosim::quad_facet(V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, 0), V3(0, 1, 0));
  EXPECT_NEAR(f.area, 1.0, kRounding);
  EXPECT_NEAR((f.normal - V3(0, 0, 1)).norm(), 0.0, kRounding);  // counter-clockwise seen from +z
  EXPECT_NEAR((f.centroid - V3(0.5, 0.5, 0)).norm(), 0.0, kRounding);
  // From its diagonals (1, 1, 0) and (-1, 1, 0): half their cross product, (0, 0, 1).
  EXPECT_NEAR((cosim::quad_area_vector_from_diagonals(V3(1, 1, 0), V3(-1, 1, 0)) - V3(0, 0, 1)).norm(), 0.0, kRounding);
}

TEST(QuadFacet, GeneralPlanarQuadMatchesTheShoelaceArea) {
  // (0,0), (4,0), (5,3), (1,2): shoelace 1/2 |0 + 12 + 7 + 0| = 9.5 (worked by hand).
  const V3 p[4] = {V3(0, 0, 2), V3(4, 0, 2), V3(5, 3, 2), V3(1, 2, 2)};
  EXPECT_NEAR(cosim::quad_area_vector(p[0], p[1], p[2], p[3]).z(), 9.5, kRounding * 10);
  // Reversed order: the normal flips, the area stays.
  const cosim::QuadFacet r = cosim::quad_facet(p[3], p[2], p[1], p[0]);
  EXPECT_NEAR(r.area, 9.5, kRounding * 10);
  EXPECT_NEAR(r.normal.z(), -1.0, kRounding);
  EXPECT_NEAR((r.centroid - V3(2.5, 1.25, 2)).norm(), 0.0, kRounding);
}

TEST(QuadFacet, RotatedTrapezoid) {
  // Parallel sides 4 and 2, height 3: area (4 + 2) / 2 * 3 = 9, normal +z before
  // the rotation; the rotation carries the normal and keeps the area.
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, V3(1, 2, 3).normalized()) *
                             Eigen::AngleAxisd(-1.1, V3(0, 1, 0))).toRotationMatrix();
  const V3 shift(10.0, -3.0, 0.5);
  const V3 p0 = R * V3(0, 0, 0) + shift, p1 = R * V3(4, 0, 0) + shift, p2 = R * V3(3, 3, 0) + shift,
           p3 = R * V3(1, 3, 0) + shift;
  const cosim::QuadFacet f = cosim::quad_facet(p0, p1, p2, p3);
  // Coordinates of size 10: rounding of the shifted points is ~1e-15 m, times lengths ~4.
  EXPECT_NEAR(f.area, 9.0, 1e-13);
  EXPECT_NEAR((f.normal - R * V3(0, 0, 1)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((f.centroid - (R * V3(2, 1.5, 0) + shift)).norm(), 0.0, 1e-13);
}

TEST(QuadFacet, WarpedQuadAreaVectorIsTheIntegralOfNdAOverTheBilinearSurface) {
  // x(xi, eta) bilinear; n dA = x_xi x x_eta dxi deta is quadratic in (xi, eta),
  // so 2 x 2 Gauss points integrate it exactly.
  const V3 p[4] = {V3(0, 0, 0), V3(1.2, 0.1, 0.3), V3(1.0, 1.1, -0.4), V3(-0.1, 0.9, 0.5)};
  const double xi_a[4] = {-1, 1, 1, -1}, eta_a[4] = {-1, -1, 1, 1};
  const double g = 1.0 / std::sqrt(3.0);
  V3 integral = V3::Zero();
  for (double xi : {-g, g})
    for (double eta : {-g, g}) {
      V3 dxi = V3::Zero(), deta = V3::Zero();
      for (int a = 0; a < 4; ++a) {
        dxi += 0.25 * xi_a[a] * (1 + eta_a[a] * eta) * p[a];
        deta += 0.25 * eta_a[a] * (1 + xi_a[a] * xi) * p[a];
      }
      integral += dxi.cross(deta);  // Gauss weights 1
    }
  EXPECT_NEAR((cosim::quad_area_vector(p[0], p[1], p[2], p[3]) - integral).norm(), 0.0, kRounding * 10);
  // By hand for the simpler warp (0,0,0) (1,0,0) (1,1,h) (0,1,0): the projections on the
  // coordinate planes (shoelace) are -h/2 (yz), -h/2 (zx) and 1 (xy).
  const double h = 0.3;
  const V3 a = cosim::quad_area_vector(V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, h), V3(0, 1, 0));
  EXPECT_NEAR((a - V3(-h / 2, -h / 2, 1.0)).norm(), 0.0, kRounding);
}

TEST(QuadFacet, DegenerateFacetHasNoNormal) {
  const cosim::QuadFacet f = cosim::quad_facet(V3(1, 1, 1), V3(1, 1, 1), V3(1, 1, 1), V3(1, 1, 1));
  EXPECT_EQ(f.area, 0.0);
  EXPECT_EQ(f.normal, V3::Zero());
  EXPECT_EQ(cosim::unit_normal(V3::Zero()), V3::Zero());
}

}  // namespace
