// The batched hexahedron forces (tyre_fe/hex8_batch.hpp) against the one-element
// kernels of elements.cpp and materials.cpp, which test_tyre_elements and
// test_tyre_materials check against the patch test, closed forms and the energy
// gradient. The batch rearranges the same formulas (positions relative to node 0,
// hourglass modes from hX instead of stored gamma, J^(-1/3) by Newton's iteration),
// so each lane must agree with the one-element result to rounding; the bulk
// viscosity, which has no one-element kernel, is checked against its closed form
// for a uniform dilatation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "tyre_fe/elements.hpp"
#include "tyre_fe/hex8_batch.hpp"
#include "tyre_fe/materials.hpp"

namespace {

using namespace tyre_fe;

constexpr double kHourglass = 0.05;
// Both sides are exact in real arithmetic and take a few hundred operations per force;
// the hourglass modes cancel to about 1e-3 of the element size in the lanes below, so
// rounding (1.1e-16) can reach ~1e-12 of the largest nodal force. 1e-10 leaves room for
// that and still fails for any wrong term (the smallest term checked, the hourglass
// force, is ~1e-4 of the largest force here).
constexpr double kAgreement = 1e-10;

SolidMaterial rubber() {
  SolidMaterial m;  // arbitrary rubber-like constants (not reference data)
  m.yeoh.C10_Pa = 0.5e6;
  m.yeoh.C20_Pa = -0.1e6;
  m.yeoh.C30_Pa = 0.03e6;
  m.yeoh.bulk_modulus_Pa = 100.0 * m.yeoh.initial_shear_modulus_Pa();
  m.yeoh.density_kg_per_m3 = 1100.0;
  return m;
}

SolidMaterial steel() {
  SolidMaterial m;
  m.kind = SolidMaterial::Kind::elastic;
  m.elastic.youngs_modulus_Pa = 200e9;
  m.elastic.poisson_ratio = 0.3;
  m.elastic.density_kg_per_m3 = 7850.0;
  return m;
}

using Hex = std::array<std::array<double, 3>, 8>;

// A 10 mm hexahedron, each node moved by up to 1.5 mm (deterministic), centred far
// from the origin as a tyre's elements are (0.3 m).
Hex distorted_hex(int seed) {
  constexpr int kXi[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
  constexpr int kEta[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
  constexpr int kZeta[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  Hex X;
  for (int i = 0; i < 8; ++i) {
    const double natural[3] = {double(kXi[i]), double(kEta[i]), double(kZeta[i])};
    for (int k = 0; k < 3; ++k)
      X[i][k] = 0.3 * (k == 2) + 0.005 * natural[k] + 0.0015 * std::sin(1.7 * i + 2.3 * k + 0.4 + seed);
  }
  return X;
}

// x = A (X - c) + c + t plus an hourglass-like wobble of the nodes.
Hex deform(const Hex& X, const Eigen::Matrix3d& A, double wobble_m, int seed) {
  Hex x;
  const Eigen::Vector3d c(0.0, 0.0, 0.3), t(0.01, -0.02, 0.005);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p = A * (Eigen::Vector3d(X[i][0], X[i][1], X[i][2]) - c) + c + t;
    for (int k = 0; k < 3; ++k) x[i][k] = p[k] + wobble_m * std::cos(0.9 * i + 1.3 * k + seed);
  }
  return x;
}

struct Reference {
  double f[8][3];
  double energy_J, hourglass_J;
};

Reference one_element(const Hex& X, const Hex& x, const SolidMaterial& m, const Eigen::Vector3d& a0,
                      double rebar_modulus_Pa) {
  double Xa[8][3], xa[8][3];
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) Xa[i][k] = X[i][k], xa[i][k] = x[i][k];
  const Hex8Reference ref = hex8_reference(Xa);
  const Eigen::Matrix3d F = hex8_deformation_gradient(ref, xa);
  double W = 0.0;
  Eigen::Matrix3d tau = kirchhoff_stress(m, F, &W);
  if (rebar_modulus_Pa > 0.0) W += add_rebar_kirchhoff_stress(a0, 1.0, rebar_modulus_Pa, F, tau);
  Reference r;
  r.hourglass_J = hex8_internal_forces(ref, xa, F, tau, kHourglass, m.shear_modulus_Pa(), r.f);
  r.energy_J = W * ref.volume_m3 + r.hourglass_J;
  return r;
}

// Four lanes with their own geometry and deformation, evaluated in one batch.
struct Lanes {
  Hex X[kHexLanes], x[kHexLanes];
  Eigen::Vector3d a0[kHexLanes];
  std::vector<double> position[3], velocity[3];
  Hex8Batch batch{};
  std::vector<double> force = std::vector<double>(24 * kHexLanes, 0.0);
  std::vector<double> energy = std::vector<double>(kHexLanes, -1.0), hourglass = energy, power = energy;
  Hex8Reference reference[kHexLanes];

  void build(const SolidMaterial& m, double rebar_modulus_Pa, double bulk_viscosity_Pa_s) {
    batch.kind = m.kind == SolidMaterial::Kind::yeoh ? Hex8Batch::Kind::yeoh : Hex8Batch::Kind::elastic;
    batch.has_rebar = rebar_modulus_Pa > 0.0;
    for (int k = 0; k < 3; ++k) position[k].assign(8 * kHexLanes, 0.0), velocity[k].assign(8 * kHexLanes, 0.0);
    for (int l = 0; l < kHexLanes; ++l) {
      double Xa[8][3];
      Hex8LaneInput in;
      for (int i = 0; i < 8; ++i) {
        in.nodes[i] = 8 * l + i;
        for (int k = 0; k < 3; ++k) Xa[i][k] = X[l][i][k], position[k][8 * l + i] = x[l][i][k];
      }
      reference[l] = hex8_reference(Xa);
      in.reference = &reference[l];
      in.reference_position_m = Xa;
      in.material = &m;
      in.hourglass_coefficient = kHourglass;
      in.bulk_viscosity_Pa_s = bulk_viscosity_Pa_s;
      in.rebar_direction = a0[l];
      in.rebar_modulus_Pa = rebar_modulus_Pa;
      in.element = l;
      set_hex8_lane(batch, l, in);
    }
  }
  void run(bool viscous) {
    const double* const pos[3] = {position[0].data(), position[1].data(), position[2].data()};
    const double* const vel[3] = {velocity[0].data(), velocity[1].data(), velocity[2].data()};
    hex8_batch_forces(batch, pos, vel, viscous, force.data(), {energy.data(), hourglass.data(), power.data()});
  }
  double f(int lane, int node, int axis) const { return force[(node * 3 + axis) * kHexLanes + lane]; }
};

void expect_lanes_match(const Lanes& lanes, const SolidMaterial& m, double rebar_modulus_Pa) {
  for (int l = 0; l < kHexLanes; ++l) {
    const Reference r = one_element(lanes.X[l], lanes.x[l], m, lanes.a0[l], rebar_modulus_Pa);
    double largest = 0.0;
    for (auto& node : r.f)
      for (double v : node) largest = std::max(largest, std::fabs(v));
    ASSERT_GT(largest, 0.0);
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(lanes.f(l, i, k), r.f[i][k], kAgreement * largest) << "lane " << l << " node " << i << " axis " << k;
    EXPECT_NEAR(lanes.energy[l], r.energy_J, kAgreement * std::fabs(r.energy_J)) << "lane " << l;
    EXPECT_NEAR(lanes.hourglass[l], r.hourglass_J, 1e-9 * std::fabs(r.hourglass_J)) << "lane " << l;
    EXPECT_GT(r.hourglass_J, 0.0);
  }
}

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// Deformations of the four lanes: stretch with shear, a 90-degree rotation of a
// sheared state, volumetric compression to J = 0.6 (outside the reach of the Newton
// guess, so cbrt finishes it) and a mild tension.
void set_deformations(Lanes& lanes, double scale) {
  Eigen::Matrix3d A[kHexLanes];
  A[0] << 1.2, 0.1, 0.0, 0.1, 0.9, 0.05, 0.0, 0.05, 1.1;
  A[1] = A[0];  // rotated below
  A[2] = std::cbrt(0.6) * Eigen::Matrix3d::Identity();
  A[3] << 1.05, 0.0, 0.02, 0.0, 1.0, 0.0, 0.0, 0.0, 0.97;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (int l = 0; l < kHexLanes; ++l) {
    Eigen::Matrix3d Al = I + scale * (A[l] - I);
    if (l == 1) Al = rotation(1.5707963267948966, Eigen::Vector3d(1, 1, 0)) * Al;
    lanes.X[l] = distorted_hex(l);
    lanes.x[l] = deform(lanes.X[l], Al, 2e-5 * scale, l);
    lanes.a0[l] = Eigen::Vector3d(std::cos(0.4 * l), std::sin(0.4 * l), 0.3).normalized();
  }
}

TEST(Hex8Batch, YeohLanesMatchTheOneElementKernels) {
  const SolidMaterial m = rubber();
  Lanes lanes;
  set_deformations(lanes, 1.0);
  lanes.build(m, 0.0, 0.0);
  lanes.run(false);
  expect_lanes_match(lanes, m, 0.0);
}

TEST(Hex8Batch, YeohWithRebarLanesMatch) {
  const SolidMaterial m = rubber();
  Lanes lanes;
  set_deformations(lanes, 1.0);
  lanes.build(m, 0.15 * 200e9, 0.0);
  lanes.run(false);
  expect_lanes_match(lanes, m, 0.15 * 200e9);
}

TEST(Hex8Batch, ElasticWithRebarLanesMatch) {
  const SolidMaterial m = steel();
  Lanes lanes;
  set_deformations(lanes, 0.01);  // steel: small strains (a large rotation in lane 1)
  lanes.build(m, 0.05 * 200e9, 0.0);
  lanes.run(false);
  expect_lanes_match(lanes, m, 0.05 * 200e9);
}

// A uniform dilatation rate v = r (X - c) on the undeformed element: tr D = 3 r, so the
// viscous pressure is -b 3 r (b = b1 rho c L_e), the nodal forces are V b 3 r B_i
// (f_i = V sigma B_i with sigma = b tr(D) I) and the power is -V b (3 r)^2. The elastic
// and hourglass parts are zero at x = X.
TEST(Hex8Batch, BulkViscosityOfAUniformDilatation) {
  const SolidMaterial m = rubber();
  const double b = 2.5e3, rate = 40.0;  // Pa s, 1/s
  Lanes lanes;
  for (int l = 0; l < kHexLanes; ++l)
    lanes.X[l] = lanes.x[l] = distorted_hex(l), lanes.a0[l] = Eigen::Vector3d::UnitX();
  lanes.build(m, 0.0, b);
  for (int l = 0; l < kHexLanes; ++l)
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) lanes.velocity[k][8 * l + i] = rate * (lanes.X[l][i][k] - (k == 2 ? 0.3 : 0.0));
  lanes.run(true);
  for (int l = 0; l < kHexLanes; ++l) {
    const Hex8Reference& ref = lanes.reference[l];
    const double pressure_scale = ref.volume_m3 * b * 3.0 * rate;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(lanes.f(l, i, k), pressure_scale * ref.dNdX[i][k], 1e-10 * pressure_scale / 0.01);
    EXPECT_NEAR(lanes.power[l], -ref.volume_m3 * b * 9.0 * rate * rate, 1e-12 * ref.volume_m3 * b * 9.0 * rate * rate);
    // x = X: I1b - 3 is zero to the rounding of a sum of magnitude 3 (a few 1e-16).
    EXPECT_NEAR(lanes.energy[l], 0.0, 1e-14 * m.yeoh.C10_Pa * ref.volume_m3);
  }
}

TEST(Hex8Batch, AnInvertedLaneIsNaNAndAPaddingLaneWritesNoResults) {
  const SolidMaterial m = rubber();
  Lanes lanes;
  set_deformations(lanes, 1.0);
  for (int i = 0; i < 8; ++i) lanes.x[2][i][2] = 0.6 - lanes.X[2][i][2];  // mirrored: det F < 0
  lanes.build(m, 0.0, 0.0);
  lanes.batch.element[3] = -1;
  lanes.run(false);
  EXPECT_TRUE(std::isnan(lanes.energy[2]));
  EXPECT_TRUE(std::isnan(lanes.f(2, 0, 0)));
  EXPECT_TRUE(std::isfinite(lanes.energy[0]) && std::isfinite(lanes.energy[1]));
  EXPECT_TRUE(std::isfinite(lanes.f(0, 0, 0)) && std::isfinite(lanes.f(1, 7, 2)));
  EXPECT_EQ(lanes.energy[3], -1.0);  // untouched
}

}  // namespace
