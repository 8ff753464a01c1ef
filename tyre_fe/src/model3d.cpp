#include "tyre_fe/model3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include "cosim/error.hpp"
#include "cosim/quad_facet.hpp"

namespace tyre_fe {
namespace {

bool touches_ground(SurfaceTag t) {
  return t != SurfaceTag::inner_liner && t != SurfaceTag::rim_contact;
}

// The direction in which a facet at c meets the road: a revolved tyre's facet
// radially out from the spin axis (y, through the origin), a tread block's
// downwards (its nodes come from no cross-section: node_source -1).
Eigen::Vector3d ground_facing(const Mesh3D& mesh, const Eigen::Vector3d& c) {
  const bool revolved = !mesh.node_source.empty() && mesh.node_source.front() >= 0;
  if (!revolved) return {0.0, 0.0, -1.0};
  const Eigen::Vector3d radial(c.x(), 0.0, c.z());
  return radial.norm() > 0.0 ? Eigen::Vector3d(radial.normalized()) : Eigen::Vector3d(0.0, 0.0, -1.0);
}

// The element's rebar layer, smeared into it as a volume fraction phi of bars
// along a0; adds the bars' density to the element's, rho.
void set_element_rebar(Model3d& m, const Mesh3D& mesh, const CrossSection& section, std::size_t e,
                       const RebarLayer& rebar, double& rho) {
  const int quad = mesh.hex_source_quad[e];
  if (rebar.area_m2 > 0.0 && quad >= 0) {
    // a0 = cos(angle) t_meridional + sin(angle) e_theta at the element's angle
    // (mesh.hpp: x = r sin(theta), z = r cos(theta)).
    const Eigen::Vector2d t = section.quad_layer_tangent[quad];
    const double th = mesh.hex_angle_rad[e];
    const Eigen::Vector3d e_r(std::sin(th), 0.0, std::cos(th));
    const Eigen::Vector3d e_y(0.0, 1.0, 0.0);
    const Eigen::Vector3d e_th(std::cos(th), 0.0, -std::sin(th));
    Eigen::Vector3d a0 = std::cos(rebar.angle_rad) * (t[0] * e_r + t[1] * e_y) +
                         std::sin(rebar.angle_rad) * e_th;
    if (a0.norm() > 0.0) {
      a0.normalize();
      const double phi = rebar.area_m2 / (rebar.spacing_m * section.quad_layer_thickness_m[quad]);
      m.rebar_direction[e] = a0;
      m.rebar_fraction[e] = phi;
      m.rebar_modulus_Pa[e] = rebar.youngs_modulus_Pa;
      rho += phi * rebar.density_kg_per_m3;
    }
  }
}

// Element e's reference geometry, material, rebar, density and wave speed;
// returns its stable time step before mass scaling [s].
double set_element(Model3d& m, const Mesh3D& mesh, const CrossSection& section, std::size_t e) {
  const TyreMaterials& materials = m.materials;
  const Model3dOptions& options = m.options;
  double X[8][3];
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 3; ++k) X[a][k] = mesh.nodes[mesh.hexes[e][a]][k];
  try {
    m.reference[e] = hex8_reference(X);
  } catch (const cosim::Error& err) {
    throw cosim::Error("hexahedron " + std::to_string(e) + " (" +
                       region_name(mesh.hex_region[e]) + "): " + err.what());
  }
  const int region = static_cast<int>(mesh.hex_region[e]);
  m.material[e] = region;
  const SolidMaterial& solid = materials.solid[region];
  double rho = solid.density_kg_per_m3();
  double modulus = solid.bulk_modulus_Pa() + 4.0 / 3.0 * solid.shear_modulus_Pa();
  set_element_rebar(m, mesh, section, e, materials.rebar[region], rho);
  m.element_density[e] = rho;
  // Dilatational wave speed of the host solid for the bulk viscosity: the bars do not
  // resist a volume change through the layer, so their modulus must not raise the
  // viscous pressure (with it the belt viscosity was ~1.4 x critical at the step).
  m.element_wave_speed[e] = std::sqrt(modulus / rho);
  // Bound of the element's highest frequency (exact for a cube, conservative when
  // distorted): L_e / c would overestimate the critical step of a one-point hex by up
  // to sqrt(3) for nearly incompressible rubber. The rebar term is directional: the
  // bars stiffen the layer along themselves, not through its thickness.
  // Linear bulk viscosity damps the highest mode by xi = b1: the step shrinks by
  // sqrt(1 + xi^2) - xi (Abaqus Analysis User's Guide, "Explicit dynamic analysis").
  const double b1 = options.bulk_viscosity_linear;
  return options.time_step_safety * (std::sqrt(1.0 + b1 * b1) - b1) *
         hex8_stable_time_step_s(m.reference[e], rho, solid.bulk_modulus_Pa(), solid.shear_modulus_Pa(),
                                 materials.hourglass_coefficient, m.rebar_modulus_Pa[e] * m.rebar_fraction[e],
                                 m.rebar_direction[e]);
}

// Every element's properties and stable step (infinite for a rigid one), the
// model's smallest and each region's.
std::vector<double> set_elements(Model3d& m, const Mesh3D& mesh, const CrossSection& section) {
  const std::size_t ne = mesh.hexes.size(), nn = mesh.nodes.size();
  std::vector<char> rim_node(nn, 0);
  for (int n : mesh.rim_nodes) rim_node[n] = 1;
  double min_dt = std::numeric_limits<double>::infinity();
  std::vector<double> element_dt(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    element_dt[e] = set_element(m, mesh, section, e);
    // A hex whose nodes all move with the rigid rim (the tied bead) never deforms: it
    // sets no step and is not mass scaled.
    bool rigid = true;
    for (int a = 0; a < 8; ++a) rigid = rigid && rim_node[mesh.hexes[e][a]];
    if (rigid) {
      element_dt[e] = std::numeric_limits<double>::infinity();
      continue;
    }
    if (element_dt[e] < min_dt) min_dt = element_dt[e], m.dt_controlling_element = static_cast<int>(e);
    double& region_dt = m.region_min_dt_s[m.material[e]];
    if (region_dt == 0.0 || element_dt[e] < region_dt) region_dt = element_dt[e];
  }
  m.unscaled_dt_s = min_dt;
  m.stable_dt_s = min_dt;
  return element_dt;
}

// Mass scaling (Abaqus *FIXED MASS SCALING, DT=target): raise the density of every
// element whose stable step is below the target so that it reaches the target.
// The element masses are lumped on their nodes, an eighth on each.
void scale_and_lump_masses(Model3d& m, const Mesh3D& mesh, const std::vector<double>& element_dt) {
  const Model3dOptions& options = m.options;
  const std::size_t ne = mesh.hexes.size();
  double physical = 0.0, scaled = 0.0;
  for (std::size_t e = 0; e < ne; ++e) {
    const double mass = m.element_density[e] * m.reference[e].volume_m3;
    physical += mass;
    if (options.mass_scaling_target_dt_s > 0.0 && element_dt[e] < options.mass_scaling_target_dt_s) {
      const double f = options.mass_scaling_target_dt_s / element_dt[e];
      m.element_density[e] *= f * f;
      m.element_wave_speed[e] /= f;
    }
    const double me = m.element_density[e] * m.reference[e].volume_m3;
    scaled += me;
    m.region_added_mass_kg[m.material[e]] += me - mass;
    for (int a = 0; a < 8; ++a) m.node_mass_kg[mesh.hexes[e][a]] += me / 8.0;
  }
  // Every scaled element now has the target step; the others had more.
  if (options.mass_scaling_target_dt_s > 0.0)
    m.stable_dt_s = std::max(m.unscaled_dt_s, options.mass_scaling_target_dt_s);
  m.physical_mass_kg = physical;
  m.added_mass_kg = scaled - physical;
}

// Surfaces: pressure on the inner liner; road contact candidates on the outside.
void set_surfaces(Model3d& m, const Mesh3D& mesh) {
  const std::size_t nn = mesh.nodes.size();
  std::vector<double> area(nn, 0.0);
  std::vector<char> outer(nn, 0);
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    const auto& facet = mesh.facets[f];
    if (facet.tag == SurfaceTag::inner_liner) m.pressure_facets.push_back(static_cast<int>(f));
    if (!touches_ground(facet.tag)) continue;
    const auto& x = mesh.nodes;
    const auto& q = facet.nodes;
    // A node's footprint is its share of its facets projected on the road (the
    // footprint of thesis Figure 4.3): a groove or sipe wall, normal to the road,
    // adds nothing, so a block tread's area is its land, not its land and walls.
    const Eigen::Vector3d centre = 0.25 * (x[q[0]] + x[q[1]] + x[q[2]] + x[q[3]]);
    const Eigen::Vector3d facet_area = cosim::quad_area_vector(x[q[0]], x[q[1]], x[q[2]], x[q[3]]);
    const double a = std::abs(facet_area.dot(ground_facing(mesh, centre)));
    for (int n : facet.nodes) area[n] += a / 4.0, outer[n] = 1;
  }
  m.is_rim_node.assign(nn, 0);
  for (int n : mesh.rim_nodes) m.is_rim_node[n] = 1;
  for (std::size_t i = 0; i < nn; ++i)
    if (outer[i] && !m.is_rim_node[i]) {
      m.contact_nodes.push_back(static_cast<int>(i));
      m.contact_node_area_m2.push_back(area[i]);
    }
}

// node -> force offsets (CSR), for a gather that gives the same sums on any thread count.
void set_node_force_offsets(Model3d& m) {
  const std::size_t ne = m.mesh.hexes.size(), nn = m.mesh.nodes.size();
  std::vector<int> count(nn + 1, 0);
  for (const auto& h : m.mesh.hexes)
    for (int a : h) ++count[a + 1];
  for (std::size_t i = 0; i < nn; ++i) count[i + 1] += count[i];
  m.node_hex_begin = count;
  m.node_hex_entries.resize(count[nn]);
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (std::size_t e = 0; e < ne; ++e)
    for (int a = 0; a < 8; ++a)
      m.node_hex_entries[fill[m.mesh.hexes[e][a]]++] = static_cast<int>(m.hex_batches.force_offset(e, a));
}

}  // namespace

Model3d build_model3d(Mesh3D mesh, const TyreMaterials& materials, const CrossSection& section,
                      const Model3dOptions& options) {
  Model3d m;
  m.options = options;
  m.materials = materials;
  const std::size_t ne = mesh.hexes.size(), nn = mesh.nodes.size();
  m.reference.resize(ne);
  m.material.resize(ne);
  m.rebar_direction.assign(ne, Eigen::Vector3d::Zero());
  m.rebar_fraction.assign(ne, 0.0);
  m.rebar_modulus_Pa.assign(ne, 0.0);
  m.element_density.resize(ne);
  m.element_wave_speed.resize(ne);
  m.node_mass_kg.assign(nn, 0.0);
  const std::vector<double> element_dt = set_elements(m, mesh, section);
  scale_and_lump_masses(m, mesh, element_dt);
  set_surfaces(m, mesh);
  m.mesh = std::move(mesh);
  m.hex_batches = build_hex8_batches(m);
  set_node_force_offsets(m);
  return m;
}

}  // namespace tyre_fe
