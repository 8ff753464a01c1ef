// The tread block (tyre_fe/tread_block.hpp, thesis 3.4): its mesh against the
// geometry it is given (closed-surface and divergence-theorem identities, not
// the generator's own arithmetic), the push path against the smoothstep speed
// it integrates, and the block on the tyre's explicit step against uniaxial
// compression of a linear elastic bar.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Geometry>

#include "cosim/quad_facet.hpp"
#include "cosim/ramp.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_fe/tread_block.hpp"

namespace {
using namespace tyre_fe;

TreadBlockGeometry grooved(bool slice) {
  TreadBlockGeometry g;
  g.length_x_m = 0.188, g.width_y_m = 0.01, g.base_thickness_m = 0.003, g.groove_depth_m = 0.010;
  g.groove_x_m = {-0.060, -0.020, 0.020, 0.060};
  g.groove_width_m = 0.010, g.element_size_m = 0.002, g.slice_in_y = slice;
  return g;
}

// The block of linear elastic tread rubber (E 4.588 MPa, nu 0, 1178 kg/m^3).
Model3d elastic_block(const Mesh3D& mesh) {
  TyreMaterials materials;
  SolidMaterial& solid = materials.solid[static_cast<int>(Region::tread)];
  solid.kind = SolidMaterial::Kind::elastic;
  solid.elastic = {4.588e6, 0.0, 1178.0};
  return build_model3d(mesh, materials, CrossSection{}, Model3dOptions{});
}

double hex_volume(const Mesh3D& m, int e) {
  double X[8][3];
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 3; ++k) X[a][k] = m.nodes[m.hexes[e][a]][k];
  return hex8_reference(X).volume_m3;  // throws for an inverted hexahedron
}

Eigen::Vector3d area_vector(const Mesh3D& m, const Mesh3D::Facet& f) {
  const auto& x = m.nodes;
  return cosim::quad_area_vector(x[f.nodes[0]], x[f.nodes[1]], x[f.nodes[2]], x[f.nodes[3]]);
}

// The solid is L W (base + depth) less the grooves; a closed surface's outward
// area vectors sum to zero, and the flux of the field (x, 0, 0) through it is
// the volume (divergence theorem): both fail if any facet points inwards or is missing.
TEST(TreadBlockMesh, VolumeAndClosedOutwardSurface) {
  const TreadBlockGeometry g = grooved(false);
  const Mesh3D m = make_tread_block_mesh(g, 0.001);
  const double expected = g.length_x_m * g.width_y_m * (g.base_thickness_m + g.groove_depth_m) -
                          4 * g.groove_width_m * g.width_y_m * g.groove_depth_m;
  double volume = 0.0;
  for (std::size_t e = 0; e < m.hexes.size(); ++e) volume += hex_volume(m, static_cast<int>(e));
  // Tolerance: a sum of ~3000 products of millimetre lengths, round-off ~1e-15 relative each.
  EXPECT_NEAR(volume, expected, 1e-12 * expected);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double flux = 0.0;
  std::map<cosim::FacetTag, double> area;
  for (const auto& f : m.facets) {
    const Eigen::Vector3d a = area_vector(m, f);
    sum += a;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int n : f.nodes) centre += 0.25 * m.nodes[n];
    flux += centre.x() * a.x();  // exact for a planar quad and a linear field
    area[f.tag] += a.norm();
  }
  EXPECT_LT(sum.norm(), 1e-15);
  EXPECT_NEAR(flux, expected, 1e-12 * expected);
  // Each tag's area against the geometry (same round-off tolerance).
  const double W = g.width_y_m, D = g.groove_depth_m, H = D + g.base_thickness_m;
  EXPECT_NEAR(area[cosim::FacetTag::tread_top], (g.length_x_m - 4 * g.groove_width_m) * W, 1e-15);
  EXPECT_NEAR(area[cosim::FacetTag::groove_bottom], 4 * g.groove_width_m * W, 1e-15);
  EXPECT_NEAR(area[cosim::FacetTag::groove_wall], 8 * D * W, 1e-15);
  EXPECT_NEAR(area[cosim::FacetTag::shoulder], 2 * H * W, 1e-15);
  EXPECT_NEAR(area[cosim::FacetTag::rim_contact], g.length_x_m * W, 1e-15);
  // The ribs' faces lie at the given height, the held top at height + H.
  for (const auto& f : m.facets) {
    if (f.tag != cosim::FacetTag::tread_top) continue;
    for (int n : f.nodes) EXPECT_DOUBLE_EQ(m.nodes[n].z(), 0.001);
  }
  for (int n : m.rim_nodes) EXPECT_NEAR(m.nodes[n].z(), 0.001 + H, 1e-15);
}

TEST(TreadBlockMesh, ASliceHasNoFacetsOnItsSymmetryPlanes) {
  const Mesh3D slice = make_tread_block_mesh(grooved(true), 0.0);
  const Mesh3D whole = make_tread_block_mesh(grooved(false), 0.0);
  for (const auto& f : slice.facets) EXPECT_LT(std::fabs(area_vector(slice, f).normalized().y()), 1e-12);
  int y_facets = 0;
  for (const auto& f : whole.facets) y_facets += std::fabs(area_vector(whole, f).normalized().y()) > 0.5;
  EXPECT_EQ(whole.facets.size() - slice.facets.size(), static_cast<std::size_t>(y_facets));
  EXPECT_GT(y_facets, 0);
}

// The path's speed is v times the smoothstep ramp in, v, then the ramp out: its
// difference quotient must match that speed, independently of the integral.
// The road's contact area of a node is its share of the footprint: the ribs'
// faces (at z = face_z) together are the land L W - 4 w W, the whole bottom with
// the groove floors L W. Shares of all outer facets (the tributary area this
// replaced) gave the face's nodes half the lowest row of every groove wall, end
// and side besides: 1.876e-3 m^2, 27 % more than the land.
// Tolerance: a sum of ~1000 quarter areas of 2 mm facets, round-off ~1e-16 m^2 each.
TEST(TreadBlockMesh, TheRoadAreaOfTheFaceIsItsLandNotItsWalls) {
  const TreadBlockGeometry g = grooved(false);
  const Mesh3D mesh = make_tread_block_mesh(g, 0.0);
  const Model3d model = elastic_block(mesh);
  double face = 0.0, all = 0.0;
  for (std::size_t c = 0; c < model.contact_nodes.size(); ++c) {
    all += model.contact_node_area_m2[c];
    if (std::abs(model.mesh.nodes[model.contact_nodes[c]].z()) < 1e-12) face += model.contact_node_area_m2[c];
  }
  const double land = g.length_x_m * g.width_y_m - 4 * g.groove_width_m * g.width_y_m;
  EXPECT_NEAR(face, land, 1e-12);
  EXPECT_NEAR(all, g.length_x_m * g.width_y_m, 1e-12);
}

TEST(TreadBlockPushPath, SpeedIsTheSmoothstepRampAndTheDepthIsMet) {
  const PushPath p{0.009, 0.5, 0.004};
  const double end = p.end_s(), h = 1e-7;
  EXPECT_DOUBLE_EQ(push_displacement_m(p, 0.0), 0.0);
  EXPECT_NEAR(push_displacement_m(p, end), 0.009, 1e-15);
  EXPECT_NEAR(push_displacement_m(p, 1.0), 0.009, 1e-15);
  for (double t = h; t < end - h; t += end / 97) {
    double speed = p.speed_m_per_s;
    if (t < p.ramp_s) speed = cosim::ramp(cosim::RampCurve::smoothstep, t, p.ramp_s, p.speed_m_per_s);
    if (t > end - p.ramp_s) speed = cosim::ramp(cosim::RampCurve::smoothstep, end - t, p.ramp_s, p.speed_m_per_s);
    const double quotient = (push_displacement_m(p, t + h) - push_displacement_m(p, t - h)) / (2 * h);
    // Central difference of a C1 cubic-quartic path: error ~ h^2 v'' ~ 1e-14 m/s; round-off ~1e-18 / 1e-7.
    EXPECT_NEAR(quotient, speed, 1e-8) << "t = " << t;
  }
}

// A block without grooves pushed 0.1 mm onto the tyre's frictionless rigid road,
// top held by the reference node, brought to rest by mass damping: the road's
// force is that of a bar in uniaxial stress, F = E A (compression / height).
// Poisson's ratio 0: the held top restrains the bar's lateral strain (with the
// tread's 0.475 a 2:1 block carries 16 % more than the bar), which has no
// closed form; with nu = 0 there is none to restrain.
TEST(TreadBlockStep, PushedOntoARoadCarriesTheUniaxialForce) {
  TreadBlockGeometry g;
  g.length_x_m = 0.02, g.width_y_m = 0.02, g.base_thickness_m = 0.01, g.element_size_m = 0.0025;
  const Mesh3D mesh = make_tread_block_mesh(g, 0.0);
  const Model3d model = elastic_block(mesh);
  State3d s = make_state3d(model, model.mesh.nodes, 0.01, 1.0);
  place_road(model, s, 0.0, 0.0, 1.0);
  s.damping_per_s = 2000.0;
  const PushPath path{1e-4, 0.02, 0.002};
  const int steps = static_cast<int>((path.end_s() + 0.01) / s.dt_s);
  for (int n = 0; n < steps; ++n) {
    RimDrive d;
    d.prescribe_vz = true;
    d.vertical_speed_m_per_s =
        -(push_displacement_m(path, s.time_s + s.dt_s) - push_displacement_m(path, s.time_s)) / s.dt_s;
    ASSERT_TRUE(step3d(model, s, d));
  }
  // The bar's stretch from the nodes: the held top's height over the face's mean height.
  double face = 0.0, top = 0.0;
  int n_face = 0;
  for (const auto& f : model.mesh.facets)
    if (f.tag == cosim::FacetTag::tread_top)
      for (int n : f.nodes) face += s.z[n], ++n_face;
  for (int n : model.mesh.rim_nodes) top += s.z[n];
  face /= n_face, top /= static_cast<double>(model.mesh.rim_nodes.size());
  const double stretch = (top - face) / g.base_thickness_m, compression = g.base_thickness_m - (top - face);
  // St. Venant-Kirchhoff bar, nu = 0 (materials.hpp): S = E (stretch^2 - 1) / 2, nominal
  // stress P = stretch S on the unchanged cross-section.
  const double expected = -4.588e6 * g.length_x_m * g.width_y_m * stretch * 0.5 * (stretch * stretch - 1.0);
  // Tolerance 0.5 %: the penalty road lets the face's nodes sit unevenly (the mean
  // height stands for the face), and the damped state is within ~1e-4 of rest; a
  // wrong modulus, area, node order or contact would be off by far more.
  EXPECT_NEAR(s.road.force_z_N, expected, 0.005 * expected);
  EXPECT_NEAR(s.rim.tyre_force_z_N, s.road.force_z_N, 1e-6 * expected);  // at rest: the holder carries the road's force
  EXPECT_GT(compression, 0.5e-4);  // most of the push is the bar's, not the penalty's
  EXPECT_LT(s.energy.balance_error(), 1e-3);
}

// A step that goes non-finite is reported where it went wrong: the time and
// step, and the first element with a non-finite energy located by its first
// node on the undeformed mesh (its current nodes are lost), not by a position
// that reads "nan".
TEST(TreadBlockStep, ANonFiniteStepNamesItsElementOnTheUndeformedMesh) {
  TreadBlockGeometry g;
  g.length_x_m = 0.02, g.width_y_m = 0.02, g.base_thickness_m = 0.01, g.element_size_m = 0.005;
  const Mesh3D mesh = make_tread_block_mesh(g, 0.0);
  TyreMaterials materials;
  materials.solid[static_cast<int>(Region::tread)].kind = SolidMaterial::Kind::elastic;
  materials.solid[static_cast<int>(Region::tread)].elastic = {4.588e6, 0.45, 1178.0};
  const Model3d model = build_model3d(mesh, materials, CrossSection{}, Model3dOptions{});
  State3d s = make_state3d(model, model.mesh.nodes, 0.01, 1.0);
  s.z[0] = std::nan("");  // a node lost: its elements' energies go non-finite in the next step
  std::size_t first = 0;  // the first element that has node 0
  while (std::find(model.mesh.hexes[first].begin(), model.mesh.hexes[first].end(), 0) == model.mesh.hexes[first].end())
    ++first;
  RimDrive d;
  ASSERT_FALSE(step3d(model, s, d));
  const std::string what = non_finite_message(model, s);
  EXPECT_EQ(what.rfind("non-finite state at t = ", 0), 0u) << what;
  EXPECT_NE(what.find("element " + std::to_string(first) + " "), std::string::npos) << what;
  EXPECT_NE(what.find("on the undeformed tyre"), std::string::npos) << what;
  EXPECT_EQ(what.find("nan"), std::string::npos) << what;
  EXPECT_EQ(what.find("inf"), std::string::npos) << what;
}

}  // namespace
