// Tyre size parsing and the generated axisymmetric cross-section: a structured
// mesh of quads swept along the carcass contour from bead to bead, with a fixed
// number of layers through the thickness (see cross_section_profile.cpp for the
// shape and the dimensions chosen).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "cosim/error.hpp"
#include "cross_section_profile.hpp"
#include "tyre_fe/geometry.hpp"

namespace tyre_fe {
namespace {

// Reads an unsigned decimal number (digits with an optional fraction) at text[pos].
bool read_number(const std::string& text, size_t& pos, double* value) {
  const size_t start = pos;
  while (pos < text.size() && (std::isdigit(static_cast<unsigned char>(text[pos])) || text[pos] == '.'))
    ++pos;
  if (pos == start) return false;
  const std::string digits = text.substr(start, pos - start);
  if (std::count(digits.begin(), digits.end(), '.') > 1 || digits.front() == '.' || digits.back() == '.')
    return false;
  *value = std::stod(digits);
  return true;
}

// A station break along the contour: hard ones (groove and tread edges, centre,
// bead seats) are always nodes; soft ones (region changes) are dropped when they
// would create a sliver next to another break.
struct Break {
  double u;
  bool hard;
};

std::vector<double> place_breaks(std::vector<Break> breaks, double min_gap) {
  std::sort(breaks.begin(), breaks.end(), [](const Break& a, const Break& b) { return a.u < b.u; });
  std::vector<double> hard;
  for (const Break& b : breaks)
    if (b.hard && (hard.empty() || b.u - hard.back() > 1e-7)) hard.push_back(b.u);
  std::vector<double> kept = hard;
  for (const Break& b : breaks) {
    if (b.hard) continue;
    bool clear = true;
    for (double k : kept) clear = clear && std::abs(k - b.u) > min_gap;
    if (clear) kept.push_back(b.u);
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

double signed_area(const CrossSection& s, int q) {
  const auto& n = s.quads[q];
  double a = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d& p = s.nodes[n[k]];
    const Eigen::Vector2d& r = s.nodes[n[(k + 1) % 4]];
    a += p.x() * r.y() - r.x() * p.y();
  }
  return 0.5 * a;
}

// --- station breaks: the hard ones at the tread edges, groove edges, centre and
// bead seats; soft ones at the region boundaries along the contour.
struct StationBreaks {
  std::vector<double> kept;
  double u_belt1, u_belt2;  // stations where the belt layers reach their half widths
};

StationBreaks station_breaks(const detail::ProfileDesign& design, const detail::HalfProfile& profile,
                             const TreadPattern& pattern, double h) {
  const int nb = profile.boundary_count();
  const int outer = nb - 1;
  const double len = profile.length();
  std::vector<Break> breaks{{-len, true}, {0.0, true}, {len, true}};
  const auto both_sides = [&](double u, bool hard) {
    breaks.push_back({u, hard});
    breaks.push_back({-u, hard});
  };
  const auto outer_y_break = [&](double y) {
    const double u = profile.station_at_y(outer, std::abs(y));
    if (u < 0) throw cosim::Error("tread pattern: y = " + cosim::number_text(y) + " m is off the tread");
    breaks.push_back({y < 0 ? -u : u, true});
  };
  outer_y_break(design.tread_half_width);
  outer_y_break(-design.tread_half_width);
  for (double yc : pattern.circumferential_groove_y_m) {
    const double hw = 0.5 * pattern.circumferential_groove_width_m;
    if (!(hw > 0) || std::abs(yc) + hw > design.tread_half_width - 1e-6)
      throw cosim::Error("tread pattern: circumferential groove at y = " + cosim::number_text(yc) +
                         " m (width " + cosim::number_text(2 * hw) + " m) is not inside the tread width");
    outer_y_break(yc - hw);
    outer_y_break(yc + hw);
  }
  // Soft breaks: region boundaries along the contour.
  both_sides(len - design.bead_height, false);
  both_sides(len - design.flange_height, false);
  both_sides(len - design.rim_strip_height, false);
  both_sides(len - design.bead_height - design.apex_height, false);
  // Belt edges: where the belt layers reach their half widths (the carcass keeps
  // widening further down, so the belts are the stations inside these).
  const double u_belt1 = profile.station_at_y(2, design.belt1_half_width);
  const double u_belt2 = profile.station_at_y(3, design.belt2_half_width);
  both_sides(u_belt1, false);
  both_sides(u_belt2, false);
  for (double u = 0.0; u < len; u += 1e-4)
    if (!profile.in_tread_zone(u)) {
      both_sides(u, false);
      break;
    }
  return {place_breaks(breaks, 0.4 * h), u_belt1, u_belt2};
}

// --- stations: equal steps of the meridional metric between breaks
std::vector<double> place_stations(const detail::HalfProfile& profile, const std::vector<double>& kept, double h) {
  std::vector<double> stations{kept.front()};
  for (size_t b = 0; b + 1 < kept.size(); ++b) {
    const double m0 = profile.metric(kept[b]), m1 = profile.metric(kept[b + 1]);
    const int n = std::max(1, static_cast<int>(std::ceil((m1 - m0) / h - 0.1)));
    for (int j = 1; j < n; ++j) stations.push_back(profile.station_at_metric(m0 + (m1 - m0) * j / n));
    stations.push_back(kept[b + 1]);
  }
  return stations;
}

// The region of layer k at contour station uc.
Region layer_region(int k, double uc, double from_bead, bool tread_zone, const detail::ProfileDesign& design,
                    const StationBreaks& breaks) {
  Region r;
  if (k == 0) {
    r = Region::inner_liner;
  } else if (k == 1) {
    r = Region::ply;
  } else if (k == 2 || k == 3) {
    if (std::abs(uc) < (k == 2 ? breaks.u_belt1 : breaks.u_belt2)) r = k == 2 ? Region::belt_1 : Region::belt_2;
    else if (from_bead < design.bead_height) r = Region::bead;
    else if (from_bead < design.bead_height + design.apex_height) r = Region::filler;
    else r = tread_zone ? Region::tread : Region::sidewall;
  } else {
    if (tread_zone) r = Region::tread;
    else if (from_bead < design.rim_strip_height) r = Region::rim_strip;
    else r = Region::sidewall;
  }
  return r;
}

// The quads between stations i, i+1 and boundaries k, k+1, with their region,
// rebar layer direction and thickness.
void add_quads(const detail::ProfileDesign& design, const detail::HalfProfile& profile,
               const std::vector<double>& stations, const StationBreaks& breaks, CrossSection& s) {
  const int nb = profile.boundary_count();
  const int ns = static_cast<int>(stations.size());
  const auto node = [nb](int i, int k) { return i * nb + k; };
  for (int i = 0; i + 1 < ns; ++i) {
    const double uc = 0.5 * (stations[i] + stations[i + 1]);
    const double from_bead = profile.from_bead(uc);
    const bool tread_zone = profile.in_tread_zone(uc);
    for (int k = 0; k + 1 < nb; ++k) {
      const Region r = layer_region(k, uc, from_bead, tread_zone, design, breaks);
      const std::array<int, 4> q{node(i, k), node(i, k + 1), node(i + 1, k + 1), node(i + 1, k)};
      s.quads.push_back(q);
      s.quad_region.push_back(r);
      // Layer direction: mean of the two edges along the contour (from the y < 0
      // bead towards the y > 0 one); thickness = area / mean length along it.
      const Eigen::Vector2d along = (s.nodes[q[3]] - s.nodes[q[0]]) + (s.nodes[q[2]] - s.nodes[q[1]]);
      const bool rebar = r == Region::ply || r == Region::belt_1 || r == Region::belt_2;
      s.quad_layer_tangent.push_back(rebar ? along.normalized() : Eigen::Vector2d::Zero());
      const int qi = static_cast<int>(s.quads.size()) - 1;
      s.quad_layer_thickness_m.push_back(signed_area(s, qi) / (0.5 * along.norm()));
      if (k == 0) s.inner_liner_edges.push_back({qi, 3});
    }
  }
}

// Quality gate: every quad strictly convex and counter-clockwise.
void check_quads_convex(const CrossSection& s) {
  for (size_t q = 0; q < s.quads.size(); ++q) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d a = s.nodes[s.quads[q][k]], b = s.nodes[s.quads[q][(k + 1) % 4]],
                            c = s.nodes[s.quads[q][(k + 2) % 4]];
      const Eigen::Vector2d e1 = b - a, e2 = c - b;
      if (e1.x() * e2.y() - e1.y() * e2.x() <= 0.0)
        throw cosim::Error("tyre cross-section generator: distorted element at r = " +
                           cosim::number_text(a.x()) + " m, y = " + cosim::number_text(a.y()) +
                           " m; this size/pattern is outside what the generator can mesh");
    }
  }
}

}  // namespace

// Accepts "235/75R15", "P235/75R15", "LT235/75R15", "235/75 R 15", "235/75ZR15"
// (case-insensitive, blanks ignored) and rim diameters with a fraction ("16.5").
TyreSize parse_tyre_size(const std::string& designation) {
  std::string text;
  for (char c : designation)
    if (!std::isspace(static_cast<unsigned char>(c)))
      text.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  const auto fail = [&](const std::string& why) {
    return cosim::Error("tyre size '" + designation + "': " + why +
                        " (expected a designation such as 235/75R15)");
  };
  size_t pos = 0;
  if (text.compare(0, 2, "LT") == 0) pos = 2;
  else if (!text.empty() && text[0] == 'P') pos = 1;
  double width_mm = 0, aspect_pct = 0, rim_in = 0;
  if (!read_number(text, pos, &width_mm)) throw fail("missing section width in mm");
  if (pos >= text.size() || text[pos] != '/') throw fail("missing '/' after the section width");
  ++pos;
  if (!read_number(text, pos, &aspect_pct)) throw fail("missing aspect ratio in %");
  if (pos < text.size() && text[pos] == 'Z') ++pos;
  if (pos >= text.size() || text[pos] != 'R') throw fail("only radial ('R') tyres are supported");
  ++pos;
  if (!read_number(text, pos, &rim_in)) throw fail("missing rim diameter in inches");
  if (pos != text.size()) throw fail("unexpected text '" + text.substr(pos) + "'");
  if (width_mm < 50 || width_mm > 500) throw fail("section width must be 50-500 mm");
  if (aspect_pct < 20 || aspect_pct > 100) throw fail("aspect ratio must be 20-100 %");
  if (rim_in < 8 || rim_in > 30) throw fail("rim diameter must be 8-30 in");
  TyreSize size;
  size.section_width_m = width_mm * 1e-3;
  size.aspect_ratio = aspect_pct * 1e-2;
  size.rim_diameter_m = rim_in * 0.0254;
  return size;
}

// Builds the structured cross-section. Stations (cross lines through the
// thickness) run from the y < 0 bead seat to the y > 0 one; at each station the
// boundary_count() nodes go from the cavity outwards. Quad (i, k) spans stations
// i, i+1 and boundaries k, k+1 with nodes (i,k), (i,k+1), (i+1,k+1), (i+1,k):
// counter-clockwise in (r, y); its edge 3 lies on boundary k.
CrossSection make_cross_section(const TyreSize& size, const TreadPattern& pattern,
                                const CrossSectionMesh& mesh) {
  const detail::ProfileDesign design = detail::design_profile(size, pattern, mesh);
  const detail::HalfProfile profile(design);
  const int nb = profile.boundary_count();
  const int outer = nb - 1;
  const double h = mesh.target_element_size_m;
  const StationBreaks breaks = station_breaks(design, profile, pattern, h);
  const std::vector<double> stations = place_stations(profile, breaks.kept, h);
  const int ns = static_cast<int>(stations.size());

  CrossSection s;
  for (int i = 0; i < ns; ++i)
    for (int k = 0; k < nb; ++k) s.nodes.push_back(profile.point(stations[i], k));
  const auto node = [nb](int i, int k) { return i * nb + k; };
  add_quads(design, profile, stations, breaks, s);

  // Rim: both bead seats (all nodes of the end stations) and the outer nodes
  // against the flange.
  for (int i = 0; i < ns; ++i) {
    const bool seat = i == 0 || i == ns - 1;
    for (int k = 0; k < nb; ++k)
      if (seat || (k == outer && profile.from_bead(stations[i]) <= design.flange_height + 1e-9))
        s.rim_nodes.push_back(node(i, k));
  }
  const int centre = static_cast<int>(std::find(stations.begin(), stations.end(), 0.0) - stations.begin());
  s.tread_centre_node = node(centre, outer);
  s.tread_half_width_m = design.tread_half_width;
  check_quads_convex(s);
  return s;
}

}  // namespace tyre_fe
