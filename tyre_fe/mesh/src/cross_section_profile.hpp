#pragma once
// Private to the cross-section generator: the design dimensions of a radial
// passenger tyre derived from its size, and the layered profile (inner carcass
// contour plus the stack of layer boundaries offset along its outward normal).
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "tyre_fe/geometry.hpp"

namespace tyre_fe::detail {

// Dimensions of the generated tyre [m]. The defaults are the fixed-size parts
// (layer gauges, bead, rim flange) of a passenger / light-truck radial tyre; the
// rest is derived from the size in design_profile().
struct ProfileDesign {
  double rim_radius = 0.0;          // bead seat radius = rim diameter / 2
  double outer_radius = 0.0;        // tread surface at y = 0
  double section_half_width = 0.0;  // maximum outer half width (sidewall)
  double rim_half_width = 0.0;      // flange inside face |y|
  double max_width_radius = 0.0;    // r where the section is widest
  // Rim flange height above the bead seat (ETRTO "J" flange, 17.5 mm).
  double flange_height = 0.0175;
  // Layer gauges through the thickness, inside out. 1.5 mm liner, 1 mm ply and
  // 1 mm per steel belt are typical calendered gauges; 3.5 mm of sidewall rubber
  // gives a total sidewall of 8 mm, typical for passenger/light-truck tyres.
  double liner = 0.0015;
  double ply = 0.0010;
  double belt = 0.0010;
  double side_rubber = 0.0035;
  // Bead bundle, modelled as the belt-1/belt-2 layers thickened to half of
  // bead_width each over bead_height from the seat: roughly a 9 mm square.
  double bead_width = 0.009;
  double bead_height = 0.009;
  double apex_height = 0.0;       // filler above the bead (tapers to the belt gauge)
  double rim_strip_height = 0.0;  // chafer on the outside, above the seat
  // Tread.
  double tread_half_width = 0.0;
  double groove_depth = 0.0;
  double tread_base = 0.0;
  int tread_layers = 0;
  int base_layers = 0;  // of tread_layers, below the groove bottoms
  double belt1_half_width = 0.0;
  double belt2_half_width = 0.0;
  // Outer surface: the crown follows the carcass at the full tread thickness up
  // to the tread edge; then a shoulder arc and a straight flank line inwards.
  double cap_shoulder_radius = 0.0;
  double cap_end_angle = 0.0;  // normal angle where the flank line starts [rad]
  // Carcass (inner contour) from the crown to the maximum width: the generalised
  // superellipse |dr/a|^p + |y/b|^q = 1. A large q keeps the crown (and the belts)
  // flat, p near 2 rounds the sidewall at the maximum width like an inflated carcass.
  double carcass_exponent_crown = 5.0;  // q
  double carcass_exponent_side = 2.2;   // p
  // Lower sidewall blend g(t) = t^2(3-2t) + c t^2(1-t)^2: c > 0 softens the
  // concave bend above the bead (where the layers are thick) at the expense of
  // the convex one at the maximum width (where offsetting is harmless).
  double lower_blend = 0.0;

  double crown_stack() const { return liner + ply + 2 * belt + groove_depth + tread_base; }
  double side_stack() const { return liner + ply + 2 * belt + side_rubber; }
  double bead_stack() const { return liner + ply + bead_width + side_rubber; }
};

// Derives the design from the size and pattern; throws cosim::Error for sizes or
// patterns the generator cannot mesh sensibly.
ProfileDesign design_profile(const TyreSize& size, const TreadPattern& pattern,
                             const CrossSectionMesh& mesh);

// The right half (y >= 0) of the layered profile, densely sampled by the arc
// length u of the inner contour from the crown centre (u = 0) to the bead seat
// (u = length()). The left half is its mirror image; signed stations u < 0 address it.
class HalfProfile {
 public:
  explicit HalfProfile(const ProfileDesign& design);

  const ProfileDesign& design() const { return design_; }
  double length() const { return length_; }
  // Layer boundaries through the thickness: 0 = inside (cavity) surface,
  // boundary_count() - 1 = outer surface. Layers: liner, ply, belt-1 layer,
  // belt-2 layer, then tread_layers rubber layers.
  int boundary_count() const { return boundary_count_; }

  // Position (r, y) of boundary k at signed station u (|u| <= length()).
  Eigen::Vector2d point(double u, int k) const;
  // Meridional metric: arc length of the longest layer boundary between the crown
  // centre and |u| (signed like u). Stations equally spaced in it keep every
  // element edge near the target size on both the concave and convex sides.
  double metric(double u) const;
  // Inverse of metric().
  double station_at_metric(double m) const;
  // True where the outer rubber belongs to the tread cap rather than the sidewall.
  bool in_tread_zone(double u) const;
  // Distance from the bead seat along the inner contour.
  double from_bead(double u) const { return length_ - std::abs(u); }
  // Smallest station u >= 0 at which boundary k reaches |y| = y_target
  // (scanning from the crown towards the bead); -1 if it never does.
  double station_at_y(int k, double y_target) const;

 private:
  struct Sample {
    Eigen::Vector2d p;  // inner contour point (r, y)
    Eigen::Vector2d n;  // unit outward normal
    std::vector<double> depth;  // offset of each boundary along n
    double metric = 0.0;
    double cap_excess = 0.0;  // tread-cap rubber minus sidewall rubber (> 0: tread)
  };
  void build_inner_contour();
  void build_stack();
  void interpolate(double u, int* i, double* w) const;

  ProfileDesign design_;
  int boundary_count_ = 0;
  double spacing_ = 0.0;
  double length_ = 0.0;
  std::vector<Sample> samples_;
};

}  // namespace tyre_fe::detail
