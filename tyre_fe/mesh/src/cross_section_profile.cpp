// Design dimensions and the layered profile of the generated tyre cross-section.
//
// The profile is built from the inner (cavity) contour of the carcass, from the
// crown centre to the bead seat: a superellipse quadrant from the crown to the
// maximum width (flat crown, round shoulder), a blended S-curve down the lower
// sidewall and a straight vertical bead face where the tyre sits against the rim
// flange. The layer boundaries are offsets of it along its outward normal: liner,
// ply and the two belt layers at fixed gauges (thickened into the bead and the
// filler near the seat), then the outer rubber: the full tread thickness over the
// crown up to the tread edge, then a shoulder cap (arc and inward flank line)
// blended smoothly into the sidewall gauge, whichever is thicker.
#include "cross_section_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cosim/error.hpp"

namespace tyre_fe::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInch = 0.0254;

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// max(a, b) rounded over a band of width k (exact outside it), so that the outer
// surface has no kink where the tread cap meets the sidewall.
double smooth_max(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::max(a, b) + h * h * k * 0.25;
}

// Closed polygon (r, y) bounding the tread shoulder beyond the tread edge `edge`
// (where the crown surface has the unit normal `edge_normal`): the shoulder arc,
// tangent to the crown there, then the straight flank line inwards to y = 0,
// closed along y = 0 and the radius of the edge.
std::vector<Eigen::Vector2d> shoulder_polygon(const ProfileDesign& d, const Eigen::Vector2d& edge,
                                              const Eigen::Vector2d& edge_normal) {
  std::vector<Eigen::Vector2d> poly{Eigen::Vector2d(edge.x(), 0.0), edge};
  const double edge_angle = std::atan2(edge_normal.y(), edge_normal.x());
  const Eigen::Vector2d centre = edge - d.cap_shoulder_radius * edge_normal;
  const int n_arc = 90;
  for (int i = 1; i <= n_arc; ++i) {
    const double a = edge_angle + (d.cap_end_angle - edge_angle) * i / n_arc;
    poly.push_back(centre + d.cap_shoulder_radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  const Eigen::Vector2d end = poly.back();
  const Eigen::Vector2d tangent(-std::sin(d.cap_end_angle), std::cos(d.cap_end_angle));
  poly.push_back(end + tangent * (end.y() / -tangent.y()));
  return poly;
}

// Distance along the ray p + t n (t > 0) to where it leaves the convex polygon, or
// -infinity if p lies outside it (even number of crossings).
double exit_distance(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p,
                     const Eigen::Vector2d& n) {
  int crossings = 0;
  double t_min = std::numeric_limits<double>::infinity();
  const size_t m = polygon.size();
  for (size_t i = 0; i < m; ++i) {
    const Eigen::Vector2d a = polygon[i];
    const Eigen::Vector2d e = polygon[(i + 1) % m] - a;
    const double det = n.x() * (-e.y()) - n.y() * (-e.x());
    if (std::abs(det) < 1e-15) continue;
    const Eigen::Vector2d rhs = a - p;
    const double t = (rhs.x() * (-e.y()) - rhs.y() * (-e.x())) / det;
    const double s = (n.x() * rhs.y() - n.y() * rhs.x()) / det;
    if (t > 0.0 && s >= 0.0 && s < 1.0) {
      ++crossings;
      t_min = std::min(t_min, t);
    }
  }
  return crossings % 2 == 1 ? t_min : -std::numeric_limits<double>::infinity();
}

}  // namespace

ProfileDesign design_profile(const TyreSize& size, const TreadPattern& pattern,
                             const CrossSectionMesh& mesh) {
  const double sw = size.section_width_m;
  const double ar = size.aspect_ratio;
  if (!(sw >= 0.1 && sw <= 0.45) || !(ar >= 0.3 && ar <= 0.95) ||
      !(size.rim_diameter_m >= 10 * kInch && size.rim_diameter_m <= 26 * kInch))
    throw cosim::Error("tyre size out of the generator's range (section width 100-450 mm, "
                       "aspect ratio 30-95 %, rim 10-26 in)");
  if (!(mesh.target_element_size_m >= 0.0005 && mesh.target_element_size_m <= 0.05))
    throw cosim::Error("cross-section mesh: target_element_size_m must be 0.5-50 mm");
  if (mesh.tread_layers < 2 || mesh.tread_layers > 20)
    throw cosim::Error("cross-section mesh: tread_layers must be 2-20 (the groove bottom "
                       "needs a layer boundary between the base and the groove layers)");
  if (!(pattern.groove_depth_m > 0.0) || !(pattern.tread_base_m > 0.0))
    throw cosim::Error("tread pattern: groove_depth_m and tread_base_m must be positive");

  ProfileDesign d;
  const double section_height = ar * sw;
  d.rim_radius = 0.5 * size.rim_diameter_m;
  d.outer_radius = d.rim_radius + section_height;
  d.section_half_width = 0.5 * sw;
  // Measuring rim width: about 70 % of the section width for 75-series tyres and
  // wider for low profiles (ETRTO: 235/75R15 on 6.5J, 205/55R16 on 6.5J, 225/45R17
  // on 7.5J), rounded to the half inch in which rims are made.
  const double rim_fraction = 0.70 + 0.5 * std::max(0.0, 0.75 - ar);
  d.rim_half_width = 0.5 * std::round(sw * rim_fraction / (0.5 * kInch)) * (0.5 * kInch);
  // Maximum section width at about mid-height, a little higher on low profiles whose
  // lower sidewall must otherwise turn sharply above the bead.
  d.max_width_radius = d.rim_radius + section_height * (0.55 + 0.4 * std::max(0.0, 0.6 - ar));
  // Filler (apex) height above the bead: 35 mm, less on low profiles, but always
  // reaching at least 10 mm above the flange where it tapers.
  d.apex_height = std::max(std::min(0.035, 0.2 * section_height), d.flange_height + 0.010 - d.bead_height);
  d.rim_strip_height = d.flange_height + std::min(0.015, 0.1 * section_height);

  d.tread_half_width = 0.5 * (pattern.tread_width_m > 0.0 ? pattern.tread_width_m : 0.8 * sw);
  d.groove_depth = pattern.groove_depth_m;
  d.tread_base = pattern.tread_base_m;
  d.tread_layers = mesh.tread_layers;
  const double tread = d.groove_depth + d.tread_base;
  d.base_layers = std::clamp(static_cast<int>(std::lround(d.tread_layers * d.tread_base / tread)), 1,
                             d.tread_layers - 1);
  // Belt 1 (inner, wider) ends just inside the tread edge, belt 2 8 mm narrower per
  // side (stepped belt edges reduce the shear stress concentration at the edge).
  d.belt1_half_width = 0.95 * d.tread_half_width;
  d.belt2_half_width = d.belt1_half_width - 0.008;
  // Shoulder arc ~ 7 % of the section width; the flank then runs inwards at 20 deg
  // from the radial so that the shoulder rubber meets the sidewall gauge about a
  // fifth of the way down the section.
  d.cap_shoulder_radius = 0.06 * sw;
  d.cap_end_angle = 110.0 * kPi / 180.0;  // normal 20 deg below the axial

  if (d.tread_half_width > d.section_half_width - d.side_stack() - 0.005 ||
      d.tread_half_width < 0.2 * d.section_half_width)
    throw cosim::Error("tread pattern: tread_width_m must lie between 40 % of the section "
                       "width and the carcass width");
  if (tread > 0.3 * section_height || d.crown_stack() > 0.35 * section_height)
    throw cosim::Error("tread pattern: groove_depth_m + tread_base_m too thick for the section height");
  const double inner_crown = d.outer_radius - d.crown_stack();
  if (inner_crown - d.max_width_radius < 0.02)
    throw cosim::Error("tyre size: section too low for the generator's layer stack");
  if (d.section_half_width - d.side_stack() - (d.rim_half_width - d.bead_stack()) < 0.005)
    throw cosim::Error("tyre size: section width too close to the rim width");
  if (d.max_width_radius - d.rim_radius - d.flange_height < 0.02)
    throw cosim::Error("tyre size: lower sidewall too short for the bead and rim flange");
  return d;
}

HalfProfile::HalfProfile(const ProfileDesign& design) : design_(design) {
  boundary_count_ = 5 + design_.tread_layers;
  build_inner_contour();
  build_stack();
}

void HalfProfile::build_inner_contour() {
  const ProfileDesign& d = design_;
  std::vector<Eigen::Vector2d> raw;
  // Crown to maximum width: superellipse quadrant |dr/a|^p + |y/b|^p = 1.
  const double r_crown = d.outer_radius - d.crown_stack();
  const double a = r_crown - d.max_width_radius;
  const double b = d.section_half_width - d.side_stack();
  const double er = 2.0 / d.carcass_exponent_side;
  const double ey = 2.0 / d.carcass_exponent_crown;
  const int n_upper = 20000;
  for (int i = 0; i <= n_upper; ++i) {
    const double phi = 0.5 * kPi * i / n_upper;
    raw.emplace_back(d.max_width_radius + a * std::pow(std::max(0.0, std::cos(phi)), er),
                     b * std::pow(std::max(0.0, std::sin(phi)), ey));
  }
  // Lower sidewall: blended S-curve with vertical tangents at both ends.
  const double y_bead = d.rim_half_width - d.bead_stack();
  const double r_flange = d.rim_radius + d.flange_height;
  const double height = d.max_width_radius - r_flange;
  const double shift = b - y_bead;
  const int n_lower = 10000;
  for (int i = 1; i <= n_lower; ++i) {
    const double t = static_cast<double>(i) / n_lower;
    const double g = t * t * (3.0 - 2.0 * t) + d.lower_blend * t * t * (1 - t) * (1 - t);
    raw.emplace_back(d.max_width_radius - t * height, b - shift * g);
  }
  // Bead face against the rim flange, down to the seat.
  const int n_bead = 2000;
  for (int i = 1; i <= n_bead; ++i)
    raw.emplace_back(r_flange - d.flange_height * i / n_bead, y_bead);

  // Resample at equal arc length so that stations interpolate linearly.
  std::vector<double> cum(raw.size(), 0.0);
  for (size_t i = 1; i < raw.size(); ++i) cum[i] = cum[i - 1] + (raw[i] - raw[i - 1]).norm();
  length_ = cum.back();
  const int n = static_cast<int>(std::ceil(length_ / 5e-5));
  spacing_ = length_ / n;
  samples_.assign(n + 1, Sample{});
  size_t seg = 0;
  for (int j = 0; j <= n; ++j) {
    const double u = std::min(j * spacing_, length_);
    while (seg + 2 < raw.size() && cum[seg + 1] < u) ++seg;
    const double w = std::clamp((u - cum[seg]) / (cum[seg + 1] - cum[seg]), 0.0, 1.0);
    samples_[j].p = (1 - w) * raw[seg] + w * raw[seg + 1];
  }
  // Outward normal = tangent rotated by -90 deg in (r, y): (t_y, -t_r). The ends
  // are exact: radial at the crown centre, axial at the bead face.
  for (int j = 0; j <= n; ++j) {
    Eigen::Vector2d t;
    if (j == 0) t = Eigen::Vector2d(0, 1);
    else if (j == n) t = Eigen::Vector2d(-1, 0);
    else t = (samples_[j + 1].p - samples_[j - 1].p).normalized();
    samples_[j].n = Eigen::Vector2d(t.y(), -t.x());
  }
}

void HalfProfile::build_stack() {
  const ProfileDesign& d = design_;
  const double tread = d.groove_depth + d.tread_base;
  const int groove_layers = d.tread_layers - d.base_layers;
  // Inner layers first: liner, ply and the belt-1/belt-2 layers, the latter half
  // the bead width each over the bead, tapering through the filler (apex) to the
  // belt gauge.
  for (size_t j = 0; j < samples_.size(); ++j) {
    Sample& s = samples_[j];
    const double from_bead = length_ - j * spacing_;
    // Full bead width up to the flange top, so that the tyre's outside stays flat
    // against the flange; the filler tapers above it.
    const double taper_start = std::max(d.bead_height, d.flange_height);
    const double taper = smoothstep((from_bead - taper_start) / (d.bead_height + d.apex_height - taper_start));
    const double mid = 0.5 * d.bead_width + (d.belt - 0.5 * d.bead_width) * taper;
    s.depth.assign(boundary_count_, 0.0);
    s.depth[1] = d.liner;
    s.depth[2] = d.liner + d.ply;
    s.depth[3] = s.depth[2] + mid;
    s.depth[4] = s.depth[3] + mid;
  }
  // Crown: the full tread thickness on top of the belts up to the tread edge, so
  // that the groove depth is the same everywhere on the tread. Beyond the edge the
  // shoulder polygon decides.
  size_t edge = 0;
  const auto outer_crown = [&](size_t j) { return samples_[j].p + samples_[j].n * (samples_[j].depth[4] + tread); };
  while (edge + 1 < samples_.size() && outer_crown(edge).y() < d.tread_half_width) ++edge;
  const auto shoulder = shoulder_polygon(d, outer_crown(edge), samples_[edge].n);
  for (size_t j = 0; j < samples_.size(); ++j) {
    Sample& s = samples_[j];
    const double cap_rubber = j <= edge ? tread : exit_distance(shoulder, s.p, s.n) - s.depth[4];
    s.cap_excess = cap_rubber - d.side_rubber;
    const double rubber = smooth_max(cap_rubber, d.side_rubber, 0.008);
    // Groove zone: exactly the groove depth where the rubber is at least the
    // full tread thickness (groove bottoms on a layer boundary); where it thins
    // towards the sidewall the split drifts to equal layers so that no layer gets
    // too thin.
    double top;
    if (rubber >= tread) {
      top = d.groove_depth;
    } else {
      const double w = std::clamp((rubber - d.side_rubber) / (tread - d.side_rubber), 0.0, 1.0);
      const double equal = static_cast<double>(groove_layers) / d.tread_layers;
      top = rubber * (equal + (d.groove_depth / tread - equal) * w);
    }
    const double base = rubber - top;
    for (int i = 1; i <= d.base_layers; ++i) s.depth[4 + i] = s.depth[4] + base * i / d.base_layers;
    for (int i = 1; i <= groove_layers; ++i)
      s.depth[4 + d.base_layers + i] = s.depth[4] + base + top * i / groove_layers;
  }
  // Metric: the longest boundary's arc length.
  samples_[0].metric = 0.0;
  for (size_t j = 1; j < samples_.size(); ++j) {
    double step = 0.0;
    for (int k = 0; k < boundary_count_; ++k) {
      const Eigen::Vector2d a = samples_[j - 1].p + samples_[j - 1].n * samples_[j - 1].depth[k];
      const Eigen::Vector2d b = samples_[j].p + samples_[j].n * samples_[j].depth[k];
      step = std::max(step, (b - a).norm());
    }
    samples_[j].metric = samples_[j - 1].metric + step;
  }
}

void HalfProfile::interpolate(double u, int* i, double* w) const {
  const double x = std::clamp(std::abs(u) / spacing_, 0.0, static_cast<double>(samples_.size() - 1));
  *i = std::min(static_cast<int>(x), static_cast<int>(samples_.size()) - 2);
  *w = x - *i;
}

Eigen::Vector2d HalfProfile::point(double u, int k) const {
  int i;
  double w;
  interpolate(u, &i, &w);
  const Sample& a = samples_[i];
  const Sample& b = samples_[i + 1];
  const Eigen::Vector2d p = (1 - w) * a.p + w * b.p;
  const Eigen::Vector2d n = ((1 - w) * a.n + w * b.n).normalized();
  const double depth = (1 - w) * a.depth[k] + w * b.depth[k];
  Eigen::Vector2d q = p + n * depth;
  if (u < 0) q.y() = -q.y();
  return q;
}

double HalfProfile::metric(double u) const {
  int i;
  double w;
  interpolate(u, &i, &w);
  const double m = (1 - w) * samples_[i].metric + w * samples_[i + 1].metric;
  return u < 0 ? -m : m;
}

double HalfProfile::station_at_metric(double m) const {
  const double target = std::abs(m);
  auto it = std::lower_bound(samples_.begin(), samples_.end(), target,
                             [](const Sample& s, double v) { return s.metric < v; });
  if (it == samples_.begin()) return 0.0;
  if (it == samples_.end()) return m < 0 ? -length_ : length_;
  const size_t j = static_cast<size_t>(it - samples_.begin());
  const double m0 = samples_[j - 1].metric, m1 = samples_[j].metric;
  const double u = (j - 1 + (target - m0) / (m1 - m0)) * spacing_;
  return m < 0 ? -u : u;
}

bool HalfProfile::in_tread_zone(double u) const {
  int i;
  double w;
  interpolate(u, &i, &w);
  return (1 - w) * samples_[i].cap_excess + w * samples_[i + 1].cap_excess > 0.0;
}

double HalfProfile::station_at_y(int k, double y_target) const {
  double u_prev = 0.0;
  if (point(0.0, k).y() >= y_target) return 0.0;
  for (size_t j = 1; j < samples_.size(); ++j) {
    const double u = j * spacing_;
    const double y = point(u, k).y();
    if (y >= y_target) {
      // Bisection on the interpolated boundary so that the node lands exactly on y.
      double lo = u_prev, hi = u;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (point(mid, k).y() < y_target ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
    u_prev = u;
  }
  return -1.0;
}

}  // namespace tyre_fe::detail
