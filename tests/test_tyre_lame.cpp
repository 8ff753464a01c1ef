// The axisymmetric dynamic-relaxation solver (tyre_fe/axisym.hpp) on Lame's
// pressurised thick cylinder in plane strain (Timoshenko & Goodier, Theory of
// Elasticity, 3rd ed., 1970, section 28): inner radius a, outer b, internal pressure p,
//   u(r)       = (1 + nu) a^2 p / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r),
//   sigma_r    = p a^2 / (b^2 - a^2) (1 - b^2 / r^2),
//   sigma_th   = p a^2 / (b^2 - a^2) (1 + b^2 / r^2),
//   sigma_y    = nu (sigma_r + sigma_th)          (plane strain: every node's y held).
// Two materials: the tread rubber of thesis Table 5.4 ($COSIM_TEST_DATA/rubber_yeoh.csv)
// with K0 / mu0 = 1000 (nu = 0.4995), and St. Venant-Kirchhoff with nu = 0.3. The
// pressure keeps strains below 5e-4 so that the finite-strain response is linear to
// well below the tolerances.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tyre_fe/axisym.hpp"

namespace {

using namespace tyre_fe;

// Discretisation error of 16 one-point quads through the wall: O((h / a)^2) = 0.4 % with
// h / a = 0.0625 (observed 0.02-0.08 % on the displacements). The centroid stresses are
// element means of a field varying as 1/r^2 compared at the centroid radius, which
// adds O((h / r)^2) again (observed <= 0.17 %). Residual tolerance 1e-6.
constexpr double kDisplacementRelTol = 0.005;
constexpr double kHoopStressRelTol = 0.01;
constexpr double kOtherStressTol = 0.01;  // times p (sigma_r and sigma_y are O(p))

constexpr double kA = 0.1, kB = 0.2, kHeight = 0.01;
constexpr int kRadial = 16;

std::string data_dir() {
  const char* env = std::getenv("COSIM_TEST_DATA");
  return (env && *env) ? std::string(env) : std::string("tests/data/reference");
}

// density, C10, C20, C30 of the tread (thesis Table 5.4).
std::vector<double> tread_row() {
  const std::string path = data_dir() + "/rubber_yeoh.csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path + " (set COSIM_TEST_DATA)");
  std::string line;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::getline(ss, cell, ',');
    if (cell != "tread") continue;
    std::vector<double> values;
    while (std::getline(ss, cell, ',')) values.push_back(std::stod(cell));
    return values;
  }
  throw std::runtime_error("no tread row in " + path);
}

// n_radial x 1 quads on a <= r <= b, 0 <= y <= height; pressure on the r = a edges.
CrossSection thick_cylinder() {
  CrossSection s;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= kRadial; ++i)
      s.nodes.emplace_back(kA + (kB - kA) * i / kRadial, kHeight * j);
  for (int i = 0; i < kRadial; ++i) {
    s.quads.push_back({i, i + 1, kRadial + 2 + i, kRadial + 1 + i});
    s.quad_region.push_back(Region::tread);
  }
  s.inner_liner_edges.push_back({0, 3});  // nodes 3 -> 0 of quad 0: the r = a edge
  return s;
}

struct Lame {
  double p, E, nu;
  double c() const { return p * kA * kA / (kB * kB - kA * kA); }
  double u(double r) const { return (1 + nu) * c() / E * ((1 - 2 * nu) * r + kB * kB / r); }
  double sigma_r(double r) const { return c() * (1 - kB * kB / (r * r)); }
  double sigma_theta(double r) const { return c() * (1 + kB * kB / (r * r)); }
};

void check_against_lame(const SolidMaterial& material, const Lame& lame) {
  const CrossSection section = thick_cylinder();
  TyreMaterials materials;
  materials.solid[static_cast<int>(Region::tread)] = material;
  AxisymLoadCase load;
  load.pressure_Pa = lame.p;
  load.fixed_nodes = std::vector<int>{};
  for (int n = 0; n < static_cast<int>(section.nodes.size()); ++n) load.fixed_y_nodes.push_back(n);

  const AxisymResult result = solve_axisym(section, materials, load);
  ASSERT_TRUE(result.converged) << "residual " << result.residual_ratio << " after " << result.steps;
  std::printf("  %ld steps of %.3g s, residual ratio %.2e, hourglass/strain energy %.1e\n",
              result.steps, result.time_step_s, result.residual_ratio,
              result.hourglass_energy_J_per_rad / result.strain_energy_J_per_rad);

  for (int i : {0, kRadial}) {
    const double r = section.nodes[i][0];
    const double expected = lame.u(r);
    for (int node : {i, i + kRadial + 1}) {  // y = 0 and y = height
      const double u = result.nodes[node][0] - r;
      if (node == i)
        std::printf("  u(%.2f) = %.6e m, Lame %.6e, error %+.3f %%\n", r, u, expected, 100 * (u / expected - 1));
      EXPECT_NEAR(u, expected, kDisplacementRelTol * expected);
    }
  }
  for (int q : {0, kRadial / 2, kRadial - 1}) {
    double R = 0.0;
    for (int n : section.quads[q]) R += 0.25 * section.nodes[n][0];
    const Eigen::Matrix3d& sigma = result.quad_stress_Pa[q];
    const double hoop = lame.sigma_theta(R), radial = lame.sigma_r(R);
    std::printf("  r = %.4f: sigma_th %.5e (Lame %.5e, %+.3f %%), sigma_r %.4e (%.4e), sigma_y %.4e (%.4e)\n",
                R, sigma(2, 2), hoop, 100 * (sigma(2, 2) / hoop - 1), sigma(0, 0), radial,
                sigma(1, 1), lame.nu * (radial + hoop));
    EXPECT_NEAR(sigma(2, 2), hoop, kHoopStressRelTol * hoop);
    EXPECT_NEAR(sigma(0, 0), radial, kOtherStressTol * lame.p);
    EXPECT_NEAR(sigma(1, 1), lame.nu * (radial + hoop), kOtherStressTol * lame.p);
    EXPECT_NEAR(sigma(0, 1), 0.0, kOtherStressTol * lame.p);
  }
}

TEST(TyreLame, NearlyIncompressibleYeohRubber) {
  const auto row = tread_row();
  SolidMaterial rubber;
  rubber.kind = SolidMaterial::Kind::yeoh;
  rubber.yeoh.density_kg_per_m3 = row.at(0);
  rubber.yeoh.C10_Pa = row.at(1);
  rubber.yeoh.C20_Pa = row.at(2);
  rubber.yeoh.C30_Pa = row.at(3);
  const double mu = rubber.yeoh.initial_shear_modulus_Pa(), K = 1000 * mu;
  rubber.yeoh.bulk_modulus_Pa = K;
  // Small-strain constants of the Yeoh solid: mu0 = 2 C10, K0.
  const double E = 9 * K * mu / (3 * K + mu), nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  check_against_lame(rubber, Lame{1.0e3, E, nu});
}

TEST(TyreLame, CompressibleStVenantKirchhoff) {
  SolidMaterial solid;
  solid.kind = SolidMaterial::Kind::elastic;
  solid.elastic = ElasticSolid{5.0e6, 0.3, 1000.0};
  check_against_lame(solid, Lame{1.0e3, 5.0e6, 0.3});
}

}  // namespace
