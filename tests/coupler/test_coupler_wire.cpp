// Facet geometry from node positions and the conversions between the neutral
// topic structs and the coupler's inputs/outputs (coupler/facet_geometry.hpp, wire.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/error.hpp"
#include "coupler/wire.hpp"
#include "test_paths.hpp"

using coupler::FacetTag;

namespace {

// Two 0.02 m square facets at z = -0.4 side by side in x, ordered so that the
// right-hand normal points down (-z, out of the tyre's bottom), and one wall
// facet in the plane x = 0.04 facing +x.
struct Surface {
  std::vector<double> x{0, 0, 0.02, 0.02, 0.04, 0.04, 0.04, 0.04};
  std::vector<double> y{0, 0.02, 0.02, 0, 0.02, 0, 0, 0.02};
  std::vector<double> z{-0.4, -0.4, -0.4, -0.4, -0.4, -0.4, -0.38, -0.38};
  std::vector<std::uint32_t> facets{0, 1, 2, 3, 3, 2, 4, 5, 5, 4, 7, 6};
  std::vector<FacetTag> tags{FacetTag::tread_top, FacetTag::tread_top, FacetTag::groove_wall};
};

}  // namespace

TEST(CouplerWire, QuadFacetGeometry) {
  const Surface s;
  const auto g = coupler::quad_facet_geometry(s.x, s.y, s.z, s.facets);
  ASSERT_EQ(g.area_m2.size(), 3u);
  for (int f = 0; f < 2; ++f) {
    EXPECT_NEAR(g.area_m2[f], 0.02 * 0.02, 1e-15);  // a square of side 0.02 m
    EXPECT_NEAR(g.normal_z[f], -1.0, 1e-12);
    EXPECT_NEAR(g.centroid_x_m[f], 0.01 + 0.02 * f, 1e-15);
    EXPECT_NEAR(g.centroid_z_m[f], -0.4, 1e-15);
  }
  EXPECT_NEAR(g.area_m2[2], 0.02 * 0.02, 1e-15);
  EXPECT_NEAR(g.normal_x[2], 1.0, 1e-12);
  EXPECT_NEAR(g.centroid_z_m[2], -0.39, 1e-15);
  EXPECT_THROW(coupler::quad_facet_geometry(s.x, s.y, s.z, {0, 1, 2}), cosim::Error);
  EXPECT_THROW(coupler::quad_facet_geometry(s.x, s.y, s.z, {0, 1, 2, 8}), cosim::Error);
  EXPECT_THROW(coupler::quad_facet_geometry(s.x, s.y, s.z, {0, 0, 0, 0}), cosim::Error);
}

TEST(CouplerWire, ContactLoadsBecomeFacetLoadsAndASummary) {
  const Surface s;
  const auto g = coupler::quad_facet_geometry(s.x, s.y, s.z, s.facets);
  cosim::transport::ContactLoads c;
  c.facets = {2, 0};  // the wall and the first bottom facet
  c.normal_force_N = {50.0, 300.0};
  // The pressure parts as the terrain sums them: on the wall (normal +x) an edge
  // contact pushing along (-0.6, 0, 0.8), on the bottom (normal -z) a face contact.
  c.pressure_x_N = {-30.0, 0.0};
  c.pressure_y_N = {0.0, 0.0};
  c.pressure_z_N = {40.0, 300.0};
  c.tangential_x_N = {0.0, 90.0};
  c.tangential_y_N = {0.0, 0.0};
  c.tangential_z_N = {1.0, 0.0};
  c.contact_area_m2 = {4e-4, 4e-4};
  const auto l = coupler::facet_loads_from_contact(c, s.tags, g);
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l.tag[0], FacetTag::groove_wall);
  // As sent, not -N n (which would give the wall's contact (-50, 0, 0)).
  EXPECT_EQ(l.pressure_x_N[0], -30.0);
  EXPECT_EQ(l.pressure_z_N[0], 40.0);
  EXPECT_EQ(l.pressure_z_N[1], 300.0);  // pushes the tyre up
  // The parts add up to the total force on the tyre, and a wrong total shows.
  EXPECT_EQ(coupler::decomposition_residual_N(l, -30.0 + 90.0, 0.0, 40.0 + 1.0 + 300.0), 0.0);
  EXPECT_NEAR(coupler::decomposition_residual_N(l, 60.0, 0.0, 345.0), 4.0, 1e-12);
  EXPECT_EQ(l.friction_x_N[1], 90.0);
  EXPECT_NEAR(l.centroid_x_m[1], 0.01, 1e-15);

  cosim::transport::WheelState ws;
  ws.rim_x_m = 0.01;
  ws.rim_z_m = 0.0;
  const auto d = coupler::decompose_forces(l, coupler::wheel_input(ws, 0.4));
  cosim::transport::SampleHeader h;
  h.run_id = 7, h.step = 12, h.sim_time_s = 0.5;
  const auto sum = coupler::force_summary(d, h);
  EXPECT_EQ(sum.header.step, 12u);
  EXPECT_EQ(sum.traction_force_N, 90.0);
  EXPECT_NEAR(sum.groove_force_N, -30.0, 1e-12);
  EXPECT_EQ(sum.motion_resistance_N, 0.0);
  EXPECT_NEAR(sum.drawbar_pull_N, 90.0 - 30.0 - sum.rolling_resistance_force_N, 1e-12);
  EXPECT_NEAR(sum.contact_area_m2, 8e-4, 1e-15);
  EXPECT_NEAR(sum.sinkage_m, 0.4, 1e-15);
  // RRM = sum Pz (x - x_rim): the wall's 40 N, 0.03 m ahead of the rim (the bottom facet is under it).
  EXPECT_NEAR(sum.rolling_resistance_moment_Nm, 40.0 * (0.04 - 0.01), 1e-12);
  EXPECT_EQ(sum.rolling_resistance_force_N, d.rolling_resistance_moment_Nm / 0.4);  // F5 = RRM / r

  c.facets[0] = 3;  // out of range
  EXPECT_THROW(coupler::facet_loads_from_contact(c, s.tags, g), cosim::Error);
}

// A wheel state with a NaN or an infinity is refused naming its field (the
// coupler would otherwise write NaN forces for the rest of the run).
TEST(CouplerWire, AWheelStateThatIsNotFiniteIsRefusedByField) {
  cosim::transport::WheelState w;
  w.rim_x_m = 1.0, w.spin_rate_radps = 7.0;
  EXPECT_NO_THROW(coupler::check_wheel_state(w, "WheelState of step 3"));
  w.reaction_moment_y_Nm = std::nan("");
  EXPECT_EQ(test_support::error_of([&] { coupler::check_wheel_state(w, "WheelState of step 3"); }),
            "WheelState of step 3: reaction_moment_y_Nm is not a finite number");
  w.reaction_moment_y_Nm = 0.0, w.rim_z_m = -HUGE_VAL;
  EXPECT_EQ(test_support::error_of([&] { coupler::check_wheel_state(w, "WheelState of step 3"); }),
            "WheelState of step 3: rim_z_m is not a finite number");
}
