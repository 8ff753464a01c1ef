// The exchange between the tyre and the terrain without any transport
// (cosim/surface_exchange.hpp): the tyre's side selects the surface near the
// terrain (tyre_fe::surface_near_terrain), the terrain's side rebuilds its
// contact surface from it (snow_sph::assemble_contact_surface) and sends back
// sparse loads (snow_sph::sparse_surface_loads), which the tyre's side checks
// (cosim::check_surface_loads). What is checked is the bookkeeping: the terrain
// sees each facet where the tyre's nodes are, and each load comes back to the
// tyre node it was computed for. The DDS ports copy these types field by field
// (test_transport_roundtrip covers the wire).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "cosim/error.hpp"
#include "cosim/surface_exchange.hpp"
#include "snow_sph/surface_contact.hpp"
#include "test_paths.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_fe/terrain_port.hpp"

namespace {

using cosim::FacetTag;

// A strip of three quads along x rising from 5 mm into the terrain (its surface
// is z = 0) to 0.2 m above it, plus an inner-liner quad that is never offered.
// The surface numbers its nodes in facet order, not the mesh's.
tyre_fe::Mesh3D strip() {
  tyre_fe::Mesh3D mesh;
  const double z[4] = {-0.005, 0.02, 0.12, 0.2};
  for (int i = 0; i < 4; ++i) {
    mesh.nodes.push_back({0.1 * i, 0.0, z[i]});
    mesh.nodes.push_back({0.1 * i, 0.1, z[i]});
  }
  mesh.nodes.push_back({0.0, 0.0, 1.0});  // 8..11: the inner liner, far above
  mesh.nodes.push_back({0.1, 0.0, 1.0});
  mesh.nodes.push_back({0.1, 0.1, 1.0});
  mesh.nodes.push_back({0.0, 0.1, 1.0});
  mesh.facets.push_back({{8, 9, 10, 11}, FacetTag::inner_liner, 0});
  mesh.facets.push_back({{0, 2, 3, 1}, FacetTag::tread_top, 0});
  mesh.facets.push_back({{2, 4, 5, 3}, FacetTag::groove_wall, 0});
  mesh.facets.push_back({{4, 6, 7, 5}, FacetTag::sidewall, 0});
  return mesh;
}

tyre_fe::State3d state_of(const tyre_fe::Mesh3D& mesh) {
  tyre_fe::State3d s;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    s.x.push_back(mesh.nodes[i][0]), s.y.push_back(mesh.nodes[i][1]), s.z.push_back(mesh.nodes[i][2]);
    s.vx.push_back(1.0 + i), s.vy.push_back(0.0), s.vz.push_back(-0.1 * i);
  }
  s.time_s = 0.25;
  s.terrain.exchange = 7;
  return s;
}

TEST(SurfaceExchange, TheTerrainSeesTheFacetsNearItWhereTheTyreHasThem) {
  const tyre_fe::Mesh3D mesh = strip();
  const tyre_fe::ContactSurfaceDef surface = tyre_fe::make_contact_surface(mesh);
  ASSERT_EQ(surface.facet_count(), 3u);  // the inner liner is not offered
  ASSERT_EQ(surface.node_count(), 8u);
  const tyre_fe::State3d s = state_of(mesh);

  cosim::SurfaceState sent;
  tyre_fe::surface_near_terrain(surface, s, 0.05, sent);  // facets with a node below 5 cm
  EXPECT_EQ(sent.exchange, 7u);
  EXPECT_EQ(sent.time_s, 0.25);
  ASSERT_EQ(sent.facets.size(), 2u);  // the tread top and the groove wall (an edge at 2 cm), not the sidewall
  EXPECT_EQ(sent.nodes.size(), 6u);
  EXPECT_NO_THROW(cosim::check_surface_state(sent, surface, "sent"));
  try {  // before the coupler has decided friction, the terrain must refuse it
    cosim::check_surface_state(sent, surface, "SurfaceKinematics of step 7", /*friction_required=*/true);
    FAIL() << "a state without friction was accepted by the terrain's check";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("SurfaceKinematics of step 7: friction_coefficient has 0 entries for 2 facets"),
              std::string::npos) << e.what();
  }

  sent.friction_coefficient = {0.45, 0.3};  // the coupler's choice
  snow_sph::ContactSurface terrain_view;
  std::vector<std::int64_t> scratch;
  snow_sph::assemble_contact_surface(surface, sent, terrain_view, scratch);
  ASSERT_EQ(terrain_view.facet_count(), 2u);
  for (std::size_t f = 0; f < 2; ++f) {
    const auto& mesh_facet = mesh.facets[surface.mesh_facets[sent.facets[f]]];
    for (int a = 0; a < 4; ++a) {
      const std::uint32_t c = terrain_view.facet_nodes[4 * f + a];
      const int model_node = mesh_facet.nodes[a];
      EXPECT_EQ(terrain_view.x[c], s.x[model_node]);
      EXPECT_EQ(terrain_view.z[c], s.z[model_node]);
      EXPECT_EQ(terrain_view.vx[c], s.vx[model_node]);
    }
    EXPECT_EQ(terrain_view.friction_coefficient[f], sent.friction_coefficient[f]);
    EXPECT_EQ(terrain_view.facet_id[f], sent.facets[f]);
  }
  EXPECT_EQ(terrain_view.closed_slit, std::vector<char>(2, 0));  // no sipe on the strip
  // A sipe's face (FacetTag::sipe_wall) is a closed slit to the terrain: no particle takes it.
  tyre_fe::ContactSurfaceDef siped = surface;
  siped.facet_tags[sent.facets[1]] = cosim::FacetTag::sipe_wall;
  snow_sph::assemble_contact_surface(siped, sent, terrain_view, scratch);
  EXPECT_EQ(terrain_view.closed_slit, (std::vector<char>{0, 1}));
}

// A splash above the scene's contact band meets the surface it flies at. A
// wall of the tyre's surface faces -x from 5 to 15 cm above the terrain, above
// the 2 cm band. Two water particles (5 mm, radius 2.5 mm) fly at it: one
// across, its centre 0.8 radii below the wall's lower edge (it touches the
// edge only), the other straight up past that edge at 60 m/s, 6 mm per
// window, more than two radii. Sent the band and the particles' reach of the
// last exchange (snow_sph::particle_reach_z), the terrain computes the same
// contact at every exchange as with the whole surface sent; sent the band
// alone, each particle passes the wall untouched.
TEST(SurfaceExchange, ASplashAboveTheBandMeetsTheSurfaceItFliesAt) {
  tyre_fe::Mesh3D mesh;
  mesh.nodes.push_back({0.2, 0.0, 0.05});
  mesh.nodes.push_back({0.2, 0.0, 0.15});
  mesh.nodes.push_back({0.2, 0.1, 0.15});
  mesh.nodes.push_back({0.2, 0.1, 0.05});
  mesh.facets.push_back({{0, 1, 2, 3}, FacetTag::sidewall, 0});  // normal -x
  const tyre_fe::ContactSurfaceDef surface = tyre_fe::make_contact_surface(mesh);
  const tyre_fe::State3d s = state_of(mesh);
  snow_sph::SurfaceContactParameters params;
  params.particle_radius_m = 0.0025;
  params.stiffness_N_per_m = 1e3;  // stable step 2 sqrt(m / k) = 0.7 ms, seven windows
  const double r = params.particle_radius_m, window_s = 1e-4, band_m = 0.02, gravity = -9.81;
  const double mass = 1.25e-4;  // 5 mm of water
  struct Flight {
    double x, y, z, vx, vy, vz, ax = 0, ay = 0, az = 0;
    double reach_z_m = -std::numeric_limits<double>::max();
    int contacts = 0;
  };
  // One exchange: the surface below `band` (and the particle's reach when
  // `follow_reach`), the contact, the particle's reach, a kick and a drift.
  std::vector<std::int64_t> scratch;
  auto exchange = [&](Flight& p, double band, bool follow_reach) {
    cosim::SurfaceState sent;
    tyre_fe::surface_near_terrain(surface, s, follow_reach ? std::max(band, p.reach_z_m) : band, sent);
    sent.friction_coefficient.assign(sent.facets.size(), 0.3);
    snow_sph::ContactSurface view;
    snow_sph::assemble_contact_surface(surface, sent, view, scratch);
    snow_sph::SurfaceContactResult loads;
    p.ax = 0.0, p.ay = 0.0, p.az = gravity;
    snow_sph::surface_contact(view, params, 1, &p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &mass, window_s, &p.ax, &p.ay,
                              &p.az, loads);
    if (loads.total_fx_N != 0.0 || loads.total_fz_N != 0.0) ++p.contacts;
    p.reach_z_m = snow_sph::particle_reach_z(1, &p.z, &p.vz, &p.az, window_s, r);
    p.vx += p.ax * window_s, p.vy += p.ay * window_s, p.vz += p.az * window_s;
    p.x += p.vx * window_s, p.y += p.vy * window_s, p.z += p.vz * window_s;
  };
  const Flight across{0.19, 0.05, 0.05 - 0.8 * r, 10.0, 0.0, 0.0};
  const Flight up{0.2 - 0.6 * r, 0.05, 0.0329, 0.0, 0.0, 60.0};  // 0.1 mm below the reach of z + 2 r at exchange 2
  for (const Flight& start : {across, up}) {
    Flight followed = start, whole = start, band_only = start;
    for (int k = 0; k < 20; ++k) {
      exchange(followed, band_m, true);
      exchange(whole, 10.0, false);
      exchange(band_only, band_m, false);
      // Tolerance: the same contacts summed over different facet lists, round-off only.
      ASSERT_NEAR(followed.ax, whole.ax, 1e-9 * (1.0 + std::abs(whole.ax))) << "exchange " << k;
      ASSERT_NEAR(followed.az, whole.az, 1e-9 * (1.0 + std::abs(whole.az))) << "exchange " << k;
    }
    EXPECT_GT(whole.contacts, 0);  // the particle did meet the wall, above the band
    EXPECT_EQ(band_only.contacts, 0);
  }
}

TEST(SurfaceExchange, EachLoadComesBackToTheNodeItWasComputedFor) {
  const tyre_fe::Mesh3D mesh = strip();
  const tyre_fe::ContactSurfaceDef surface = tyre_fe::make_contact_surface(mesh);
  const tyre_fe::State3d s = state_of(mesh);
  cosim::SurfaceState sent;
  tyre_fe::surface_near_terrain(surface, s, 0.05, sent);
  sent.friction_coefficient.assign(sent.facets.size(), 0.3);
  snow_sph::ContactSurface terrain_view;
  std::vector<std::int64_t> scratch;
  snow_sph::assemble_contact_surface(surface, sent, terrain_view, scratch);

  // The terrain's result: a force on each node equal to its position (so that the
  // tyre can tell where it came from), none on the last node, contact on facet 0 only.
  snow_sph::SurfaceContactResult result;
  const std::size_t n = terrain_view.x.size();
  for (std::size_t j = 0; j < n; ++j) {
    const bool loaded = j + 1 < n;
    result.node_fx.push_back(loaded ? terrain_view.x[j] : 0.0);
    result.node_fy.push_back(loaded ? terrain_view.y[j] : 0.0);
    result.node_fz.push_back(loaded ? terrain_view.z[j] + 10.0 : 0.0);
  }
  result.particles_in_contact = {3, 0};
  result.facet_normal_force_N = {12.0, 0.0};
  result.facet_pressure_x_N = {-3.0, 0.0}, result.facet_pressure_y_N = {0.0, 0.0};
  result.facet_pressure_z_N = {11.0, 0.0};
  result.facet_tangential_x_N = {1.0, 0.0}, result.facet_tangential_y_N = {0.0, 0.0};
  result.facet_tangential_z_N = {0.0, 0.0};
  result.facet_contact_area_m2 = {0.01, 0.0}, result.facet_pressure_Pa = {1200.0, 0.0};

  cosim::SurfaceLoads loads;
  snow_sph::sparse_surface_loads(sent, result, loads);
  EXPECT_EQ(loads.exchange, 7u);
  ASSERT_EQ(loads.nodes.size(), n - 1);  // the unloaded node is left out
  ASSERT_EQ(loads.facets.size(), 1u);
  EXPECT_EQ(loads.facets[0], sent.facets[0]);
  EXPECT_EQ(loads.pressure_x_N[0], -3.0);
  EXPECT_EQ(loads.pressure_z_N[0], 11.0);
  EXPECT_NO_THROW(cosim::check_surface_loads(loads, surface, "loads"));
  for (std::size_t k = 0; k < loads.nodes.size(); ++k) {
    const int model_node = surface.node_ids[loads.nodes[k]];
    EXPECT_EQ(loads.fx_N[k], s.x[model_node]);
    EXPECT_EQ(loads.fy_N[k], s.y[model_node]);
    EXPECT_EQ(loads.fz_N[k], s.z[model_node] + 10.0);
  }
  const cosim::SurfaceLoadTotals t = cosim::totals(loads);
  double fz = 0.0;
  for (double f : loads.fz_N) fz += f;
  EXPECT_EQ(t.force_N[2], fz);
  EXPECT_EQ(t.contact_area_m2, 0.01);
}

TEST(SurfaceExchange, InconsistentSamplesNameTheSampleAndTheField) {
  const tyre_fe::ContactSurfaceDef surface = tyre_fe::make_contact_surface(strip());
  cosim::SurfaceLoads loads;
  loads.nodes = {0, 1};
  loads.fx_N = {1.0};
  loads.fy_N = loads.fz_N = {1.0, 2.0};
  try {
    cosim::check_surface_loads(loads, surface, "ContactLoads of step 3");
    FAIL() << "a short fx_N was accepted";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("ContactLoads of step 3: fx_N has 1 entries for 2 nodes"), std::string::npos) << e.what();
  }
  loads.fx_N = {1.0, 2.0};
  loads.nodes = {0, 8};
  try {
    cosim::check_surface_loads(loads, surface, "ContactLoads of step 3");
    FAIL() << "a node outside the surface was accepted";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("surface node 8 does not exist (8 surface nodes"), std::string::npos) << e.what();
  }

  cosim::SurfaceState state;
  state.exchange = 4;
  state.nodes = {0, 1, 2};  // facet 0 of the surface needs four nodes
  state.x_m = state.y_m = state.z_m = state.vx_mps = state.vy_mps = state.vz_mps = {0.0, 0.0, 0.0};
  state.facets = {0};
  state.friction_coefficient = {0.3};
  snow_sph::ContactSurface terrain_view;
  std::vector<std::int64_t> scratch;
  try {
    snow_sph::assemble_contact_surface(surface, state, terrain_view, scratch);
    FAIL() << "a facet with a node not sent was accepted";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("surface of exchange 4: facet 0 has a node that was not sent"), std::string::npos)
        << e.what();
  }
}

// A NaN or an infinity from a peer, a negative friction coefficient, a zero
// node mass or a facet tag outside the enumeration is refused at the sample,
// naming the entry, instead of poisoning the receiver's state a step later.
TEST(SurfaceExchange, NonFiniteOrImpossibleValuesAreRefusedByEntry) {
  const tyre_fe::ContactSurfaceDef surface = tyre_fe::make_contact_surface(strip());
  auto refused = [](const std::function<void()>& f, const std::string& expected) {
    const std::string message = test_support::error_of(f);
    EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "', got '" << message << "'";
  };
  cosim::SurfaceState state;
  state.nodes = {0, 1};
  state.x_m = state.y_m = state.z_m = state.vx_mps = state.vy_mps = state.vz_mps = {0.0, 0.0};
  state.facets = {0};
  state.friction_coefficient = {0.3};
  EXPECT_NO_THROW(cosim::check_surface_state(state, surface, "k"));
  state.vz_mps[1] = std::nan("");
  refused([&] { cosim::check_surface_state(state, surface, "SurfaceKinematics of step 9"); },
          "SurfaceKinematics of step 9: vz_mps[1] is not a finite number");
  state.vz_mps[1] = 0.0;
  state.friction_coefficient[0] = -0.1;
  refused([&] { cosim::check_surface_state(state, surface, "k"); }, "friction_coefficient[0] is not a coefficient");
  state.friction_coefficient[0] = 0.3;
  state.time_s = INFINITY;
  refused([&] { cosim::check_surface_state(state, surface, "k"); }, "time_s is not a finite number");

  cosim::SurfaceLoads loads;
  loads.nodes = {3};
  loads.fx_N = loads.fy_N = {0.0};
  loads.fz_N = {-INFINITY};
  refused([&] { cosim::check_surface_loads(loads, surface, "ContactLoads of step 2"); },
          "ContactLoads of step 2: a force, area or pressure[0] is not a finite number");
  loads.fz_N = {0.0};
  loads.particle_reach_z_m = std::nan("");
  refused([&] { cosim::check_surface_loads(loads, surface, "ContactLoads of step 3"); },
          "ContactLoads of step 3: particle_reach_z_m is not a finite number");

  cosim::SurfaceTopology topology = surface;
  topology.node_mass_kg.assign(topology.node_count(), 0.1);
  EXPECT_NO_THROW(cosim::check_surface_topology(topology, "SurfaceMesh"));
  topology.node_mass_kg[2] = 0.0;
  refused([&] { cosim::check_surface_topology(topology, "SurfaceMesh"); }, "node_mass_kg[2] is not a positive finite mass");
  topology.node_mass_kg[2] = 0.1;
  topology.facet_tags[1] = static_cast<FacetTag>(200);
  refused([&] { cosim::check_surface_topology(topology, "SurfaceMesh"); }, "facet_tags[1] is not a facet tag");
}

}  // namespace
