// Abaqus input-deck import of an axisymmetric tyre cross-section.
//
// Accepted (keywords and names case-insensitive, "**" comments, blank lines):
//  *NODE [, NSET=name]                      id, r, y [, ignored]
//  *ELEMENT, TYPE=CAX4|CAX4R|CGAX4|CGAX4R (also the hybrid ...H variants) [, ELSET=name]
//                                           id, n1, n2, n3, n4 (may continue on the
//                                           next line after a trailing comma)
//  *ELSET, ELSET=name [, GENERATE]          ids and/or earlier set names; GENERATE:
//  *NSET, NSET=name [, GENERATE]            first, last [, step]
//  *SURFACE, NAME=name [, TYPE=ELEMENT]     element id or elset name, S1..S4
// Every other keyword and its data lines are skipped (materials, steps, ...).
//
// Regions come from element sets named after them; names are compared without
// case, '_', '-' or blanks: TREAD, SIDEWALL, INNER_LINER / INNERLINER, PLY /
// CARCASS, BELT_1 / BELT1, BELT_2 / BELT2, BEAD, FILLER / APEX, RIM_STRIP /
// RIMSTRIP / CHAFER. Every element must be in exactly one of them.
// Rim nodes: NSET RIM (or RIM_NODES); without it, the nodes of bead and rim-strip
// elements within 0.1 mm of their smallest radius (the bead seat).
// Inner liner (pressure) edges, first found of: SURFACE INNER_LINER / INNERLINER /
// CAVITY; an NSET of that name (boundary edges with both nodes in it); else the
// boundary edges of inner-liner elements whose outward normal points towards the
// cavity (the middle of the section's bounding box).
// Tread centre: NSET TREAD_CENTRE / TREAD_CENTER, else the outer tread node
// nearest to y = 0 (largest r on ties).
// Nodes not used by any element (e.g. a rim reference node) are dropped; nodes and
// elements keep the deck's order; clockwise elements are reordered.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "abaqus_deck.hpp"
#include "cosim/error.hpp"
#include "tyre_fe/geometry.hpp"

namespace tyre_fe {
namespace {

using detail::AbaqusDeck;

std::string normalised(const std::string& name) {
  std::string out;
  for (char c : name)
    if (c != '_' && c != '-' && !std::isspace(static_cast<unsigned char>(c)))
      out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

bool region_of_set(const std::string& set_name, Region* region) {
  static const std::pair<const char*, Region> kNames[] = {
      {"tread", Region::tread},         {"sidewall", Region::sidewall},
      {"innerliner", Region::inner_liner}, {"ply", Region::ply},
      {"carcass", Region::ply},         {"belt1", Region::belt_1},
      {"belt2", Region::belt_2},        {"bead", Region::bead},
      {"filler", Region::filler},       {"apex", Region::filler},
      {"rimstrip", Region::rim_strip},  {"chafer", Region::rim_strip}};
  const std::string n = normalised(set_name);
  for (const auto& [name, r] : kNames)
    if (n == name) {
      *region = r;
      return true;
    }
  return false;
}

const std::vector<int>* find_set(const std::map<std::string, std::vector<int>>& sets,
                                 std::initializer_list<const char*> names) {
  for (const auto& [name, members] : sets)
    for (const char* wanted : names)
      if (normalised(name) == wanted) return &members;
  return nullptr;
}

using EdgeKey = std::pair<int, int>;
EdgeKey edge_key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }
using EdgeUses = std::map<EdgeKey, std::vector<std::array<int, 2>>>;

// "file:line" for the messages about one line of the deck.
std::string where(const std::string& inp_path, int line) { return inp_path + ":" + std::to_string(line); }

// Regions from the element sets: element id -> (region, the set that gave it).
std::map<int, std::pair<Region, std::string>> element_regions(const AbaqusDeck& deck, const std::string& inp_path) {
  std::map<int, std::pair<Region, std::string>> element_region;
  for (const auto& [set_name, members] : deck.elsets) {
    Region r;
    if (!region_of_set(set_name, &r)) continue;
    for (int id : members) {
      auto [it, inserted] = element_region.emplace(id, std::make_pair(r, set_name));
      if (!inserted && it->second.first != r)
        throw cosim::Error(inp_path + ": element " + std::to_string(id) + " is in both ELSET " +
                           it->second.second + " and ELSET " + set_name);
    }
  }
  return element_region;
}

// The used nodes in deck order and the quads (counter-clockwise) with their
// regions; returns the deck's node id -> node index.
std::map<int, int> add_nodes_and_quads(const AbaqusDeck& deck,
                                       const std::map<int, std::pair<Region, std::string>>& element_region,
                                       const std::string& inp_path, CrossSection& s) {
  std::map<int, int> node_index;
  std::set<int> used;
  for (const auto& e : deck.elements)
    for (int n : e.nodes) {
      if (!deck.nodes.count(n))
        throw cosim::Error(where(inp_path, e.line) + ": element " + std::to_string(e.id) + " uses node " +
                           std::to_string(n) + " which is not defined by *NODE");
      used.insert(n);
    }
  for (int id : deck.node_order)
    if (used.count(id)) {
      node_index[id] = static_cast<int>(s.nodes.size());
      s.nodes.push_back(deck.nodes.at(id).position);
    }

  for (const auto& e : deck.elements) {
    const auto reg = element_region.find(e.id);
    if (reg == element_region.end())
      throw cosim::Error(where(inp_path, e.line) + ": element " + std::to_string(e.id) +
                         " is in no region ELSET (tread, sidewall, inner_liner, ply, belt_1, "
                         "belt_2, bead, filler, rim_strip)");
    std::array<int, 4> q;
    for (int k = 0; k < 4; ++k) q[k] = node_index.at(e.nodes[k]);
    double area2 = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d& a = s.nodes[q[k]];
      const Eigen::Vector2d& b = s.nodes[q[(k + 1) % 4]];
      area2 += a.x() * b.y() - b.x() * a.y();
    }
    if (std::abs(area2) < 1e-14)
      throw cosim::Error(where(inp_path, e.line) + ": element " + std::to_string(e.id) + " has zero area");
    if (area2 < 0) q = {q[0], q[3], q[2], q[1]};
    s.quads.push_back(q);
    s.quad_region.push_back(reg->second.first);
  }
  return node_index;
}

// Edge adjacency: the (quad, local edge) uses of every edge.
EdgeUses edge_uses_of(const CrossSection& s) {
  EdgeUses edge_uses;
  for (size_t q = 0; q < s.quads.size(); ++q)
    for (int k = 0; k < 4; ++k)
      edge_uses[edge_key(s.quads[q][k], s.quads[q][(k + 1) % 4])].push_back({static_cast<int>(q), k});
  return edge_uses;
}

// The cavity's stand-in: the middle of the section's bounding box.
Eigen::Vector2d bounding_box_middle(const CrossSection& s) {
  Eigen::Vector2d lo = s.nodes[0], hi = s.nodes[0];
  for (const auto& p : s.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return 0.5 * (lo + hi);
}

// Layer direction of ply and belt quads: the edges shared with quads of the same
// region cross the layer, so the layer runs along the other pair of edges (the
// longer pair where that does not decide). Thickness = area / length along it.
void add_layer_directions(EdgeUses& edge_uses, const Eigen::Vector2d& cavity, CrossSection& s) {
  for (size_t q = 0; q < s.quads.size(); ++q) {
    const auto& n = s.quads[q];
    const auto shared_same = [&](int k) {
      for (const auto& use : edge_uses[edge_key(n[k], n[(k + 1) % 4])])
        if (use[0] != static_cast<int>(q) && s.quad_region[use[0]] == s.quad_region[q]) return true;
      return false;
    };
    const Eigen::Vector2d a = (s.nodes[n[3]] - s.nodes[n[0]]) + (s.nodes[n[2]] - s.nodes[n[1]]);  // along edges 1, 3
    const Eigen::Vector2d b = (s.nodes[n[1]] - s.nodes[n[0]]) + (s.nodes[n[2]] - s.nodes[n[3]]);  // along edges 0, 2
    const bool cross_02 = shared_same(0) || shared_same(2);
    const bool cross_13 = shared_same(1) || shared_same(3);
    Eigen::Vector2d along = cross_02 != cross_13 ? (cross_02 ? a : b) : (a.norm() >= b.norm() ? a : b);
    double area2 = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d& p = s.nodes[n[k]];
      const Eigen::Vector2d& r = s.nodes[n[(k + 1) % 4]];
      area2 += p.x() * r.y() - r.x() * p.y();
    }
    s.quad_layer_thickness_m.push_back(0.5 * area2 / (0.5 * along.norm()));
    const Region r = s.quad_region[q];
    if (r == Region::ply || r == Region::belt_1 || r == Region::belt_2) {
      // Orientation: from the y < 0 bead towards the y > 0 one, i.e. with the
      // cavity on the left of the direction in the (r, y) plane.
      const Eigen::Vector2d centre = 0.25 * (s.nodes[n[0]] + s.nodes[n[1]] + s.nodes[n[2]] + s.nodes[n[3]]);
      const Eigen::Vector2d to_cavity = cavity - centre;
      if (along.x() * to_cavity.y() - along.y() * to_cavity.x() < 0) along = -along;
      s.quad_layer_tangent.push_back(along.normalized());
    } else {
      s.quad_layer_tangent.push_back(Eigen::Vector2d::Zero());
    }
  }
}

// Rim nodes.
std::vector<int> find_rim_nodes(const AbaqusDeck& deck, const std::map<int, int>& node_index, const CrossSection& s,
                                const std::string& inp_path) {
  std::set<int> rim;
  if (const auto* set = find_set(deck.nsets, {"rim", "rimnodes"})) {
    for (int id : *set)
      if (node_index.count(id)) rim.insert(node_index.at(id));
    if (rim.empty()) throw cosim::Error(inp_path + ": NSET RIM contains no node of the cross-section");
  } else {
    double r_min = 1e30;
    std::set<int> candidates;
    for (size_t q = 0; q < s.quads.size(); ++q)
      if (s.quad_region[q] == Region::bead || s.quad_region[q] == Region::rim_strip)
        for (int n : s.quads[q]) {
          candidates.insert(n);
          r_min = std::min(r_min, s.nodes[n].x());
        }
    for (int n : candidates)
      if (s.nodes[n].x() <= r_min + 1e-4) rim.insert(n);
    if (rim.empty())
      throw cosim::Error(inp_path + ": no NSET RIM and no bead or rim_strip elements to find the bead seat");
  }
  return std::vector<int>(rim.begin(), rim.end());
}

// Inner liner edges.
void add_inner_liner_edges(const AbaqusDeck& deck, const std::map<int, int>& node_index,
                           const std::map<int, int>& quad_of_element, const EdgeUses& edge_uses,
                           const Eigen::Vector2d& cavity, const std::string& inp_path, CrossSection& s) {
  const auto quad_edge = [&](int quad, int a, int b) {
    for (int k = 0; k < 4; ++k)
      if (edge_key(s.quads[quad][k], s.quads[quad][(k + 1) % 4]) == edge_key(a, b)) return k;
    return -1;
  };
  const std::initializer_list<const char*> liner_names{"innerliner", "cavity", "innerlinersurface"};
  const detail::AbaqusSurface* surface = nullptr;
  for (const auto& [name, surf] : deck.surfaces)
    for (const char* wanted : liner_names)
      if (normalised(name) == wanted) surface = &surf;
  if (surface) {
    for (const auto& face : surface->faces) {
      const int quad = quad_of_element.count(face.element) ? quad_of_element.at(face.element) : -1;
      if (quad < 0)
        throw cosim::Error(where(inp_path, face.line) + ": surface face on unknown element " +
                           std::to_string(face.element));
      const auto& e = deck.elements[quad];
      const int a = node_index.at(e.nodes[face.face]), b = node_index.at(e.nodes[(face.face + 1) % 4]);
      s.inner_liner_edges.push_back({quad, quad_edge(quad, a, b)});
    }
  } else if (const auto* set = find_set(deck.nsets, liner_names)) {
    std::set<int> on;
    for (int id : *set)
      if (node_index.count(id)) on.insert(node_index.at(id));
    for (const auto& [key, uses] : edge_uses)
      if (uses.size() == 1 && on.count(key.first) && on.count(key.second)) s.inner_liner_edges.push_back(uses[0]);
  } else {
    for (const auto& [key, uses] : edge_uses) {
      if (uses.size() != 1 || s.quad_region[uses[0][0]] != Region::inner_liner) continue;
      const auto& n = s.quads[uses[0][0]];
      const Eigen::Vector2d a = s.nodes[n[uses[0][1]]], b = s.nodes[n[(uses[0][1] + 1) % 4]];
      const Eigen::Vector2d outward(b.y() - a.y(), -(b.x() - a.x()));  // right of a->b: outside a CCW quad
      if (outward.dot(cavity - 0.5 * (a + b)) > 0) s.inner_liner_edges.push_back(uses[0]);
    }
    std::sort(s.inner_liner_edges.begin(), s.inner_liner_edges.end());
  }
  if (s.inner_liner_edges.empty()) throw cosim::Error(inp_path + ": no inner liner surface found");
}

// Tread centre node.
int find_tread_centre_node(const AbaqusDeck& deck, const std::map<int, int>& node_index, const EdgeUses& edge_uses,
                           const CrossSection& s, const std::string& inp_path) {
  int centre = s.tread_centre_node;
  if (const auto* set = find_set(deck.nsets, {"treadcentre", "treadcenter"})) {
    if (set->empty() || !node_index.count(set->front()))
      throw cosim::Error(inp_path + ": NSET TREAD_CENTRE names no node of the cross-section");
    centre = node_index.at(set->front());
  } else {
    for (const auto& [key, uses] : edge_uses) {
      if (uses.size() != 1 || s.quad_region[uses[0][0]] != Region::tread) continue;
      for (int n : {key.first, key.second}) {
        const int best = centre;
        const auto& p = s.nodes[n];
        if (best < 0 || std::abs(p.y()) < std::abs(s.nodes[best].y()) - 1e-9 ||
            (std::abs(p.y()) <= std::abs(s.nodes[best].y()) + 1e-9 && p.x() > s.nodes[best].x()))
          centre = n;
      }
    }
  }
  return centre;
}

}  // namespace

CrossSection import_abaqus_cross_section(const std::string& inp_path, double tread_half_width_m) {
  const AbaqusDeck deck = detail::read_abaqus_deck(inp_path);
  if (deck.elements.empty()) throw cosim::Error(inp_path + ": no *ELEMENT of a supported type");
  const auto element_region = element_regions(deck, inp_path);
  CrossSection s;
  const std::map<int, int> node_index = add_nodes_and_quads(deck, element_region, inp_path, s);
  std::map<int, int> quad_of_element;
  for (size_t i = 0; i < deck.elements.size(); ++i) quad_of_element[deck.elements[i].id] = static_cast<int>(i);
  EdgeUses edge_uses = edge_uses_of(s);
  const Eigen::Vector2d cavity = bounding_box_middle(s);
  add_layer_directions(edge_uses, cavity, s);
  s.rim_nodes = find_rim_nodes(deck, node_index, s, inp_path);
  add_inner_liner_edges(deck, node_index, quad_of_element, edge_uses, cavity, inp_path, s);
  s.tread_centre_node = find_tread_centre_node(deck, node_index, edge_uses, s, inp_path);
  s.tread_half_width_m = tread_half_width_m;
  return s;
}

}  // namespace tyre_fe
