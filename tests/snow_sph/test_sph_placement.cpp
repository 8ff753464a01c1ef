// The terrain placed around a body (snow_sph/placement.hpp): which particles
// are inside it, by the downward crossing-number test, against the exact inside
// of the bodies the surfaces facet: a wheel standing in a water layer and a
// tread block with a groove open to the road.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "snow_sph/placement.hpp"

namespace {

using snow_sph::ContactSurface;

void add_node(ContactSurface& s, double x, double y, double z) {
  s.x.push_back(x), s.y.push_back(y), s.z.push_back(z);
  s.vx.push_back(0), s.vy.push_back(0), s.vz.push_back(0);
}

void add_quad(ContactSurface& s, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  for (std::uint32_t v : {a, b, c, d}) s.facet_nodes.push_back(v);
  s.friction_coefficient.push_back(0.0);
}

// A lattice of particles filling [x0, x1] x [y0, y1] x [z0, z1] at spacing dx,
// centres half a spacing in from the faces (as snow_sph fills a block).
struct Lattice {
  std::vector<double> x, y, z;
  Lattice(double x0, double x1, double y0, double y1, double z0, double z1, double dx) {
    for (double px = x0 + dx / 2; px < x1; px += dx)
      for (double py = y0 + dx / 2; py < y1; py += dx)
        for (double pz = z0 + dx / 2; pz < z1; pz += dx) x.push_back(px), y.push_back(py), z.push_back(pz);
  }
};

std::vector<char> inside_flags(const ContactSurface& s, const Lattice& l, double clearance_m = 0.0) {
  const auto inside = snow_sph::particles_in_body(s, l.x.size(), l.x.data(), l.y.data(), l.z.data(), clearance_m);
  std::vector<char> flag(l.x.size(), 0);
  for (std::size_t k = 1; k < inside.size(); ++k) EXPECT_LT(inside[k - 1], inside[k]) << "indices ascend";
  for (std::uint32_t i : inside) flag[i] = 1;
  return flag;
}

// A wheel of radius R and width W (axis along y) whose lowest point stands on
// the floor of a 2 cm water layer, as the hydroplaning tyre stands on its road
// when the water is placed; its tread faceted into N strips around and 10
// across, and only the facets below the 6 cm band sent, as the coupler sends
// them. A particle is inside if it is inside the faceted polygon: the chord
// lies at most R (1 - cos(pi / N)) = 2.9 um inside the circle, and particles
// nearer the circle than that are not judged.
TEST(Placement, TheParticlesInsideAWheelStandingInTheWaterAreThoseUnderItsTread) {
  const double R = 0.3, W = 0.2, floor_z = -0.02, band_z = 0.06, dx = 0.004;
  const double zc = floor_z + R;
  const int N = 720, M = 10;
  ContactSurface s;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j <= M; ++j) {
      const double a = 2 * M_PI * i / N;
      add_node(s, R * std::sin(a), -W / 2 + W * j / M, zc - R * std::cos(a));
    }
  auto node = [&](int i, int j) { return static_cast<std::uint32_t>((i % N) * (M + 1) + j); };
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < M; ++j) {
      const std::uint32_t q[4] = {node(i, j), node(i, j + 1), node(i + 1, j + 1), node(i + 1, j)};
      bool below = false;
      for (std::uint32_t v : q) below = below || s.z[v] < band_z;
      if (below) add_quad(s, q[0], q[1], q[2], q[3]);
    }
  const Lattice l(-0.25, 0.25, -0.15, 0.15, floor_z, 0.0, dx);
  const std::vector<char> flag = inside_flags(s, l);
  const double sagitta = R * (1 - std::cos(M_PI / N));
  std::size_t unjudged_near_the_circle = 0, inside = 0;
  for (std::size_t k = 0; k < l.x.size(); ++k) {
    const double r = std::hypot(l.x[k], l.z[k] - zc);
    if (std::fabs(l.y[k]) > W / 2 - 1e-9 && std::fabs(l.y[k]) < W / 2 + 1e-9) continue;  // on a side face
    if (r > R - sagitta - 1e-9 && r < R + 1e-9) {  // between the chords and the circle
      ++unjudged_near_the_circle;
      continue;
    }
    const bool expected = r < R && std::fabs(l.y[k]) < W / 2;
    EXPECT_EQ(flag[k] != 0, expected) << "particle at (" << l.x[k] << ", " << l.y[k] << ", " << l.z[k] << ")";
    inside += expected;
  }
  EXPECT_LT(unjudged_near_the_circle, 20u);
  EXPECT_GT(inside, 500u);  // the test has particles on both sides of the tread
}

// A tread block 4 x 4 cm standing on the floor, with a groove 1 cm wide and
// 1 cm deep along x across its middle, open to the road: water in the groove
// is outside the block, rubber above the groove's floor and beside it inside.
// The particles stand every 2 mm on even millimetres, on the facets' corners
// in x and on their edges in y: a downward ray would pass through edges and
// corners but for its offset. Particles on the block's end and side faces
// (|x| or |y| = 2 cm) are not judged.
constexpr double kFloorZ = -0.02, kGrooveFloorZ = -0.01, kHalf = 0.02, kGrooveHalf = 0.005, kDx = 0.002;

ContactSurface grooved_block() {
  const double floor_z = kFloorZ, groove_floor_z = kGrooveFloorZ, half = kHalf, groove_half = kGrooveHalf, dx = kDx;
  ContactSurface s;
  // A strip along x from (y0, z0) to (y1, z1), split every 2 mm.
  auto strip = [&](double y0, double z0, double y1, double z1) {
    for (int i = 0; i < 20; ++i) {
      const double x = -half + i * dx;
      const auto b = static_cast<std::uint32_t>(s.x.size());
      add_node(s, x, y0, z0), add_node(s, x, y1, z1), add_node(s, x + dx, y1, z1), add_node(s, x + dx, y0, z0);
      add_quad(s, b, b + 1, b + 2, b + 3);
    }
  };
  // The bottom on both sides of the groove: strips from the block's side to
  // the groove's wall at 2, 4, ..., 14 mm from the side, then 1 mm.
  const std::vector<double> side = {-0.020, -0.018, -0.016, -0.014, -0.012, -0.010, -0.008, -0.006, -0.005};
  for (std::size_t k = 0; k + 1 < side.size(); ++k) {
    strip(side[k], floor_z, side[k + 1], floor_z);
    strip(-side[k + 1], floor_z, -side[k], floor_z);
  }
  strip(-groove_half, floor_z, -groove_half, groove_floor_z);  // the walls, edge-on from above
  strip(groove_half, groove_floor_z, groove_half, floor_z);
  strip(-groove_half, groove_floor_z, groove_half, groove_floor_z);  // the groove's floor
  return s;
}

TEST(Placement, WaterInAGrooveOpenToTheRoadIsOutsideTheBlock) {
  const double floor_z = kFloorZ, groove_floor_z = kGrooveFloorZ, half = kHalf, groove_half = kGrooveHalf, dx = kDx;
  const ContactSurface s = grooved_block();
  const Lattice l(-0.031, 0.031, -0.031, 0.031, floor_z, 0.0, dx);
  const std::vector<char> flag = inside_flags(s, l);
  std::size_t in_groove = 0, judged_inside = 0;
  for (std::size_t k = 0; k < l.x.size(); ++k) {
    const double ax = std::fabs(l.x[k]), ay = std::fabs(l.y[k]);
    if (std::fabs(ax - half) < 1e-9 || std::fabs(ay - half) < 1e-9) continue;
    const bool over_block = ax < half && ay < half;
    const bool in_the_groove = ay < groove_half && l.z[k] < groove_floor_z;
    const bool expected = over_block && !in_the_groove;
    EXPECT_EQ(flag[k] != 0, expected) << "particle at (" << l.x[k] << ", " << l.y[k] << ", " << l.z[k] << ")";
    in_groove += over_block && in_the_groove;
    judged_inside += expected;
  }
  EXPECT_EQ(in_groove, 19u * 5u * 5u);  // 19 along x, 5 across, 5 up: all kept
  EXPECT_EQ(judged_inside, 19u * 14u * 10u + 19u * 5u * 5u);  // beside the groove, and above its floor
}

// With a clearance of 1.5 mm the particles whose centre is nearer than that to
// the block go too: in the groove, those 1 mm from its walls or its floor; the
// rest of the groove's water (3 across, the lowest 4 up) stays, and no
// particle beyond the block's plan, 2 mm or more from its bottom's edge, goes.
TEST(Placement, TheClearanceTakesTheParticlesThatWouldOverlapTheBlock) {
  const ContactSurface s = grooved_block();
  const Lattice l(-0.031, 0.031, -0.031, 0.031, kFloorZ, 0.0, kDx);
  const std::vector<char> flag = inside_flags(s, l, 0.0015);
  std::size_t kept_in_groove = 0;
  for (std::size_t k = 0; k < l.x.size(); ++k) {
    const double ax = std::fabs(l.x[k]), ay = std::fabs(l.y[k]);
    if (std::fabs(ax - kHalf) < 1e-9 || std::fabs(ay - kHalf) < 1e-9) continue;
    const bool over_block = ax < kHalf && ay < kHalf;
    if (!over_block) {
      EXPECT_FALSE(flag[k]) << "particle at (" << l.x[k] << ", " << l.y[k] << ", " << l.z[k] << ")";
    }
    const bool in_the_groove = ay < kGrooveHalf && l.z[k] < kGrooveFloorZ;
    if (over_block && !in_the_groove) {
      EXPECT_TRUE(flag[k]);
    }
    if (over_block && in_the_groove && !flag[k]) {
      ++kept_in_groove;
      EXPECT_LT(ay, kGrooveHalf - 0.0015);
      EXPECT_LT(l.z[k], kGrooveFloorZ - 0.0015);
    }
  }
  EXPECT_EQ(kept_in_groove, 19u * 3u * 4u);
}

}  // namespace
