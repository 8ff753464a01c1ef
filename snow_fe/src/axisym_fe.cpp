// Axisymmetric quads with B-bar and the snow's mdpc_update; see axisym_fe.hpp.
#include "snow_fe/axisym_fe.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "cosim/error.hpp"

namespace snow_fe::axisym {
namespace {

// The snow's material model is the particles' (snow_sph/mdpc.hpp).
using snow_sph::MdpcParameters;
using snow_sph::MdpcStepResult;
using snow_sph::mdpc_update;

// Node a of a quad: natural coordinates (corner order (i,j), (i+1,j), (i+1,j+1), (i,j+1)).
constexpr std::array<double, 4> kXi{-1.0, 1.0, 1.0, -1.0};
constexpr std::array<double, 4> kEta{-1.0, -1.0, 1.0, 1.0};
const double kGauss = 1.0 / std::sqrt(3.0);

std::array<int, 4> element_nodes(const Mesh& m, int e) {
  const int i = e % m.elements_r(), j = e / m.elements_r();
  return {m.node(i, j), m.node(i + 1, j), m.node(i + 1, j + 1), m.node(i, j + 1)};
}

// The element's node indices and their current (r, z).
struct Corners {
  std::array<int, 4> nodes;
  std::array<double, 4> r, z;
};
Corners corners(const Mesh& m, int e) {
  Corners c{element_nodes(m, e), {}, {}};
  for (int a = 0; a < 4; ++a) c.r[a] = m.r_m[c.nodes[a]], c.z[a] = m.z_m[c.nodes[a]];
  return c;
}

// Shape functions and their (r, z) derivatives at Gauss point g of a quad with
// corners (r[a], z[a]); det is det J (the Gauss weight is 1).
struct PointShape {
  std::array<double, 4> N, dN_dr, dN_dz;
  double r, det;
};

PointShape point_shape(const std::array<double, 4>& r, const std::array<double, 4>& z, int g) {
  const double xi = kXi[g] * kGauss, eta = kEta[g] * kGauss;
  PointShape s{};
  std::array<double, 4> dxi{}, deta{};
  double r_xi = 0, r_eta = 0, z_xi = 0, z_eta = 0;
  for (int a = 0; a < 4; ++a) {
    s.N[a] = 0.25 * (1 + kXi[a] * xi) * (1 + kEta[a] * eta);
    dxi[a] = 0.25 * kXi[a] * (1 + kEta[a] * eta);
    deta[a] = 0.25 * kEta[a] * (1 + kXi[a] * xi);
    r_xi += r[a] * dxi[a], r_eta += r[a] * deta[a];
    z_xi += z[a] * dxi[a], z_eta += z[a] * deta[a];
    s.r += s.N[a] * r[a];
  }
  s.det = r_xi * z_eta - r_eta * z_xi;
  const double inv = s.det != 0.0 ? 1.0 / s.det : 0.0;
  for (int a = 0; a < 4; ++a) {
    s.dN_dr[a] = (z_eta * dxi[a] - z_xi * deta[a]) * inv;
    s.dN_dz[a] = (-r_eta * dxi[a] + r_xi * deta[a]) * inv;
  }
  return s;
}

// The integration weight's radius (2 pi r dA per 2 pi: r) and a hoop term
// value / r (the hoop strain u_r / r, its operator N_a / r); in plane strain
// the weight is dA and there is no hoop term.
double radius_weight(const Mesh& m, double r) { return m.geometry == Geometry::plane_strain ? 1.0 : r; }
double hoop(const Mesh& m, double value, double r) { return m.geometry == Geometry::plane_strain ? 0.0 : value / r; }

void check_lines(const std::vector<double>& lines, const char* name, double lowest) {
  if (lines.size() < 2) throw cosim::Error(std::string("axisymmetric mesh: ") + name + " needs at least two lines");
  if (!(lines[0] >= lowest)) throw cosim::Error(std::string("axisymmetric mesh: ") + name + " starts below its lowest value");
  for (std::size_t k = 1; k < lines.size(); ++k)
    if (!(lines[k] > lines[k - 1]))
      throw cosim::Error(std::string("axisymmetric mesh: ") + name + " must increase strictly (line " +
                         std::to_string(k) + ")");
}

}  // namespace

Mesh make_mesh(const std::vector<double>& r_lines, const std::vector<double>& z_lines, double density,
               const MdpcParameters& params, Geometry geometry) {
  check_lines(r_lines, "r_lines", 0.0);
  check_lines(z_lines, "z_lines", -1e300);
  if (!(density > 0.0)) throw cosim::Error("axisymmetric mesh: density must be positive");
  Mesh m;
  m.nodes_r = static_cast<int>(r_lines.size());
  m.nodes_z = static_cast<int>(z_lines.size());
  m.density_kg_per_m3 = density;
  m.geometry = geometry;
  const auto n = static_cast<std::size_t>(m.nodes());
  m.r_m.resize(n), m.z_m.resize(n);
  for (int j = 0; j < m.nodes_z; ++j)
    for (int i = 0; i < m.nodes_r; ++i) m.r_m[m.node(i, j)] = r_lines[i], m.z_m[m.node(i, j)] = z_lines[j];
  m.v_r.assign(n, 0.0), m.v_z.assign(n, 0.0), m.mass_kg_per_rad.assign(n, 0.0);
  m.hold_r.assign(n, 0), m.hold_z.assign(n, 0);
  m.stress_Pa.assign(4 * static_cast<std::size_t>(m.elements()), Eigen::Matrix3d::Zero());
  m.eps_vol_pl.assign(4 * static_cast<std::size_t>(m.elements()), params.initial_cap_volumetric_plastic_strain);
  // Row-sum lumping of the consistent mass: m_a = rho integral N_a r dA.
  for (int e = 0; e < m.elements(); ++e) {
    const auto [nodes, r, z] = corners(m, e);
    for (int g = 0; g < 4; ++g) {
      const PointShape s = point_shape(r, z, g);
      for (int a = 0; a < 4; ++a) m.mass_kg_per_rad[nodes[a]] += density * s.N[a] * radius_weight(m, s.r) * s.det;
    }
  }
  return m;
}

Eigen::Vector2d gauss_point_position(const Mesh& m, int e, int g) {
  const auto [nodes, r, z] = corners(m, e);
  const PointShape s = point_shape(r, z, g);
  double zg = 0.0;
  for (int a = 0; a < 4; ++a) zg += s.N[a] * z[a];
  return {s.r, zg};
}

ElementPassResult element_pass(Mesh& m, const MdpcParameters& params, double dt, std::vector<double>& f_r,
                               std::vector<double>& f_z) {
  const auto n = static_cast<std::size_t>(m.nodes());
  f_r.assign(n, 0.0), f_z.assign(n, 0.0);
  ElementPassResult result;
  for (int e = 0; e < m.elements(); ++e) {
    const auto [nodes, r, z] = corners(m, e);
    std::array<double, 4> vr{}, vz{};
    for (int a = 0; a < 4; ++a) vr[a] = m.v_r[nodes[a]], vz[a] = m.v_z[nodes[a]];
    std::array<PointShape, 4> s;
    std::array<double, 4> weight{};  // current volume per radian of each point: r det J
    double volume = 0.0, area = 0.0;
    // Mean-dilatation operator b_bar_a = (1/V) sum_g w_g (dN_a/dr + N_a/r, dN_a/dz).
    std::array<double, 4> bbar_r{}, bbar_z{};
    for (int g = 0; g < 4; ++g) {
      s[g] = point_shape(r, z, g);
      weight[g] = radius_weight(m, s[g].r) * s[g].det;
      volume += weight[g], area += s[g].det;
      for (int a = 0; a < 4; ++a) {
        bbar_r[a] += weight[g] * (s[g].dN_dr[a] + hoop(m, s[g].N[a], s[g].r));
        bbar_z[a] += weight[g] * s[g].dN_dz[a];
      }
    }
    for (int g = 0; g < 4; ++g)
      result.smallest_jacobian_ratio =
          std::min(result.smallest_jacobian_ratio, area > 0.0 ? 4.0 * s[g].det / area : -1.0);
    if (!(area > 0.0) || !(volume > 0.0)) continue;  // inverted: the caller stops the run
    double mean_dilatation = 0.0;
    for (int a = 0; a < 4; ++a) {
      bbar_r[a] /= volume, bbar_z[a] /= volume;
      mean_dilatation += bbar_r[a] * vr[a] + bbar_z[a] * vz[a];
    }
    for (int g = 0; g < 4; ++g) {
      const PointShape& p = s[g];
      const std::size_t q = 4 * static_cast<std::size_t>(e) + g;
      Eigen::Matrix3d& sigma = m.stress_Pa[q];
      if (dt > 0.0) {
        double drr = 0, dvr_dz = 0, dvz_dr = 0, dzz = 0, vr_point = 0;
        for (int a = 0; a < 4; ++a) {
          drr += p.dN_dr[a] * vr[a], dvr_dz += p.dN_dz[a] * vr[a];
          dvz_dr += p.dN_dr[a] * vz[a], dzz += p.dN_dz[a] * vz[a];
          vr_point += p.N[a] * vr[a];
        }
        Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
        D(0, 0) = drr, D(1, 1) = dzz, D(2, 2) = hoop(m, vr_point, p.r);
        D(0, 1) = D(1, 0) = 0.5 * (dvr_dz + dvz_dr);
        D.diagonal().array() += (mean_dilatation - D.trace()) / 3.0;  // B-bar
        Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
        W(0, 1) = 0.5 * (dvr_dz - dvz_dr), W(1, 0) = -W(0, 1);
        sigma += dt * (W * sigma - sigma * W);  // Jaumann rotation
        const MdpcStepResult step = mdpc_update(params, dt * D, sigma, m.eps_vol_pl[q]);
        result.plastic_work_J_per_rad += step.plastic_work_density_J_per_m3 * weight[g];
      }
      // f_a = -w_g B_bar_a^T sigma, with B_bar = B + (b_bar - b) (x) m / 3.
      const double mean_stress = sigma.trace() / 3.0;
      for (int a = 0; a < 4; ++a) {
        const double b_r = p.dN_dr[a] + hoop(m, p.N[a], p.r), b_z = p.dN_dz[a];
        f_r[nodes[a]] -= weight[g] * (p.dN_dr[a] * sigma(0, 0) + p.dN_dz[a] * sigma(0, 1) +
                                      hoop(m, p.N[a], p.r) * sigma(2, 2) + (bbar_r[a] - b_r) * mean_stress);
        f_z[nodes[a]] -= weight[g] * (p.dN_dr[a] * sigma(0, 1) + p.dN_dz[a] * sigma(1, 1) +
                                      (bbar_z[a] - b_z) * mean_stress);
      }
    }
  }
  return result;
}

void nodal_accelerations(const Mesh& m, const std::vector<double>& f_r, const std::vector<double>& f_z, double g,
                         std::vector<double>& a_r, std::vector<double>& a_z) {
  const auto n = static_cast<std::size_t>(m.nodes());
  a_r.resize(n), a_z.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    a_r[k] = m.hold_r[k] ? 0.0 : f_r[k] / m.mass_kg_per_rad[k];
    a_z[k] = m.hold_z[k] ? 0.0 : f_z[k] / m.mass_kg_per_rad[k] - g;
  }
}

void advance_nodes(Mesh& m, const std::vector<double>& a_r, const std::vector<double>& a_z, double dt_v, double dt,
                   double damping) {
  const double keep = 1.0 / (1.0 + damping * dt_v);
  for (std::size_t k = 0; k < static_cast<std::size_t>(m.nodes()); ++k) {
    if (!m.hold_r[k]) m.v_r[k] = (m.v_r[k] + dt_v * a_r[k]) * keep;
    if (!m.hold_z[k]) m.v_z[k] = (m.v_z[k] + dt_v * a_z[k]) * keep;
    m.r_m[k] += dt * m.v_r[k], m.z_m[k] += dt * m.v_z[k];
  }
}

double stable_time_step(const Mesh& m, double wave_speed, double fraction) {
  double smallest = 1e300;
  for (int e = 0; e < m.elements(); ++e) {
    const auto [nodes, r, z] = corners(m, e);
    const double area = 0.5 * ((r[0] - r[2]) * (z[1] - z[3]) - (r[1] - r[3]) * (z[0] - z[2]));
    const double d1 = std::hypot(r[2] - r[0], z[2] - z[0]), d2 = std::hypot(r[3] - r[1], z[3] - z[1]);
    smallest = std::min(smallest, std::sqrt(2.0) * std::abs(area) / std::max(d1, d2));
  }
  return fraction * smallest / wave_speed;
}

double kinetic_energy_J_per_rad(const Mesh& m) {
  double sum = 0.0;
  for (int k = 0; k < m.nodes(); ++k)
    sum += 0.5 * m.mass_kg_per_rad[k] * (m.v_r[k] * m.v_r[k] + m.v_z[k] * m.v_z[k]);
  return sum;
}

double elastic_energy_J_per_rad(const Mesh& m, const MdpcParameters& params) {
  const double K = params.bulk_modulus_Pa(), G = params.shear_modulus_Pa();
  double sum = 0.0;
  for (int e = 0; e < m.elements(); ++e) {
    const auto [nodes, r, z] = corners(m, e);
    for (int g = 0; g < 4; ++g) {
      const PointShape s = point_shape(r, z, g);
      const Eigen::Matrix3d& sigma = m.stress_Pa[4 * static_cast<std::size_t>(e) + g];
      const double p = -sigma.trace() / 3.0;
      const Eigen::Matrix3d dev = sigma + p * Eigen::Matrix3d::Identity();
      const double q2 = 1.5 * dev.squaredNorm();
      sum += (p * p / (2.0 * K) + q2 / (6.0 * G)) * radius_weight(m, s.r) * s.det;
    }
  }
  return sum;
}

}  // namespace snow_fe::axisym
