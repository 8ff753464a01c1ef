// The 3D tyre: the cross-section revolved about the spin axis, with the tread
// pattern cut into it (grooves remove tread elements, sipes split nodes) and the
// boundary facets tagged for contact, friction and pressure loading.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cosim/error.hpp"
#include "cosim/quad_facet.hpp"
#include "tyre_fe/geometry.hpp"

namespace tyre_fe {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

// Local node lists of the hex faces with outward normals (VTK_HEXAHEDRON): the
// start face (angle theta_j), the end face (theta_j+1), then the four side faces,
// which are the revolved quad edges kSideEdge[f - 2].
constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr int kSideEdge[4] = {3, 2, 1, 0};

struct AngularGrid {
  std::vector<double> theta;  // N + 1 grid angles, 0 ... 2 pi
  std::vector<char> lateral;  // per division: inside a lateral groove
  std::vector<int> sipe_lines;
};

// Circumferential grid. Smooth and rib: uniform. Block variants, per pitch: the
// lateral groove (its width an arc length at the outer radius) at the start of the
// pitch, then the block cut into sipes_per_block + 1 equal segments whose inner
// boundaries carry the sipes. The block variant uses the same segmentation (when
// elements_per_pitch allows it) so that block and block_sipes differ only by the slits.
AngularGrid make_grid(const TreadPattern& p, double outer_radius) {
  if (p.pitch_count < 1 || p.elements_per_pitch < 1)
    throw cosim::Error("tread pattern: pitch_count and elements_per_pitch must be >= 1");
  const int per = p.elements_per_pitch;
  const double pitch = kTwoPi / p.pitch_count;
  AngularGrid g;
  const bool blocks = p.variant == TreadVariant::block || p.variant == TreadVariant::block_sipes;
  if (!blocks) {
    const int n = p.pitch_count * per;
    for (int j = 0; j <= n; ++j) g.theta.push_back(kTwoPi * j / n);
    g.lateral.assign(n, 0);
    return g;
  }
  const double groove = p.lateral_groove_width_m / outer_radius;
  if (!(groove > 0.0) || groove >= 0.9 * pitch)
    throw cosim::Error("tread pattern: lateral_groove_width_m must be positive and well below the pitch length");
  const bool sipes = p.variant == TreadVariant::block_sipes;
  if (sipes && (p.sipes_per_block < 1 || !(p.sipe_depth_m > 0.0)))
    throw cosim::Error("tread pattern: block_sipes needs sipes_per_block >= 1 and sipe_depth_m > 0");
  const int wanted = std::max(0, p.sipes_per_block) + 1;
  if (per < 2 || (sipes && per < 1 + wanted))
    throw cosim::Error("tread pattern: elements_per_pitch = " + std::to_string(per) +
                       " is too small (one for the lateral groove and " +
                       std::to_string(sipes ? wanted : 1) + " for the block segments)");
  const int segments = per - 1 >= wanted ? wanted : 1;
  const int n_groove = std::clamp(static_cast<int>(std::lround(per * groove / pitch)), 1, per - segments);
  const int n_block = per - n_groove;
  const double segment = (pitch - groove) / segments;
  for (int k = 0; k < p.pitch_count; ++k) {
    const double base = k * pitch;
    for (int i = 0; i < n_groove; ++i) {
      g.theta.push_back(base + groove * i / n_groove);
      g.lateral.push_back(1);
    }
    for (int s = 0; s < segments; ++s) {
      const int count = n_block / segments + (s < n_block % segments ? 1 : 0);
      for (int i = 0; i < count; ++i) {
        if (i == 0 && s > 0 && sipes) g.sipe_lines.push_back(static_cast<int>(g.theta.size()));
        g.theta.push_back(base + groove + segment * (s + static_cast<double>(i) / count));
        g.lateral.push_back(0);
      }
    }
  }
  g.theta.push_back(kTwoPi);
  return g;
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * e)).norm();
}

// --- 2D topology: quad-edge neighbours (-1 on the boundary), inner-liner
// edges and rim nodes of the cross-section.
struct SectionTopology {
  std::vector<std::array<int, 4>> neighbour;
  std::vector<char> liner_edge;
  std::vector<char> rim_2d;
};

SectionTopology section_topology(const CrossSection& s) {
  const int nq = static_cast<int>(s.quads.size());
  const int nn = static_cast<int>(s.nodes.size());
  std::map<std::pair<int, int>, std::vector<std::array<int, 2>>> edge_uses;
  for (int q = 0; q < nq; ++q)
    for (int k = 0; k < 4; ++k) {
      const int a = s.quads[q][k], b = s.quads[q][(k + 1) % 4];
      edge_uses[{std::min(a, b), std::max(a, b)}].push_back({q, k});
    }
  std::vector<std::array<int, 4>> neighbour(nq, {-1, -1, -1, -1});
  for (const auto& [key, uses] : edge_uses)
    if (uses.size() == 2) {
      neighbour[uses[0][0]][uses[0][1]] = uses[1][0];
      neighbour[uses[1][0]][uses[1][1]] = uses[0][0];
    }
  std::vector<char> liner_edge(4 * nq, 0);
  for (const auto& e : s.inner_liner_edges) liner_edge[4 * e[0] + e[1]] = 1;
  std::vector<char> rim_2d(nn, 0);
  for (int n : s.rim_nodes) rim_2d[n] = 1;
  return {std::move(neighbour), std::move(liner_edge), std::move(rim_2d)};
}

// --- depth below the outer tread surface (the boundary edges of tread quads)
using Segments = std::vector<std::array<Eigen::Vector2d, 2>>;

Segments tread_surface_edges(const CrossSection& s, const std::vector<std::array<int, 4>>& neighbour) {
  const int nq = static_cast<int>(s.quads.size());
  Segments tread_surface;
  for (int q = 0; q < nq; ++q)
    if (s.quad_region[q] == Region::tread)
      for (int k = 0; k < 4; ++k)
        if (neighbour[q][k] < 0) tread_surface.push_back({s.nodes[s.quads[q][k]], s.nodes[s.quads[q][(k + 1) % 4]]});
  return tread_surface;
}

double depth_below(const Segments& tread_surface, const Eigen::Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& e : tread_surface) d = std::min(d, segment_distance(p, e[0], e[1]));
  return d;
}

std::vector<Eigen::Vector2d> quad_centres(const CrossSection& s) {
  const int nq = static_cast<int>(s.quads.size());
  std::vector<Eigen::Vector2d> centre(nq);
  for (int q = 0; q < nq; ++q)
    centre[q] = 0.25 * (s.nodes[s.quads[q][0]] + s.nodes[s.quads[q][1]] + s.nodes[s.quads[q][2]] + s.nodes[s.quads[q][3]]);
  return centre;
}

// --- which tread quads the grooves and sipes cut (by their centre)
struct TreadCuts {
  std::vector<char> circumferential, lateral, slit;
};

TreadCuts mark_tread_cuts(const CrossSection& s, const TreadPattern& pattern, const Segments& tread_surface,
                          const std::vector<Eigen::Vector2d>& centre) {
  const int nq = static_cast<int>(s.quads.size());
  const TreadVariant v = pattern.variant;
  const bool blocks = v == TreadVariant::block || v == TreadVariant::block_sipes;
  const bool grooves = v != TreadVariant::smooth;
  if (grooves && !(pattern.groove_depth_m > 0.0)) throw cosim::Error("tread pattern: groove_depth_m must be positive");
  const double twh = s.tread_half_width_m;
  std::vector<char> circumferential(nq, 0), lateral(nq, 0), slit(nq, 0);
  for (int q = 0; q < nq; ++q) {
    if (!grooves || s.quad_region[q] != Region::tread) continue;
    const double depth = depth_below(tread_surface, centre[q]);
    const double y = centre[q].y();
    for (double yc : pattern.circumferential_groove_y_m)
      if (std::abs(y - yc) < 0.5 * pattern.circumferential_groove_width_m && depth < pattern.groove_depth_m)
        circumferential[q] = 1;
    // Lateral grooves and sipes span the ground-contacting width; their ends at
    // the tread edge are closed by the shoulder rubber.
    lateral[q] = blocks && std::abs(y) <= twh && depth < pattern.groove_depth_m;
    slit[q] = v == TreadVariant::block_sipes && std::abs(y) <= twh && depth < pattern.sipe_depth_m;
  }
  return {std::move(circumferential), std::move(lateral), std::move(slit)};
}

// Whether the hex of quad q in division j (taken modulo the divisions) is
// meshed: a circumferential groove removes it everywhere, a lateral groove in
// its divisions.
struct HexPresence {
  const TreadCuts& cuts;
  const AngularGrid& grid;
  int nd;
  bool operator()(int q, int j) const {
    j = (j + nd) % nd;
    return !cuts.circumferential[q] && !(grid.lateral[j] && cuts.lateral[q]);
  }
};

// --- sipes: split the nodes of the slit faces, except on the slit's edges
// inside the body (bottom, closed ends), so that the two faces can separate.
struct SipeSplit {
  std::vector<int> sipe_of_line;
  std::vector<std::vector<int>> copy_id;    // per sipe line: 2D node -> copy index or -1
  std::vector<std::vector<char>> slit_face; // per sipe line: quad -> slit
  int copies = 0;
};

SipeSplit split_sipe_nodes(const CrossSection& s, const AngularGrid& grid, const HexPresence& exists,
                           const std::vector<char>& slit, const Segments& tread_surface,
                           const std::vector<Eigen::Vector2d>& centre, Mesh3D& m) {
  const int nq = static_cast<int>(s.quads.size());
  const int nn = static_cast<int>(s.nodes.size());
  const int nd = static_cast<int>(grid.lateral.size());
  const double twh = s.tread_half_width_m;
  SipeSplit sp;
  sp.sipe_of_line.assign(nd, -1);
  for (int js : grid.sipe_lines) {
    sp.sipe_of_line[js] = static_cast<int>(sp.copy_id.size());
    std::vector<char> face(nq, 0), blocked(nn, 0), touched(nn, 0);
    for (int q = 0; q < nq; ++q) {
      if (!exists(q, js - 1) || !exists(q, js)) continue;
      face[q] = slit[q];
      for (int n : s.quads[q]) (face[q] ? touched : blocked)[n] = 1;
    }
    std::vector<int> ids(nn, -1);
    for (int n = 0; n < nn; ++n)
      if (touched[n] && !blocked[n]) ids[n] = sp.copies++;
    // Slit depth as meshed, measured over the central half of the tread where
    // the layers are uniform (towards the tread edge the rounding by element
    // centres may reach one layer deeper).
    for (int q = 0; q < nq; ++q)
      if (face[q] && std::abs(centre[q].y()) <= 0.5 * twh)
        for (int n : s.quads[q]) m.sipe_depth_m = std::max(m.sipe_depth_m, depth_below(tread_surface, s.nodes[n]));
    sp.copy_id.push_back(std::move(ids));
    sp.slit_face.push_back(std::move(face));
  }
  return sp;
}

// --- hexes on grid node ids (j * nn + n; copies after nd * nn)
struct GridHexes {
  std::vector<std::array<int, 8>> hexes;
  std::vector<int> hex_quad, hex_div;
};

GridHexes grid_hexes(const CrossSection& s, int nd, const HexPresence& exists, const SipeSplit& sp) {
  const int nq = static_cast<int>(s.quads.size());
  const int nn = static_cast<int>(s.nodes.size());
  const auto grid_id = [&](int n, int j) { return ((j + nd) % nd) * nn + n; };
  GridHexes gh;
  for (int j = 0; j < nd; ++j)
    for (int q = 0; q < nq; ++q) {
      if (!exists(q, j)) continue;
      const auto& c = s.quads[q];
      const int order[4] = {c[0], c[3], c[2], c[1]};
      std::array<int, 8> h;
      const int si = sp.sipe_of_line[j];
      for (int a = 0; a < 4; ++a) {
        const int n = order[a];
        h[a] = si >= 0 && sp.copy_id[si][n] >= 0 ? nd * nn + sp.copy_id[si][n] : grid_id(n, j);
        h[a + 4] = grid_id(n, j + 1);
      }
      gh.hexes.push_back(h);
      gh.hex_quad.push_back(q);
      gh.hex_div.push_back(j);
    }
  return gh;
}

// --- compact numbering of the used nodes; the mesh's nodes and hexes
void add_nodes_and_hexes(const CrossSection& s, const AngularGrid& grid, const SipeSplit& sp,
                         const GridHexes& gh, const std::vector<char>& rim_2d, Mesh3D& m) {
  const int nn = static_cast<int>(s.nodes.size());
  const int nd = static_cast<int>(grid.lateral.size());
  const int copies = sp.copies;
  const auto& hexes = gh.hexes;
  const auto& copy_id = sp.copy_id;
  std::vector<int> new_id(static_cast<size_t>(nd) * nn + copies, -1);
  for (const auto& h : hexes)
    for (int g : h) new_id[g] = 0;
  std::vector<int> copy_source(copies), copy_line(copies);
  for (size_t si = 0; si < copy_id.size(); ++si)
    for (int n = 0; n < nn; ++n)
      if (copy_id[si][n] >= 0) {
        copy_source[copy_id[si][n]] = n;
        copy_line[copy_id[si][n]] = grid.sipe_lines[si];
      }
  for (size_t g = 0; g < new_id.size(); ++g) {
    if (new_id[g] < 0) continue;
    const bool copy = g >= static_cast<size_t>(nd) * nn;
    const int src = copy ? copy_source[g - static_cast<size_t>(nd) * nn] : static_cast<int>(g % nn);
    const int j = copy ? copy_line[g - static_cast<size_t>(nd) * nn] : static_cast<int>(g / nn);
    const double th = grid.theta[j];
    const Eigen::Vector2d& p = s.nodes[src];
    new_id[g] = static_cast<int>(m.nodes.size());
    m.nodes.emplace_back(p.x() * std::sin(th), p.y(), p.x() * std::cos(th));
    m.node_source.push_back(src);
    m.node_angle_rad.push_back(th);
    if (rim_2d[src]) m.rim_nodes.push_back(new_id[g]);
  }
  for (size_t e = 0; e < hexes.size(); ++e) {
    std::array<int, 8> h;
    for (int a = 0; a < 8; ++a) h[a] = new_id[hexes[e][a]];
    m.hexes.push_back(h);
    m.hex_region.push_back(s.quad_region[gh.hex_quad[e]]);
    m.hex_source_quad.push_back(gh.hex_quad[e]);
    m.hex_angle_rad.push_back(0.5 * (grid.theta[gh.hex_div[e]] + grid.theta[gh.hex_div[e] + 1]));
  }
}

// --- boundary facets: a side face is exposed where the 2D edge is on the
// boundary or the neighbouring quad's hex was removed; an angular face where
// the previous/next hex was removed or a slit separates them.
void add_boundary_facets(const CrossSection& s, const SectionTopology& topo, const GridHexes& gh,
                         const SipeSplit& sp, const HexPresence& exists, Mesh3D& m) {
  const int nd = exists.nd;
  const double twh = s.tread_half_width_m;
  Eigen::Vector2d lo = s.nodes[0], hi = s.nodes[0];
  for (const auto& p : s.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d cavity = 0.5 * (lo + hi);
  for (size_t e = 0; e < m.hexes.size(); ++e) {
    const int q = gh.hex_quad[e], j = gh.hex_div[e];
    for (int f = 0; f < 6; ++f) {
      Mesh3D::Facet facet;
      for (int a = 0; a < 4; ++a) facet.nodes[a] = m.hexes[e][kFaces[f][a]];
      facet.hex = static_cast<int>(e);
      const Eigen::Vector3d p0 = m.nodes[facet.nodes[0]], p1 = m.nodes[facet.nodes[1]],
                            p2 = m.nodes[facet.nodes[2]], p3 = m.nodes[facet.nodes[3]];
      const Eigen::Vector3d mid = cosim::quad_centroid(p0, p1, p2, p3);
      const Eigen::Vector3d normal = cosim::unit_normal(cosim::quad_area_vector(p0, p1, p2, p3));
      const double radial = normal.dot(Eigen::Vector3d(mid.x(), 0.0, mid.z()).normalized());
      bool all_rim = true;
      for (int n : facet.nodes) all_rim = all_rim && topo.rim_2d[m.node_source[n]];
      if (f < 2) {
        const int line = f == 0 ? j : (j + 1) % nd;
        const int si = sp.sipe_of_line[line];
        const bool cut = si >= 0 && sp.slit_face[si][q];
        if (exists(q, f == 0 ? j - 1 : j + 1) && !cut) continue;
        facet.tag = cut ? SurfaceTag::sipe_wall : SurfaceTag::groove_wall;
      } else {
        const int k = kSideEdge[f - 2];
        const int other = topo.neighbour[q][k];
        if (other >= 0 && exists(other, j)) continue;
        if (topo.liner_edge[4 * q + k]) facet.tag = SurfaceTag::inner_liner;
        else if (all_rim) facet.tag = SurfaceTag::rim_contact;
        else if (other >= 0) facet.tag = radial > 0.7 ? SurfaceTag::groove_bottom : SurfaceTag::groove_wall;
        else if (s.quad_region[q] == Region::tread)
          facet.tag = std::abs(mid.y()) <= twh + 1e-9 && radial > 0.5 ? SurfaceTag::tread_top : SurfaceTag::shoulder;
        else {
          const Eigen::Vector2d a = s.nodes[s.quads[q][k]], b = s.nodes[s.quads[q][(k + 1) % 4]];
          const Eigen::Vector2d outward(b.y() - a.y(), a.x() - b.x());
          facet.tag = outward.dot(cavity - 0.5 * (a + b)) > 0 ? SurfaceTag::other : SurfaceTag::sidewall;
        }
      }
      m.facets.push_back(facet);
    }
  }
}

}  // namespace

// The stages: 2D topology and tread depth, the quads the pattern cuts, the
// angular grid, sipe node copies, hexes, node numbering, tagged boundary facets.
Mesh3D revolve(const CrossSection& s, const TreadPattern& pattern) {
  const int nq = static_cast<int>(s.quads.size());
  if (nq == 0 || static_cast<int>(s.quad_region.size()) != nq)
    throw cosim::Error("revolve: cross-section without quads or regions");
  const SectionTopology topo = section_topology(s);
  const Segments tread_surface = tread_surface_edges(s, topo.neighbour);
  const std::vector<Eigen::Vector2d> centre = quad_centres(s);
  const TreadCuts cuts = mark_tread_cuts(s, pattern, tread_surface, centre);

  double outer_radius = 0.0;
  if (s.tread_centre_node >= 0) outer_radius = s.nodes[s.tread_centre_node].x();
  else for (const auto& p : s.nodes) outer_radius = std::max(outer_radius, p.x());
  const AngularGrid grid = make_grid(pattern, outer_radius);
  const int nd = static_cast<int>(grid.lateral.size());
  const HexPresence exists{cuts, grid, nd};

  Mesh3D m;
  const SipeSplit sp = split_sipe_nodes(s, grid, exists, cuts.slit, tread_surface, centre, m);
  if (pattern.variant == TreadVariant::block_sipes) m.sipe_width_m = pattern.sipe_width_m;
  const GridHexes gh = grid_hexes(s, nd, exists, sp);
  add_nodes_and_hexes(s, grid, sp, gh, topo.rim_2d, m);
  add_boundary_facets(s, topo, gh, sp, exists, m);
  return m;
}

std::vector<Eigen::Vector3d> revolve_positions(const Mesh3D& mesh, const std::vector<Eigen::Vector2d>& section,
                                               const std::vector<double>& twist_rad) {
  std::vector<Eigen::Vector3d> x(mesh.nodes.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Eigen::Vector2d& p = section[mesh.node_source[i]];
    const double th = mesh.node_angle_rad[i] + (twist_rad.empty() ? 0.0 : twist_rad[mesh.node_source[i]]);
    x[i] = Eigen::Vector3d(p[0] * std::sin(th), p[1], p[0] * std::cos(th));
  }
  return x;
}

}  // namespace tyre_fe
