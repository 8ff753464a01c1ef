// Tyre geometry: size parsing, the generated cross-section, the Abaqus deck
// import/export and the 3D revolve with tread patterns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "cosim/error.hpp"
#include "tyre_fe/geometry.hpp"
#include "tyre_fe/outputs.hpp"
#include "tyre_fe/terrain_port.hpp"
#include "tyre_fe/vtk_mesh.hpp"

using namespace tyre_fe;

namespace {

std::string source_dir() {
  const char* s = std::getenv("COSIM_SOURCE_DIR");
  return s ? s : ".";
}

std::string scratch_dir() {
  const auto dir = std::filesystem::temp_directory_path() / "cosim_test_tyre_geometry";
  std::filesystem::create_directories(dir);
  return dir.string();
}

TreadPattern four_grooves(TreadVariant v) {
  TreadPattern p;
  p.variant = v;
  p.circumferential_groove_y_m = {-0.06, -0.02, 0.02, 0.06};
  p.circumferential_groove_width_m = 0.010;
  return p;
}

// The default 235/75R15 section at 8 mm with four circumferential grooves.
const CrossSection& default_section() {
  static const CrossSection s =
      make_cross_section(parse_tyre_size("235/75R15"), four_grooves(TreadVariant::smooth), CrossSectionMesh{});
  return s;
}

double quad_area(const CrossSection& s, int q) {
  double a = 0.0;
  for (int k = 0; k < 4; ++k) {
    const auto& p = s.nodes[s.quads[q][k]];
    const auto& r = s.nodes[s.quads[q][(k + 1) % 4]];
    a += p.x() * r.y() - r.x() * p.y();
  }
  return 0.5 * a;
}

// Edges of the 2D mesh used by one quad only.
std::set<std::pair<int, int>> boundary_edges(const CrossSection& s) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& q : s.quads)
    for (int k = 0; k < 4; ++k) count[{std::min(q[k], q[(k + 1) % 4]), std::max(q[k], q[(k + 1) % 4])}]++;
  std::set<std::pair<int, int>> out;
  for (const auto& [e, c] : count)
    if (c == 1) out.insert(e);
  return out;
}

// Volume of a trilinear hex by 2x2x2 Gauss quadrature; also the minimum Jacobian
// determinant at the Gauss points and the corners.
double hex_volume(const Mesh3D& m, int e, double* min_det) {
  static const int xi[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                               {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  double volume = 0.0;
  *min_det = 1e30;
  const double g = 1.0 / std::sqrt(3.0);
  for (int pass = 0; pass < 2; ++pass)
    for (int gp = 0; gp < 8; ++gp) {
      const double a = (pass == 0 ? g : 1.0) * xi[gp][0], b = (pass == 0 ? g : 1.0) * xi[gp][1],
                   c = (pass == 0 ? g : 1.0) * xi[gp][2];
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int n = 0; n < 8; ++n) {
        const Eigen::Vector3d dN(0.125 * xi[n][0] * (1 + b * xi[n][1]) * (1 + c * xi[n][2]),
                                 0.125 * xi[n][1] * (1 + a * xi[n][0]) * (1 + c * xi[n][2]),
                                 0.125 * xi[n][2] * (1 + a * xi[n][0]) * (1 + b * xi[n][1]));
        J += m.nodes[m.hexes[e][n]] * dN.transpose();
      }
      const double det = J.determinant();
      *min_det = std::min(*min_det, det);
      if (pass == 0) volume += det;
    }
  return volume;
}

std::map<SurfaceTag, int> tag_counts(const Mesh3D& m) {
  std::map<SurfaceTag, int> c;
  for (const auto& f : m.facets) c[f.tag]++;
  return c;
}

}  // namespace

TEST(TyreSize, ParsesDesignations) {
  const TyreSize s = parse_tyre_size("235/75R15");
  EXPECT_DOUBLE_EQ(s.section_width_m, 0.235);
  EXPECT_DOUBLE_EQ(s.aspect_ratio, 0.75);
  EXPECT_DOUBLE_EQ(s.rim_diameter_m, 15 * 0.0254);
  for (const char* ok : {"P235/75R15", "235/75 R 15", "p235/75r15", " LT235/75R15 ", "235/75ZR15"}) {
    const TyreSize t = parse_tyre_size(ok);
    EXPECT_DOUBLE_EQ(t.section_width_m, 0.235) << ok;
    EXPECT_DOUBLE_EQ(t.rim_diameter_m, 0.381) << ok;
  }
  EXPECT_DOUBLE_EQ(parse_tyre_size("215/65R16.5").rim_diameter_m, 16.5 * 0.0254);
}

TEST(TyreSize, RejectsMalformedDesignations) {
  for (const char* bad : {"", "235/75", "235-75R15", "235/75D15", "235/75R15 109S", "R15", "235/R15",
                          "235/75R", "2350/75R15", "235/5R15", "235/75R15.", "235/75R1.5.1"}) {
    try {
      parse_tyre_size(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const cosim::Error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(CrossSection, DefaultSizeHasTheRightDimensionsAndRegions) {
  const CrossSection& s = default_section();
  const int nq = static_cast<int>(s.quads.size());
  ASSERT_GT(nq, 100);
  ASSERT_EQ(s.quad_region.size(), s.quads.size());
  ASSERT_EQ(s.quad_layer_tangent.size(), s.quads.size());
  ASSERT_EQ(s.quad_layer_thickness_m.size(), s.quads.size());
  double r_max = 0.0, y_max = 0.0;
  for (const auto& p : s.nodes) {
    r_max = std::max(r_max, p.x());
    y_max = std::max(y_max, std::abs(p.y()));
  }
  EXPECT_NEAR(r_max, 0.3665, 1e-3);
  EXPECT_NEAR(2 * y_max, 0.235, 0.03 * 0.235);
  ASSERT_GE(s.tread_centre_node, 0);
  EXPECT_EQ(s.nodes[s.tread_centre_node].y(), 0.0);
  EXPECT_DOUBLE_EQ(s.nodes[s.tread_centre_node].x(), r_max);
  EXPECT_NEAR(s.tread_half_width_m, 0.4 * 0.235, 1e-12);

  std::vector<int> count(kRegionCount, 0);
  for (int q = 0; q < nq; ++q) {
    count[static_cast<int>(s.quad_region[q])]++;
    EXPECT_GT(quad_area(s, q), 0.0) << q;
    double lmin = 1e9, lmax = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d e1 = s.nodes[s.quads[q][(k + 1) % 4]] - s.nodes[s.quads[q][k]];
      const Eigen::Vector2d e2 = s.nodes[s.quads[q][(k + 2) % 4]] - s.nodes[s.quads[q][(k + 1) % 4]];
      EXPECT_GT(e1.x() * e2.y() - e1.y() * e2.x(), 0.0) << "quad " << q << " not convex";
      lmin = std::min(lmin, e1.norm());
      lmax = std::max(lmax, e1.norm());
    }
    EXPECT_LT(lmax / lmin, 10.0) << "quad " << q;
    EXPECT_GT(s.quad_layer_thickness_m[q], 0.0);
    const Region r = s.quad_region[q];
    if (r == Region::ply || r == Region::belt_1 || r == Region::belt_2) {
      EXPECT_NEAR(s.quad_layer_tangent[q].norm(), 1.0, 1e-12);
    }
  }
  for (int r = 0; r < kRegionCount; ++r) EXPECT_GT(count[r], 0) << region_name(static_cast<Region>(r));
  // Ply quads carry the 1 mm ply gauge.
  for (int q = 0; q < nq; ++q) {
    if (s.quad_region[q] == Region::ply) {
      EXPECT_NEAR(s.quad_layer_thickness_m[q], 0.001, 2e-4);
    }
  }
}

TEST(CrossSection, GroovesAndTreadEdgesLieOnNodeLines) {
  const CrossSection& s = default_section();
  const TreadPattern p = four_grooves(TreadVariant::rib);
  std::vector<double> wanted{-s.tread_half_width_m, s.tread_half_width_m};
  for (double y : p.circumferential_groove_y_m) {
    wanted.push_back(y - 0.5 * p.circumferential_groove_width_m);
    wanted.push_back(y + 0.5 * p.circumferential_groove_width_m);
  }
  std::set<int> outer;
  for (const auto& [a, b] : boundary_edges(s)) {
    outer.insert(a);
    outer.insert(b);
  }
  for (double y : wanted) {
    bool found = false;
    for (int n : outer) found = found || (std::abs(s.nodes[n].y() - y) < 1e-7 && s.nodes[n].x() > 0.35);
    EXPECT_TRUE(found) << "no outer tread node at y = " << y;
  }
  // The groove bottom is a layer boundary: a node lies groove_depth below the
  // tread centre on the centre line.
  const double top = s.nodes[s.tread_centre_node].x();
  bool bottom = false;
  for (const auto& n : s.nodes) bottom = bottom || (n.y() == 0.0 && std::abs(top - n.x() - p.groove_depth_m) < 1e-6);
  EXPECT_TRUE(bottom);
}

TEST(CrossSection, InnerLinerIsAChainFromBeadToBeadAndRimHoldsTheBeads) {
  const CrossSection& s = default_section();
  std::map<int, std::vector<int>> adj;
  for (const auto& e : s.inner_liner_edges) {
    ASSERT_EQ(s.quad_region[e[0]], Region::inner_liner);
    const int a = s.quads[e[0]][e[1]], b = s.quads[e[0]][(e[1] + 1) % 4];
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
  std::vector<int> ends;
  for (const auto& [n, nb] : adj) {
    EXPECT_LE(nb.size(), 2u);
    if (nb.size() == 1) ends.push_back(n);
  }
  ASSERT_EQ(ends.size(), 2u);
  // Walk the chain: it must visit every node.
  std::set<int> seen{ends[0]};
  int prev = -1, cur = ends[0];
  while (true) {
    int next = -1;
    for (int n : adj[cur])
      if (n != prev) next = n;
    if (next < 0 || seen.count(next)) break;
    seen.insert(next);
    prev = cur;
    cur = next;
  }
  EXPECT_EQ(seen.size(), adj.size());
  EXPECT_EQ(cur, ends[1]);
  const std::set<int> rim(s.rim_nodes.begin(), s.rim_nodes.end());
  const double rim_radius = 0.5 * 15 * 0.0254;
  for (int e : ends) {
    EXPECT_TRUE(rim.count(e));
    EXPECT_NEAR(s.nodes[e].x(), rim_radius, 1e-9);
  }
  for (int n : s.rim_nodes) EXPECT_LT(s.nodes[n].x(), rim_radius + 0.02);
}

TEST(CrossSection, OtherSizesMeshAndBadInputIsRejected) {
  for (const char* size : {"205/55R16", "195/65R15", "225/45R17", "265/70R17", "175/70R13"}) {
    const CrossSection s = make_cross_section(parse_tyre_size(size), TreadPattern{}, CrossSectionMesh{});
    for (int q = 0; q < static_cast<int>(s.quads.size()); ++q) ASSERT_GT(quad_area(s, q), 0.0) << size;
  }
  CrossSectionMesh one_layer;
  one_layer.tread_layers = 1;
  EXPECT_THROW(make_cross_section(TyreSize{}, TreadPattern{}, one_layer), cosim::Error);
  TreadPattern off_tread;
  off_tread.circumferential_groove_y_m = {0.093};
  EXPECT_THROW(make_cross_section(TyreSize{}, off_tread, CrossSectionMesh{}), cosim::Error);
}

TEST(Revolve, SmoothCountsAndPositiveVolumes) {
  const CrossSection& s = default_section();
  TreadPattern p = four_grooves(TreadVariant::smooth);
  p.pitch_count = 30;
  p.elements_per_pitch = 4;
  const Mesh3D m = revolve(s, p);
  const size_t n = 30 * 4;
  EXPECT_EQ(m.nodes.size(), n * s.nodes.size());
  EXPECT_EQ(m.hexes.size(), n * s.quads.size());
  EXPECT_EQ(m.facets.size(), n * boundary_edges(s).size());
  EXPECT_EQ(m.rim_nodes.size(), n * s.rim_nodes.size());
  ASSERT_EQ(m.node_source.size(), m.nodes.size());
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const auto& src = s.nodes[m.node_source[i]];
    const double th = m.node_angle_rad[i];
    ASSERT_NEAR(m.nodes[i].x(), src.x() * std::sin(th), 1e-12);
    ASSERT_NEAR(m.nodes[i].z(), src.x() * std::cos(th), 1e-12);
    ASSERT_EQ(m.nodes[i].y(), src.y());
  }
  double total = 0.0;
  for (int e = 0; e < static_cast<int>(m.hexes.size()); ++e) {
    double min_det;
    const double v = hex_volume(m, e, &min_det);
    ASSERT_GT(min_det, 0.0) << "hex " << e;
    total += v;
  }
  // Pappus: rubber volume = 2 pi sum(area * centroid radius), less the chord
  // error of the straight circumferential edges (1 - d^2/6 = 0.9995 at 3 deg).
  double pappus = 0.0;
  for (int q = 0; q < static_cast<int>(s.quads.size()); ++q) {
    double first_moment = 0.0;  // integral of r over the quad
    for (int k = 0; k < 4; ++k) {
      const auto& a = s.nodes[s.quads[q][k]];
      const auto& b = s.nodes[s.quads[q][(k + 1) % 4]];
      first_moment += (a.x() + b.x()) * (a.x() * b.y() - b.x() * a.y()) / 6.0;
    }
    pappus += 2 * M_PI * first_moment;
  }
  EXPECT_NEAR(total / pappus, 1.0, 1e-3);
  EXPECT_GT(tag_counts(m)[SurfaceTag::tread_top], 0);
}

TEST(Revolve, PatternsRemoveTreadAndSipesSplitNodes) {
  const CrossSection& s = default_section();
  std::map<TreadVariant, Mesh3D> mesh;
  for (TreadVariant v : {TreadVariant::smooth, TreadVariant::rib, TreadVariant::block, TreadVariant::block_sipes}) {
    TreadPattern p = four_grooves(v);
    p.pitch_count = 20;
    mesh[v] = revolve(s, p);
  }
  const Mesh3D& smooth = mesh[TreadVariant::smooth];
  const Mesh3D& rib = mesh[TreadVariant::rib];
  const Mesh3D& block = mesh[TreadVariant::block];
  const Mesh3D& sipes = mesh[TreadVariant::block_sipes];
  EXPECT_LT(rib.hexes.size(), smooth.hexes.size());
  EXPECT_LT(block.hexes.size(), rib.hexes.size());
  ASSERT_EQ(sipes.hexes.size(), block.hexes.size());
  for (size_t e = 0; e < block.hexes.size(); ++e)
    for (int a = 0; a < 8; ++a)
      ASSERT_EQ(sipes.nodes[sipes.hexes[e][a]], block.nodes[block.hexes[e][a]]) << "hex " << e;
  EXPECT_GT(sipes.nodes.size(), block.nodes.size());
  EXPECT_EQ(tag_counts(block)[SurfaceTag::sipe_wall], 0);
  EXPECT_GT(tag_counts(sipes)[SurfaceTag::sipe_wall], 0);
  // 7 mm nominal sipes in 5 mm groove layers are meshed 5 mm deep.
  EXPECT_NEAR(sipes.sipe_depth_m, 0.005, 2e-4);
  EXPECT_DOUBLE_EQ(sipes.sipe_width_m, 0.0006);
  for (const auto* m : {&rib, &block}) {
    auto c = tag_counts(*m);
    EXPECT_GT(c[SurfaceTag::groove_wall], 0);
    EXPECT_GT(c[SurfaceTag::groove_bottom], 0);
    EXPECT_GT(c[SurfaceTag::tread_top], 0);
  }

  for (const auto& [variant, m] : mesh) {
    // No unused nodes.
    std::vector<char> used(m.nodes.size(), 0);
    for (const auto& h : m.hexes)
      for (int n : h) used[n] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    // Closed surface: every facet edge is shared by exactly two facets.
    std::map<std::pair<int, int>, int> edges;
    for (const auto& f : m.facets)
      for (int a = 0; a < 4; ++a)
        edges[{std::min(f.nodes[a], f.nodes[(a + 1) % 4]), std::max(f.nodes[a], f.nodes[(a + 1) % 4])}]++;
    int bad = 0;
    for (const auto& [e, c] : edges) bad += c != 2;
    EXPECT_EQ(bad, 0) << "variant " << static_cast<int>(variant);
    // Facet normals point out of their hex.
    for (const auto& f : m.facets) {
      Eigen::Vector3d hc = Eigen::Vector3d::Zero(), fc = Eigen::Vector3d::Zero();
      for (int n : m.hexes[f.hex]) hc += m.nodes[n] / 8;
      for (int n : f.nodes) fc += m.nodes[n] / 4;
      const Eigen::Vector3d normal = (m.nodes[f.nodes[2]] - m.nodes[f.nodes[0]])
                                         .cross(m.nodes[f.nodes[3]] - m.nodes[f.nodes[1]]);
      ASSERT_GT(normal.dot(fc - hc), 0.0);
    }
  }
}

TEST(Abaqus, RoundTripGivesTheSameSection) {
  const CrossSection& s = default_section();
  const std::string path = scratch_dir() + "/round_trip.inp";
  write_abaqus_cross_section(s, path);
  const CrossSection t = import_abaqus_cross_section(path, s.tread_half_width_m);
  ASSERT_EQ(t.nodes.size(), s.nodes.size());
  for (size_t i = 0; i < s.nodes.size(); ++i) ASSERT_EQ(t.nodes[i], s.nodes[i]);
  EXPECT_EQ(t.quads, s.quads);
  EXPECT_EQ(t.quad_region, s.quad_region);
  auto sorted = [](std::vector<int> v) { std::sort(v.begin(), v.end()); return v; };
  EXPECT_EQ(sorted(t.rim_nodes), sorted(s.rim_nodes));
  auto liner = [](std::vector<std::array<int, 2>> v) { std::sort(v.begin(), v.end()); return v; };
  EXPECT_EQ(liner(t.inner_liner_edges), liner(s.inner_liner_edges));
  EXPECT_EQ(t.tread_centre_node, s.tread_centre_node);
  for (size_t q = 0; q < s.quads.size(); ++q) {
    const Region r = s.quad_region[q];
    if (r != Region::ply && r != Region::belt_1 && r != Region::belt_2) continue;
    EXPECT_GT(t.quad_layer_tangent[q].dot(s.quad_layer_tangent[q]), 0.9999) << q;
    EXPECT_NEAR(t.quad_layer_thickness_m[q], s.quad_layer_thickness_m[q], 1e-12) << q;
  }
}

TEST(Abaqus, ExampleDeckImports) {
  const CrossSection s =
      import_abaqus_cross_section(source_dir() + "/tests/data/tyre/example_cross_section.inp", 0.094);
  std::set<Region> regions(s.quad_region.begin(), s.quad_region.end());
  EXPECT_EQ(static_cast<int>(regions.size()), kRegionCount);
  for (int q = 0; q < static_cast<int>(s.quads.size()); ++q) EXPECT_GT(quad_area(s, q), 0.0);
  EXPECT_FALSE(s.rim_nodes.empty());
  EXPECT_FALSE(s.inner_liner_edges.empty());
  EXPECT_GE(s.tread_centre_node, 0);
  const Mesh3D m = revolve(s, TreadPattern{});
  EXPECT_EQ(m.hexes.size(), s.quads.size() * 60 * 4);
}

TEST(Abaqus, ParsesKeywordVariantsAndFallsBack) {
  // A liner quad written clockwise over a continuation line, a tread quad on top
  // of it and two rim-strip quads far below; sets by GENERATE, by name and by the
  // ELSET parameter; no RIM set and no surface, so the fallbacks apply.
  const std::string path = scratch_dir() + "/small.inp";
  std::ofstream(path) << "** hand-written deck\n*heading\nsmall\n*Node, nset=all\n"
                         "1, 0.300, -0.01\n2, 0.300, 0.01\n3, 0.301, 0.01\n4, 0.301, -0.01\n"
                         "5, 0.310, 0.01\n6, 0.310, -0.01\n7, 0.5, 0.5\n"
                         "8, 0.20, -0.06\n9, 0.21, -0.06\n10, 0.21, -0.05\n11, 0.20, -0.05\n"
                         "12, 0.20, 0.05\n13, 0.21, 0.05\n14, 0.21, 0.06\n15, 0.20, 0.06\n"
                         "*element, type=cax4r\n1, 1, 2,\n 3, 4\n"
                         "*Element, TYPE=CGAX4R, ELSET=tread\n2, 4, 6, 5, 3\n"
                         "** the rim strips\n*ELEMENT, TYPE=CAX4\n3, 8, 9, 10, 11\n4, 12, 13, 14, 15\n"
                         "*ELSET, ELSET=Liner, generate\n1, 1, 1\n"
                         "*elset, elset=innerLINER\nLINER\n*ELSET, ELSET=rim_strip, GENERATE\n3, 4\n"
                         "*MATERIAL, NAME=RUBBER\n*DENSITY\n1100.\n";
  const CrossSection s = import_abaqus_cross_section(path, 0.01);
  ASSERT_EQ(s.nodes.size(), 14u);  // node 7 is unused and dropped
  ASSERT_EQ(s.quads.size(), 4u);
  EXPECT_EQ(s.quad_region[0], Region::inner_liner);
  EXPECT_EQ(s.quad_region[1], Region::tread);
  EXPECT_EQ(s.quad_region[2], Region::rim_strip);
  EXPECT_EQ(s.quad_region[3], Region::rim_strip);
  for (int q = 0; q < 4; ++q) EXPECT_GT(quad_area(s, q), 0.0) << q;
  EXPECT_EQ(s.quads[0], (std::array<int, 4>{0, 3, 2, 1}));  // reordered counter-clockwise
  EXPECT_EQ(s.rim_nodes, (std::vector<int>{6, 9, 10, 13}));  // rim strip nodes at the lowest radius
  ASSERT_EQ(s.inner_liner_edges.size(), 1u);                 // the liner face towards the axis
  EXPECT_EQ(s.inner_liner_edges[0], (std::array<int, 2>{0, 3}));
  ASSERT_GE(s.tread_centre_node, 0);
  EXPECT_DOUBLE_EQ(s.nodes[s.tread_centre_node].x(), 0.310);
}

TEST(Abaqus, ErrorsNameFileAndLine) {
  const std::string dir = scratch_dir();
  const auto expect_error = [&](const std::string& name, const std::string& text, const std::string& where) {
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    try {
      import_abaqus_cross_section(path, 0.01);
      ADD_FAILURE() << name << " accepted";
    } catch (const cosim::Error& e) {
      EXPECT_NE(std::string(e.what()).find(path + ":" + where), std::string::npos) << e.what();
    }
  };
  const std::string nodes = "*NODE\n1, 0.2, 0\n2, 0.21, 0\n3, 0.21, 0.01\n4, 0.2, 0.01\n";
  expect_error("type.inp", nodes + "*ELEMENT, TYPE=C3D8R\n1, 1, 2, 3, 4\n", "6");
  expect_error("node.inp", nodes + "*ELEMENT, TYPE=CAX4\n1, 1, 2, 3, 9\n*ELSET, ELSET=TREAD\n1\n", "7");
  expect_error("region.inp", nodes + "*ELEMENT, TYPE=CAX4\n1, 1, 2, 3, 4\n", "7");
  expect_error("coordinate.inp", "*NODE\n1, 0.2, zero\n", "2");
}

TEST(Vtk, WritesBigEndianLegacyFiles) {
  const CrossSection& s = default_section();
  TreadPattern p = four_grooves(TreadVariant::block);
  p.pitch_count = 10;
  const Mesh3D m = revolve(s, p);
  const std::string dir = scratch_dir();
  write_vtk_cross_section(dir + "/section.vtk", s);
  VtkField pressure{"contact_pressure", 1, std::vector<double>(m.facets.size(), 1.0)};
  write_vtk_facets(dir + "/facets.vtk", m, m.nodes, {pressure});
  write_vtk_mesh(dir + "/mesh.vtk", m, m.nodes, {{"displacement", 3, std::vector<double>(3 * m.nodes.size(), 0.0)}});
  std::ifstream in(dir + "/mesh.vtk", std::ios::binary);
  std::string header;
  for (int i = 0; i < 5; ++i) {
    std::string line;
    std::getline(in, line);
    header += line + "\n";
  }
  EXPECT_NE(header.find("BINARY"), std::string::npos);
  EXPECT_NE(header.find("POINTS " + std::to_string(m.nodes.size()) + " double"), std::string::npos);
  unsigned char bytes[8];
  in.read(reinterpret_cast<char*>(bytes), 8);
  std::uint64_t bits = 0;
  for (unsigned char b : bytes) bits = (bits << 8) | b;
  double x0;
  std::memcpy(&x0, &bits, 8);
  EXPECT_EQ(x0, m.nodes[0].x());
  EXPECT_FALSE(std::filesystem::exists(dir + "/mesh.vtk.tmp"));
  EXPECT_THROW(write_vtk_facets(dir + "/bad.vtk", m, m.nodes, {{"bad name", 1, {}}}), cosim::Error);
  EXPECT_THROW(write_vtk_mesh(dir + "/no_such_dir/x.vtk", m, m.nodes), cosim::Error);
}

// The contact surface offered to a terrain: every outer facet (not the inner
// liner, not the rim faces), and the terrain's facet pressures come back onto
// the mesh facets they were reported on (the surface VTK's contact_pressure_Pa
// in a coupled run), added to the road's nodal mean.
TEST(ContactSurface, OuterFacetsAndTerrainPressureOnTheRightMeshFacet) {
  TreadPattern p = four_grooves(TreadVariant::rib);
  p.pitch_count = 12;
  p.elements_per_pitch = 2;
  const Mesh3D m = revolve(default_section(), p);
  const ContactSurfaceDef surface = make_contact_surface(m);
  ASSERT_EQ(surface.mesh_facets.size(), surface.facet_count());
  ASSERT_EQ(surface.facet_nodes.size(), 4 * surface.facet_count());
  std::map<SurfaceTag, int> outer;
  for (const auto& f : m.facets)
    if (f.tag != SurfaceTag::inner_liner && f.tag != SurfaceTag::rim_contact) ++outer[f.tag];
  std::map<SurfaceTag, int> offered;
  for (std::size_t f = 0; f < surface.facet_count(); ++f) {
    const auto& mesh_facet = m.facets.at(surface.mesh_facets[f]);
    ASSERT_EQ(mesh_facet.tag, surface.facet_tags[f]) << "surface facet " << f;
    for (int k = 0; k < 4; ++k)
      ASSERT_EQ(surface.node_ids.at(surface.facet_nodes[4 * f + k]), mesh_facet.nodes[k]) << "surface facet " << f;
    ++offered[surface.facet_tags[f]];
  }
  EXPECT_EQ(offered, outer);

  // A road pressure of 4 kPa on one node and the terrain's 70 and 35 kPa on two facets.
  std::vector<double> nodal(m.nodes.size(), 0.0);
  const int road_node = m.facets[0].nodes[2];
  nodal[road_node] = 4000.0;
  cosim::SurfaceLoads loads;
  const std::uint32_t f1 = 3, f2 = static_cast<std::uint32_t>(surface.facet_count() - 1);
  loads.facets = {f1, f2};
  loads.pressure_Pa = {70e3, 35e3};
  const std::vector<double> facet_p = facet_contact_pressure_Pa(m, nodal, surface, loads);
  ASSERT_EQ(facet_p.size(), m.facets.size());
  for (std::size_t f = 0; f < m.facets.size(); ++f) {
    const auto& n = m.facets[f].nodes;
    double expected = std::count(n.begin(), n.end(), road_node) * 1000.0;
    if (static_cast<int>(f) == surface.mesh_facets[f1]) expected += 70e3;
    if (static_cast<int>(f) == surface.mesh_facets[f2]) expected += 35e3;
    ASSERT_EQ(facet_p[f], expected) << "mesh facet " << f;
  }
}
