// Element kernels (tyre_fe/elements.hpp): the patch test on distorted meshes (Irons;
// Belytschko, Liu & Moran 2000, section 8.5: an affine field must give the exact F
// and nodal forces equal to the consistent boundary tractions), rigid motions,
// hourglass resistance and objectivity, equilibrium of the nodal forces, forces as
// the exact energy gradient, and the critical time step bound against the eigenvalues
// of M^-1 K of the element.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "cosim/error.hpp"
#include "tyre_fe/elements.hpp"
#include "tyre_fe/materials.hpp"

namespace {

using namespace tyre_fe;

constexpr double kHourglass = 0.05;
constexpr double kRoundOff = 1e-12;       // relative, for identities exact in exact arithmetic
constexpr double kGradientRelTol = 1e-6;  // central differences, step 1e-6 of the size

// Arbitrary rubber-like constants (not reference data).
SolidMaterial rubber(double bulk_over_shear) {
  SolidMaterial m;
  m.yeoh.C10_Pa = 0.5e6;
  m.yeoh.C20_Pa = -0.1e6;
  m.yeoh.C30_Pa = 0.03e6;
  m.yeoh.bulk_modulus_Pa = bulk_over_shear * m.yeoh.initial_shear_modulus_Pa();
  m.yeoh.density_kg_per_m3 = 1100.0;
  return m;
}

constexpr int kXi[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
constexpr int kEta[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
constexpr int kZeta[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

struct Hex { double x[8][3]; };
struct Quad { double x[4][2]; };

Hex cube(double h, const Eigen::Vector3d& centre) {
  Hex c;
  for (int i = 0; i < 8; ++i) {
    c.x[i][0] = centre[0] + 0.5 * h * kXi[i];
    c.x[i][1] = centre[1] + 0.5 * h * kEta[i];
    c.x[i][2] = centre[2] + 0.5 * h * kZeta[i];
  }
  return c;
}

// A unit-ish hexahedron with every node moved by up to 0.15 (deterministic).
Hex distorted_hex() {
  Hex c = cube(1.0, Eigen::Vector3d(0.5, 0.5, 0.5));
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) c.x[i][k] += 0.15 * std::sin(1.7 * i + 2.3 * k + 0.4);
  return c;
}

Hex map(const Hex& X, const Eigen::Matrix3d& A, const Eigen::Vector3d& t) {
  Hex x;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d y = A * Eigen::Vector3d(X.x[i][0], X.x[i][1], X.x[i][2]) + t;
    for (int k = 0; k < 3; ++k) x.x[i][k] = y[k];
  }
  return x;
}

// Nodal forces; returns the total energy (strain + hourglass).
double hex_forces(const Hex8Reference& ref, const SolidMaterial& m, const Hex& x, double f[8][3]) {
  const Eigen::Matrix3d F = hex8_deformation_gradient(ref, x.x);
  double W = 0.0;
  const Eigen::Matrix3d tau = kirchhoff_stress(m, F, &W);
  return ref.volume_m3 * W + hex8_internal_forces(ref, x.x, F, tau, kHourglass, m.shear_modulus_Pa(), f);
}

double hex_energy(const Hex8Reference& ref, const SolidMaterial& m, const Hex& x) {
  double f[8][3];
  return hex_forces(ref, m, x, f);
}

Eigen::Matrix3d sample_gradient() {
  Eigen::Matrix3d A;
  A << 1.2, 0.1, 0.0, 0.1, 0.9, 0.05, 0.0, 0.05, 1.1;
  return Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix() * A;
}

TEST(Hex8, CubeReferenceData) {
  const double h = 0.02;
  const Hex8Reference ref = hex8_reference(cube(h, Eigen::Vector3d(0.3, -0.1, 0.2)).x);
  EXPECT_NEAR(ref.volume_m3, h * h * h, kRoundOff * h * h * h);
  EXPECT_NEAR(ref.characteristic_length_m, h, kRoundOff * h);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(ref.dNdX[i][0], kXi[i] / (4 * h), kRoundOff / h);
    EXPECT_NEAR(ref.dNdX[i][1], kEta[i] / (4 * h), kRoundOff / h);
    EXPECT_NEAR(ref.dNdX[i][2], kZeta[i] / (4 * h), kRoundOff / h);
    EXPECT_NEAR(ref.gamma[2][i], kXi[i] * kEta[i], kRoundOff);  // gamma = h for a cube
  }
}

TEST(Hex8, MeanGradientReproducesLinearFields) {
  const Hex X = distorted_hex();
  const Hex8Reference ref = hex8_reference(X.x);
  Eigen::Matrix3d grad_X = Eigen::Matrix3d::Zero();
  Eigen::Vector3d sum_B = Eigen::Vector3d::Zero();
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) {
      sum_B[k] += ref.dNdX[i][k];
      for (int l = 0; l < 3; ++l) grad_X(k, l) += X.x[i][k] * ref.dNdX[i][l];
    }
  EXPECT_LE((grad_X - Eigen::Matrix3d::Identity()).norm(), kRoundOff);
  EXPECT_LE(sum_B.norm(), kRoundOff);
  for (int a = 0; a < 4; ++a) {
    double ones = 0.0, lin[3] = {0, 0, 0};
    for (int i = 0; i < 8; ++i) {
      ones += ref.gamma[a][i];
      for (int k = 0; k < 3; ++k) lin[k] += ref.gamma[a][i] * X.x[i][k];
    }
    EXPECT_NEAR(ones, 0.0, kRoundOff);
    for (double v : lin) EXPECT_NEAR(v, 0.0, kRoundOff);
  }
  // Volume of a parallelepiped (affine image of the unit cube) is det A.
  const Eigen::Matrix3d A = sample_gradient();
  EXPECT_NEAR(hex8_reference(map(cube(1.0, Eigen::Vector3d::Zero()), A, Eigen::Vector3d::Zero()).x).volume_m3,
              A.determinant(), kRoundOff);
}

TEST(Hex8, PatchTestOnDistortedMesh) {
  // 2x2x2 hexes on [0,1]^3; every coordinate of a node that is not on a boundary plane
  // is moved by up to 0.1, so the interior node moves freely and the outer faces stay
  // planar. Under x = A X + t every element must give F = A, no hourglass energy, zero
  // force on the interior node and, on the boundary, the consistent nodal forces of
  // the uniform traction P N.
  auto id = [](int i, int j, int k) { return i + 3 * j + 9 * k; };
  std::vector<Eigen::Vector3d> X(27);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const int n = id(i, j, k), index[3] = {i, j, k};
        for (int d = 0; d < 3; ++d)
          X[n][d] = 0.5 * index[d] + (index[d] == 1 ? 0.1 * std::sin(3.1 * n + 1.3 * d) : 0.0);
      }
  std::vector<std::array<int, 8>> hexes;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                         id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  const SolidMaterial m = rubber(50.0);
  const Eigen::Matrix3d A = sample_gradient();
  const Eigen::Vector3d t(0.3, -0.2, 0.1);
  const Eigen::Matrix3d P = kirchhoff_stress(m, A) * A.inverse().transpose();

  std::vector<Eigen::Vector3d> force(27, Eigen::Vector3d::Zero());
  for (const auto& hex : hexes) {
    Hex Xe, xe;
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) {
        Xe.x[a][d] = X[hex[a]][d];
        xe.x[a][d] = (A * X[hex[a]] + t)[d];
      }
    const Hex8Reference ref = hex8_reference(Xe.x);
    const Eigen::Matrix3d F = hex8_deformation_gradient(ref, xe.x);
    EXPECT_LE((F - A).norm(), kRoundOff);
    double f[8][3];
    const double hourglass = hex8_internal_forces(ref, xe.x, F, kirchhoff_stress(m, F), kHourglass,
                                                  m.shear_modulus_Pa(), f);
    EXPECT_LE(hourglass, kRoundOff * kRoundOff * m.shear_modulus_Pa() * ref.volume_m3);
    for (int a = 0; a < 8; ++a) force[hex[a]] += Eigen::Vector3d(f[a][0], f[a][1], f[a][2]);
  }
  // Consistent forces of the traction P N on the planar boundary faces (bilinear N_a;
  // 2x2 Gauss points integrate N_a |x_s x x_t| exactly on a planar quad).
  std::vector<Eigen::Vector3d> traction(27, Eigen::Vector3d::Zero());
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side)
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          int face[4];
          const int corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
          for (int c = 0; c < 4; ++c) {
            int index[3];
            index[d] = 2 * side;
            index[(d + 1) % 3] = a + corner[c][0];
            index[(d + 2) % 3] = b + corner[c][1];
            face[c] = id(index[0], index[1], index[2]);
          }
          Eigen::Vector3d normal = Eigen::Vector3d::Zero();
          normal[d] = side ? 1.0 : -1.0;
          const double g = 1.0 / std::sqrt(3.0);
          for (double s : {-g, g})
            for (double r : {-g, g}) {
              const double N[4] = {(1 - s) * (1 - r) / 4, (1 + s) * (1 - r) / 4,
                                   (1 + s) * (1 + r) / 4, (1 - s) * (1 + r) / 4};
              const Eigen::Vector3d xs = 0.25 * ((1 - r) * (X[face[1]] - X[face[0]]) + (1 + r) * (X[face[2]] - X[face[3]]));
              const Eigen::Vector3d xr = 0.25 * ((1 - s) * (X[face[3]] - X[face[0]]) + (1 + s) * (X[face[2]] - X[face[1]]));
              const double dA = xs.cross(xr).norm();
              for (int c = 0; c < 4; ++c) traction[face[c]] += N[c] * dA * (P * normal);
            }
        }
  for (int n = 0; n < 27; ++n)
    EXPECT_LE((force[n] - traction[n]).norm(), kRoundOff * P.norm()) << "node " << n;
  EXPECT_LE(force[id(1, 1, 1)].norm(), kRoundOff * P.norm());
}

TEST(Hex8, RigidRotationOf90DegreesIsObjective) {
  // Rotating the reference by 90 deg gives F = R and no force, no energy; rotating a
  // deformed state with hourglass content keeps the energy and rotates the forces.
  const Hex X = distorted_hex();
  const Hex8Reference ref = hex8_reference(X.x);
  const SolidMaterial m = rubber(1000.0);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.4, -1.0, 2.0);
  const Hex x0 = map(X, R, t);
  EXPECT_LE((hex8_deformation_gradient(ref, x0.x) - R).norm(), kRoundOff);
  double f0[8][3];
  const double energy0 = hex_forces(ref, m, x0, f0);
  // F = R to round-off; the noise is a strain of ~1e-16 times K0.
  const double noise = kRoundOff * m.bulk_modulus_Pa() * ref.volume_m3 / ref.characteristic_length_m;
  EXPECT_LE(std::abs(energy0), kRoundOff * m.shear_modulus_Pa() * ref.volume_m3);
  for (auto& fi : f0) EXPECT_LE(Eigen::Vector3d(fi[0], fi[1], fi[2]).norm(), noise);

  Hex x1 = map(X, sample_gradient(), Eigen::Vector3d(0.1, 0.0, 0.0));
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) x1.x[i][k] += 0.03 * (ref.gamma[k][i] + 0.5 * ref.gamma[3][i]);
  const Hex x2 = map(x1, R, t);
  double f1[8][3], f2[8][3];
  const double e1 = hex_forces(ref, m, x1, f1), e2 = hex_forces(ref, m, x2, f2);
  EXPECT_NEAR(e1, e2, kRoundOff * e1);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d rotated = R * Eigen::Vector3d(f1[i][0], f1[i][1], f1[i][2]);
    EXPECT_LE((rotated - Eigen::Vector3d(f2[i][0], f2[i][1], f2[i][2])).norm(), noise);
  }
}

TEST(Hex8, HourglassModeIsResisted) {
  // Cube, x-displacement delta * (xi eta) at the nodes: invisible to the centroid
  // gradient (F = I), resisted only by the hourglass stiffness k = c G V sum|B|^2 =
  // 1.5 c G h, energy k (8 delta)^2 / 2, force k 8 delta (xi eta)_i along x.
  const double h = 0.01, delta = 1e-4;
  const SolidMaterial m = rubber(1000.0);
  const Hex X = cube(h, Eigen::Vector3d(0.2, 0.1, 0.0));
  const Hex8Reference ref = hex8_reference(X.x);
  Hex x = X;
  for (int i = 0; i < 8; ++i) x.x[i][0] += delta * kXi[i] * kEta[i];
  EXPECT_LE((hex8_deformation_gradient(ref, x.x) - Eigen::Matrix3d::Identity()).norm(), kRoundOff);
  double f[8][3];
  const double energy = hex_forces(ref, m, x, f);
  const double k = kHourglass * m.shear_modulus_Pa() * 1.5 * h;
  EXPECT_NEAR(energy, 0.5 * k * 64 * delta * delta, kRoundOff * energy);
  // F = I only to round-off: a strain of ~1e-16 times K0 h^2 (K0 = 1000 G) is the noise.
  const double noise = kRoundOff * m.bulk_modulus_Pa() * h * h;
  double work = 0.0;
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(f[i][0], k * 8 * delta * kXi[i] * kEta[i], noise);
    EXPECT_NEAR(f[i][1], 0.0, noise);
    work += f[i][0] * delta * kXi[i] * kEta[i];
  }
  EXPECT_NEAR(work, 2 * energy, 8 * noise * delta);  // restoring: f . u = 2 E > 0

  // On a distorted hex every base vector gamma_a is resisted as well.
  const Hex Xd = distorted_hex();
  const Hex8Reference refd = hex8_reference(Xd.x);
  for (int a = 0; a < 4; ++a) {
    Hex xd = Xd;
    for (int i = 0; i < 8; ++i) xd.x[i][1] += delta * refd.gamma[a][i];
    double fd[8][3], restoring = 0.0;
    EXPECT_GT(hex_forces(refd, m, xd, fd), 0.0);
    for (int i = 0; i < 8; ++i) restoring += fd[i][1] * refd.gamma[a][i];
    EXPECT_GT(restoring, 0.0);
  }
}

// Each force component f[i][k] of the element's nodes x against the central difference
// of its energy, (energy(x + step e_ik) - energy(x - step e_ik)) / (2 step), within tolerance.
template <class Element, int N, int D, class Energy>
void expect_forces_are_energy_gradient(const Element& x, const double (&f)[N][D], double step, double tolerance,
                                       Energy energy) {
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < D; ++k) {
      Element xp = x, xm = x;
      xp.x[i][k] += step;
      xm.x[i][k] -= step;
      const double derivative = (energy(xp) - energy(xm)) / (2 * step);
      EXPECT_NEAR(f[i][k], derivative, tolerance);
    }
}

TEST(Hex8, NodalForcesAreInEquilibriumAndAreTheEnergyGradient) {
  const Hex X = distorted_hex();
  const Hex8Reference ref = hex8_reference(X.x);
  const SolidMaterial m = rubber(20.0);
  Hex x = map(X, sample_gradient(), Eigen::Vector3d(0.2, 0.3, -0.1));
  for (int i = 0; i < 8; ++i) x.x[i][2] += 0.05 * std::cos(2.0 * i);  // with hourglass content
  double f[8][3];
  hex_forces(ref, m, x, f);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  double scale = 0.0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d fi(f[i][0], f[i][1], f[i][2]), xi(x.x[i][0], x.x[i][1], x.x[i][2]);
    sum += fi;
    moment += xi.cross(fi);
    scale += fi.norm() * xi.norm();
  }
  EXPECT_LE(sum.norm(), kRoundOff * scale);
  EXPECT_LE(moment.norm(), kRoundOff * scale);
  expect_forces_are_energy_gradient(x, f, 1e-6, kGradientRelTol * scale,
                                    [&](const Hex& y) { return hex_energy(ref, m, y); });
}

TEST(Hex8, InvertedHexThrows) {
  Hex X = cube(1.0, Eigen::Vector3d::Zero());
  for (int i = 0; i < 8; ++i) X.x[i][2] = -X.x[i][2];  // mirror: negative volume
  EXPECT_THROW(hex8_reference(X.x), cosim::Error);
}

// Largest eigenvalue of M^-1 K with K by central differences of the forces at the
// reference state and equal lumped masses.
template <int N, class Forces>
double max_omega_sq(Forces forces, double nodal_mass) {
  Eigen::Matrix<double, N, N> K;
  const double step = 1e-7;
  for (int j = 0; j < N; ++j) {
    Eigen::Matrix<double, N, 1> fp = forces(j, step), fm = forces(j, -step);
    K.col(j) = (fp - fm) / (2 * step);
  }
  const Eigen::Matrix<double, N, N> symmetric = 0.5 * (K + K.transpose()) / nodal_mass;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>>(symmetric).eigenvalues().maxCoeff();
}

TEST(Hex8, StableStepBoundsTheElementFrequencies) {
  const SolidMaterial m = rubber(1000.0);
  const double rho = m.density_kg_per_m3(), K = m.bulk_modulus_Pa(), G = m.shear_modulus_Pa();
  for (const Hex& X : {cube(0.01, Eigen::Vector3d::Zero()), distorted_hex()}) {
    const Hex8Reference ref = hex8_reference(X.x);
    auto forces = [&](int j, double dx) {
      Hex x = X;
      x.x[j / 3][j % 3] += dx * ref.characteristic_length_m;
      double f[8][3];
      hex_forces(ref, m, x, f);
      Eigen::Matrix<double, 24, 1> out;
      for (int i = 0; i < 24; ++i) out[i] = f[i / 3][i % 3] / ref.characteristic_length_m;
      return out;
    };
    const double exact = 2.0 / std::sqrt(max_omega_sq<24>(forces, rho * ref.volume_m3 / 8));
    const double bound = hex8_stable_time_step_s(ref, rho, K, G, kHourglass);
    std::printf("  hex: bound / exact critical step = %.4f\n", bound / exact);
    EXPECT_LE(bound, exact * (1 + 1e-6));
    EXPECT_GE(bound, 0.5 * exact);
    // L / c_dilatational overestimates the critical step of nearly incompressible
    // one-point hexes (sqrt(3) for a cube): the reason for the bound.
    const double dilatational = std::sqrt((K + 4.0 / 3.0 * G) / rho);
    EXPECT_GT(ref.characteristic_length_m / dilatational, 1.2 * exact);
  }
  const Hex8Reference ref = hex8_reference(cube(0.01, Eigen::Vector3d::Zero()).x);
  EXPECT_NEAR(hex8_stable_time_step_s(ref, rho, K, G, 0.0),
              0.01 / std::sqrt(3.0 * K / rho), 1e-9 * 0.01 / std::sqrt(K / rho));
}

// A thin belt-like layer (1 mm thick, 20 mm x 16 mm in plane, slightly skewed) with
// steel rebar in the plane at 66.7 deg: the directional bound still bounds the true
// highest frequency, and it allows a much longer step than the direction-free one
// (which lets the steel act through the thickness).
TEST(Hex8, DirectionalRebarBoundStaysSafeAndSeesTheInPlaneLength) {
  const SolidMaterial m = rubber(20.0);
  const double rho = 1500.0, K = m.bulk_modulus_Pa(), G = m.shear_modulus_Pa();
  const double phi = 0.1, E = 200e9;  // belt-like smeared steel
  const double angle = 66.7 * M_PI / 180.0;
  const Eigen::Vector3d a0(std::cos(angle), std::sin(angle), 0.0);
  Hex X = cube(1.0, Eigen::Vector3d::Zero());
  for (int i = 0; i < 8; ++i) {
    X.x[i][0] = 0.010 * kXi[i] + 0.002 * kEta[i];
    X.x[i][1] = 0.008 * kEta[i];
    X.x[i][2] = 0.0005 * kZeta[i] + 0.0001 * kXi[i];
  }
  const Hex8Reference ref = hex8_reference(X.x);
  auto forces = [&](int j, double dx) {
    Hex x = X;
    x.x[j / 3][j % 3] += dx * ref.characteristic_length_m;
    const Eigen::Matrix3d F = hex8_deformation_gradient(ref, x.x);
    double W = 0.0;
    Eigen::Matrix3d tau = kirchhoff_stress(m, F, &W);
    add_rebar_kirchhoff_stress(a0, phi, E, F, tau);
    double f[8][3];
    hex8_internal_forces(ref, x.x, F, tau, kHourglass, G, f);
    Eigen::Matrix<double, 24, 1> out;
    for (int i = 0; i < 24; ++i) out[i] = f[i / 3][i % 3] / ref.characteristic_length_m;
    return out;
  };
  const double exact = 2.0 / std::sqrt(max_omega_sq<24>(forces, rho * ref.volume_m3 / 8));
  const double directional = hex8_stable_time_step_s(ref, rho, K, G, kHourglass, phi * E, a0);
  const double isotropic = hex8_stable_time_step_s(ref, rho, K, G, kHourglass, phi * E);
  std::printf("  thin rebar layer: directional bound / exact = %.4f, direction-free / exact = %.4f\n",
              directional / exact, isotropic / exact);
  EXPECT_LE(directional, exact * (1 + 1e-6));
  EXPECT_GE(directional, 0.5 * exact);
  EXPECT_GT(directional, 4.0 * isotropic);  // the steel no longer acts through 1 mm
  // A zero direction falls back to the direction-free bound.
  EXPECT_DOUBLE_EQ(hex8_stable_time_step_s(ref, rho, K, G, kHourglass, phi * E, Eigen::Vector3d::Zero()),
                   isotropic);
}

// ---- axisymmetric quad ----------------------------------------------------------

Quad distorted_quad() {
  return Quad{{{0.100, 0.000}, {0.112, 0.002}, {0.115, 0.013}, {0.098, 0.010}}};
}

double quad_forces(const Quad4AxiReference& ref, const SolidMaterial& m, const Quad& x, double f[4][2]) {
  const Eigen::Matrix3d F = quad4axi_deformation_gradient(ref, x.x);
  double W = 0.0;
  const Eigen::Matrix3d tau = kirchhoff_stress(m, F, &W);
  return ref.volume_per_rad_m3 * W +
         quad4axi_internal_forces(ref, x.x, F, tau, kHourglass, m.shear_modulus_Pa(), f);
}

TEST(Quad4Axi, UniformRadialExpansionGivesTheHoopStretch) {
  // u_r = c r, u_y = d y: F = diag(1 + c, 1 + d, 1 + c) exactly, on any quad.
  const Quad X = distorted_quad();
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  const double c = 0.07, d = -0.03;
  Quad x = X;
  for (auto& p : x.x) p[0] *= 1 + c, p[1] = (1 + d) * p[1] + 0.2;
  const Eigen::Matrix3d F = quad4axi_deformation_gradient(ref, x.x);
  EXPECT_LE((F - Eigen::Vector3d(1 + c, 1 + d, 1 + c).asDiagonal().toDenseMatrix()).norm(), kRoundOff);
}

TEST(Quad4Axi, AxialTranslationGivesNoForce) {
  const Quad X = distorted_quad();
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  Quad x = X;
  for (auto& p : x.x) p[1] += 0.3;
  const SolidMaterial m = rubber(1000.0);
  double f[4][2];
  // F = I to round-off; the noise is a strain of ~1e-16 times the moduli.
  EXPECT_NEAR(quad_forces(ref, m, x, f), 0.0, kRoundOff * m.shear_modulus_Pa() * ref.volume_per_rad_m3);
  const double noise = kRoundOff * m.bulk_modulus_Pa() * ref.volume_per_rad_m3 / ref.characteristic_length_m;
  for (auto& fi : f) EXPECT_NEAR(std::hypot(fi[0], fi[1]), 0.0, noise);
}

TEST(Quad4Axi, HourglassModeIsResisted) {
  // Rectangle: delta h = delta (1, -1, 1, -1) on r leaves F = I (the hoop stretch too,
  // sum h = 0); energy k (4 delta)^2 / 2 with k = c G V sum|B|^2.
  const Quad X{{{0.2, 0.0}, {0.21, 0.0}, {0.21, 0.02}, {0.2, 0.02}}};
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  const SolidMaterial m = rubber(1000.0);
  const double delta = 1e-5, h[4] = {1, -1, 1, -1};
  Quad x = X;
  for (int i = 0; i < 4; ++i) x.x[i][0] += delta * h[i];
  EXPECT_LE((quad4axi_deformation_gradient(ref, x.x) - Eigen::Matrix3d::Identity()).norm(), kRoundOff);
  double f[4][2];
  const double energy = quad_forces(ref, m, x, f);
  const double k = kHourglass * m.shear_modulus_Pa() * ref.volume_per_rad_m3 * ref.gradient_sq_sum_per_m2;
  EXPECT_NEAR(energy, 0.5 * k * 16 * delta * delta, 1e-9 * energy);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(f[i][0], k * 4 * delta * h[i], 1e-9 * k * delta);
}

TEST(Quad4Axi, NetForcesAndEnergyGradient) {
  // sum_i f_y = 0 (translation along the axis); sum_i f_r = V P_thth / R_c, the hoop
  // term, since sum_i B_i = 0 and sum_i gamma_i = 0. Forces = d(V W + E_hg)/dx.
  const Quad X = distorted_quad();
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  const SolidMaterial m = rubber(20.0);
  Quad x = X;
  for (int i = 0; i < 4; ++i) x.x[i][0] *= 1.1 + 0.01 * i, x.x[i][1] += 0.002 * std::sin(i);
  double f[4][2];
  quad_forces(ref, m, x, f);
  const Eigen::Matrix3d F = quad4axi_deformation_gradient(ref, x.x);
  const double hoop_total = ref.volume_per_rad_m3 * kirchhoff_stress(m, F)(2, 2) / F(2, 2) / ref.radius_m;
  double sum_r = 0.0, sum_y = 0.0, scale = 0.0;
  for (auto& fi : f) sum_r += fi[0], sum_y += fi[1], scale += std::hypot(fi[0], fi[1]);
  EXPECT_NEAR(sum_y, 0.0, kRoundOff * scale);
  EXPECT_NEAR(sum_r, hoop_total, kRoundOff * scale);
  expect_forces_are_energy_gradient(x, f, 1e-8, kGradientRelTol * scale, [&](const Quad& y) {
    double g[4][2];
    return quad_forces(ref, m, y, g);
  });
}

TEST(Quad4Axi, PatchTestOnGradedRectangularGrid) {
  // 2x2 rectangles with unequal widths and heights under u_r = c r, u_y = d y: a uniform
  // state with sigma_rr = sigma_thth, which is an exact equilibrium state of the
  // axisymmetric continuum; the interior node must carry no force. (On distorted
  // quads the one-point axisymmetric element satisfies this only to O(h).)
  const double R[3] = {0.10, 0.107, 0.121}, Y[3] = {0.0, 0.012, 0.017};
  const SolidMaterial m = rubber(50.0);
  Eigen::Vector2d interior = Eigen::Vector2d::Zero();
  double scale = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const Quad X{{{R[i], Y[j]}, {R[i + 1], Y[j]}, {R[i + 1], Y[j + 1]}, {R[i], Y[j + 1]}}};
      const Quad4AxiReference ref = quad4axi_reference(X.x);
      Quad x = X;
      for (auto& p : x.x) p[0] *= 1.05, p[1] *= 0.98;
      double f[4][2];
      quad_forces(ref, m, x, f);
      const int interior_local[2][2] = {{2, 3}, {1, 0}};  // node (R[1], Y[1]) in quad (i, j)
      const int a = interior_local[j][i];
      interior += Eigen::Vector2d(f[a][0], f[a][1]);
      scale += std::hypot(f[a][0], f[a][1]);
    }
  EXPECT_LE(interior.norm(), kRoundOff * scale);
}

TEST(Quad4Axi, NodesOnTheAxis) {
  // Two nodes on the axis are fine (R_c > 0); a centroid on the axis is rejected.
  const Quad X{{{0.0, 0.0}, {0.01, 0.0}, {0.01, 0.01}, {0.0, 0.01}}};
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  Quad x = X;
  for (auto& p : x.x) p[0] *= 1.02;
  double f[4][2];
  EXPECT_TRUE(std::isfinite(quad_forces(ref, rubber(100.0), x, f)));
  EXPECT_NEAR(quad4axi_deformation_gradient(ref, x.x)(2, 2), 1.02, kRoundOff);
  const Quad across{{{-0.01, 0.0}, {0.01, 0.0}, {0.01, 0.01}, {-0.01, 0.01}}};
  EXPECT_THROW(quad4axi_reference(across.x), cosim::Error);
  const Quad clockwise{{{0.1, 0.0}, {0.1, 0.01}, {0.11, 0.01}, {0.11, 0.0}}};
  EXPECT_THROW(quad4axi_reference(clockwise.x), cosim::Error);
}

// ---- axisymmetric quad with twist (CGAX4R-type) -----------------------------------

// Host rubber with an optional smeared rebar along the reference direction a0 in
// (r, y, theta) (fibre modulus phi E, volume fraction folded in).
struct Host {
  SolidMaterial solid;
  Eigen::Vector3d a0 = Eigen::Vector3d::Zero();
  double fibre_modulus_Pa = 0.0;
};

// A belt-like host: the bars at 0.9 rad from a meridional tangent (0.3, 0.95) towards
// theta, so every component of tau (r-theta and y-theta shear too) is non-zero.
Host belt_host(double bulk_over_shear) {
  Host h;
  h.solid = rubber(bulk_over_shear);
  const Eigen::Vector2d t = Eigen::Vector2d(0.3, 0.95).normalized();
  h.a0 = Eigen::Vector3d(std::cos(0.9) * t[0], std::cos(0.9) * t[1], std::sin(0.9));
  h.fibre_modulus_Pa = 20.0 * h.solid.shear_modulus_Pa();
  return h;
}

Eigen::Matrix3d host_stress(const Host& m, const Eigen::Matrix3d& F, const Eigen::Vector3d& a0, double* W) {
  Eigen::Matrix3d tau = kirchhoff_stress(m.solid, F, W);
  if (m.fibre_modulus_Pa > 0.0) *W += add_rebar_kirchhoff_stress(a0, 1.0, m.fibre_modulus_Pa, F, tau);
  return tau;
}

// Forces and twist moments; returns the total energy (strain + hourglass).
double twisted_quad_forces(const Quad4AxiReference& ref, const Host& m, const Quad& x,
                           const double phi[4], double f[4][2], double moment[4],
                           double hourglass = kHourglass) {
  const Eigen::Matrix3d F = quad4axi_deformation_gradient(ref, x.x, phi);
  double W = 0.0;
  const Eigen::Matrix3d tau = host_stress(m, F, m.a0, &W);
  return ref.volume_per_rad_m3 * W + quad4axi_internal_forces(ref, x.x, phi, F, tau, hourglass,
                                                              m.solid.shear_modulus_Pa(), f, moment);
}

// A non-affine deformed state of distorted_quad() and a non-linear twist field.
Quad deformed_quad() {
  Quad x = distorted_quad();
  for (int i = 0; i < 4; ++i) x.x[i][0] *= 1.1 + 0.01 * i, x.x[i][1] += 0.002 * std::sin(i);
  return x;
}
constexpr double kTwistField[4] = {0.31, 0.36, 0.27, 0.295};  // rad; gradient ~ 5 rad/m

TEST(Quad4AxiTwist, ForcesAndMomentsAreTheEnergyGradient) {
  // d(V W + E_hg)/d(r_i, y_i, phi_i) by central differences, with the coupling
  // terms: the r-force from d(F_thR, F_thY)/dr_i = grad(phi)/4 and the moments.
  // Net: sum_i f_y = 0, sum_i M_i = 0 (invariance under a rigid rotation about the
  // axis), sum_i f_r = V (P_thR dphi/dR + P_thY dphi/dY + P_thth / R_c).
  const Quad X = distorted_quad();
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  const Host m = belt_host(20.0);
  const Quad x = deformed_quad();
  double f[4][2], moment[4];
  twisted_quad_forces(ref, m, x, kTwistField, f, moment);
  const double R = ref.radius_m;
  double scale = 0.0, sum_r = 0.0, sum_y = 0.0, sum_moment = 0.0, moment_size = 0.0;
  for (int i = 0; i < 4; ++i) {
    scale += std::hypot(f[i][0], f[i][1]) + std::abs(moment[i]) / R;
    sum_r += f[i][0], sum_y += f[i][1], sum_moment += moment[i];
    moment_size += std::abs(moment[i]);
  }
  EXPECT_GT(moment_size / R, 0.1 * scale);  // the twist terms are not negligible here
  const Eigen::Matrix3d F = quad4axi_deformation_gradient(ref, x.x, kTwistField);
  double W = 0.0;
  const Eigen::Matrix3d P = host_stress(m, F, m.a0, &W) * F.inverse().transpose();
  double twist_R = 0.0, twist_Y = 0.0;
  for (int i = 0; i < 4; ++i) twist_R += kTwistField[i] * ref.dNdX[i][0], twist_Y += kTwistField[i] * ref.dNdX[i][1];
  EXPECT_NEAR(sum_r, ref.volume_per_rad_m3 * (P(2, 0) * twist_R + P(2, 1) * twist_Y + P(2, 2) / R),
              kRoundOff * scale);
  EXPECT_NEAR(sum_y, 0.0, kRoundOff * scale);
  EXPECT_NEAR(sum_moment, 0.0, kRoundOff * scale * R);

  const double step = 1e-8;  // m; R_c ~ 0.1 m, so 1e-7 rad on phi
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 2; ++k) {
      Quad xp = x, xm = x;
      xp.x[i][k] += step;
      xm.x[i][k] -= step;
      double g[4][2], mg[4];
      const double derivative = (twisted_quad_forces(ref, m, xp, kTwistField, g, mg) -
                                 twisted_quad_forces(ref, m, xm, kTwistField, g, mg)) / (2 * step);
      EXPECT_NEAR(f[i][k], derivative, kGradientRelTol * scale) << "node " << i << " dof " << k;
    }
    double php[4], phm[4];
    std::copy(kTwistField, kTwistField + 4, php);
    std::copy(kTwistField, kTwistField + 4, phm);
    php[i] += step / R;
    phm[i] -= step / R;
    double g[4][2], mg[4];
    const double derivative =
        (twisted_quad_forces(ref, m, x, php, g, mg) - twisted_quad_forces(ref, m, x, phm, g, mg)) / (2 * step / R);
    EXPECT_NEAR(moment[i], derivative, kGradientRelTol * scale * R) << "node " << i << " twist";
  }
}

TEST(Quad4AxiTwist, RigidRotationAboutTheAxisChangesNothing) {
  // A uniform phi is a rigid rotation about the axis: F, energy, forces and moments
  // are those of phi = 0; for isotropic rubber without twist gradient the moments
  // vanish (tau_thR = tau_thY = 0), with angled rebar they do not but sum to zero.
  const Quad X = distorted_quad();
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  const Quad x = deformed_quad();
  const double still[4] = {0, 0, 0, 0}, turned[4] = {0.8, 0.8, 0.8, 0.8};
  EXPECT_LE((quad4axi_deformation_gradient(ref, x.x, turned) - quad4axi_deformation_gradient(ref, x.x)).norm(),
            kRoundOff);
  for (const Host& m : {Host{rubber(1000.0)}, belt_host(1000.0)}) {
    double f0[4][2], m0[4], f1[4][2], m1[4];
    const double e0 = twisted_quad_forces(ref, m, x, still, f0, m0);
    const double e1 = twisted_quad_forces(ref, m, x, turned, f1, m1);
    double scale = 0.0, sum_moment = 0.0;
    for (int i = 0; i < 4; ++i) scale += std::hypot(f0[i][0], f0[i][1]);
    EXPECT_NEAR(e1, e0, kRoundOff * e0);
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(f1[i][0], f0[i][0], kRoundOff * scale);
      EXPECT_NEAR(f1[i][1], f0[i][1], kRoundOff * scale);
      EXPECT_NEAR(m1[i], m0[i], kRoundOff * scale * ref.radius_m);
      if (m.fibre_modulus_Pa == 0.0) {
        EXPECT_NEAR(m1[i], 0.0, kRoundOff * scale * ref.radius_m);
      }
      sum_moment += m1[i];
    }
    EXPECT_NEAR(sum_moment, 0.0, kRoundOff * scale * ref.radius_m);
    // The CAX4 overload is the phi = 0 case.
    double fc[4][2];
    const Eigen::Matrix3d F = quad4axi_deformation_gradient(ref, x.x);
    double W = 0.0;
    quad4axi_internal_forces(ref, x.x, F, host_stress(m, F, m.a0, &W), kHourglass, m.solid.shear_modulus_Pa(), fc);
    for (int i = 0; i < 4; ++i) EXPECT_LE(std::hypot(fc[i][0] - f0[i][0], fc[i][1] - f0[i][1]), kRoundOff * scale);
  }
}

TEST(Quad4AxiTwist, UniformTwistGradientGivesTheExactF) {
  // phi = c + a R + b Y together with an affine in-plane map x = A X + t: on any quad
  // the theta row of F is exactly (r_c a, r_c b, r_c / R_c) (a tube twisted by a per
  // unit length has the shear gamma_y-theta = r a), and the twist hourglass is idle.
  const Quad X = distorted_quad();
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  Eigen::Matrix2d A;
  A << 1.04, 0.03, -0.02, 0.97;
  const double a = 2.5, b = -4.0, c = 0.7;  // rad/m, rad/m, rad
  Quad x;
  double phi[4], r_c = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d p = A * Eigen::Vector2d(X.x[i][0], X.x[i][1]) + Eigen::Vector2d(0.01, -0.02);
    x.x[i][0] = p[0], x.x[i][1] = p[1];
    phi[i] = c + a * X.x[i][0] + b * X.x[i][1];
    r_c += 0.25 * p[0];
  }
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  expected.topLeftCorner<2, 2>() = A;
  expected.row(2) << r_c * a, r_c * b, r_c / ref.radius_m;
  const Eigen::Matrix3d F = quad4axi_deformation_gradient(ref, x.x, phi);
  EXPECT_LE((F - expected).norm(), kRoundOff);
  double f[4][2], moment[4];
  const SolidMaterial m = rubber(50.0);
  const double hourglass = quad4axi_internal_forces(ref, x.x, phi, F, kirchhoff_stress(m, F), kHourglass,
                                                    m.shear_modulus_Pa(), f, moment);
  EXPECT_LE(hourglass, kRoundOff * kRoundOff * m.shear_modulus_Pa() * ref.volume_per_rad_m3);
}

TEST(Quad4AxiTwist, TwistHourglassModeIsResisted) {
  // Rectangle, phi = delta h with h = (1, -1, 1, -1): invisible to the one-point
  // gradient (F = I), resisted on the hoop displacement R_c phi with the in-plane
  // stiffness k: energy k R_c^2 (4 delta)^2 / 2, moment k R_c^2 4 delta h_i.
  const Quad X{{{0.2, 0.0}, {0.21, 0.0}, {0.21, 0.02}, {0.2, 0.02}}};
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  const SolidMaterial m = rubber(1000.0);
  const double delta = 1e-4, h[4] = {1, -1, 1, -1};
  double phi[4];
  for (int i = 0; i < 4; ++i) phi[i] = delta * h[i];
  EXPECT_LE((quad4axi_deformation_gradient(ref, X.x, phi) - Eigen::Matrix3d::Identity()).norm(), kRoundOff);
  double f[4][2], moment[4];
  const double energy = twisted_quad_forces(ref, Host{m}, X, phi, f, moment);
  const double k = kHourglass * m.shear_modulus_Pa() * ref.volume_per_rad_m3 * ref.gradient_sq_sum_per_m2;
  const double R2 = ref.radius_m * ref.radius_m;
  EXPECT_NEAR(energy, 0.5 * k * R2 * 16 * delta * delta, 1e-9 * energy);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(moment[i], k * R2 * 4 * delta * h[i], 1e-9 * k * R2 * delta);
    EXPECT_NEAR(std::hypot(f[i][0], f[i][1]), 0.0, 1e-9 * k * ref.radius_m * delta);
  }
}

// Revolves a small copy of distorted_quad() (size h ~ 0.015 * size_factor * 10 / R,
// centre R = 0.1) over dtheta into a hex (the mesh.hpp node order), carries a twisted
// state into 3D as node (r, y, phi) at theta -> (r sin(theta + phi), y, r cos(theta + phi))
// and compares the hex with the axisym element: F rotated into the local (r, y, theta)
// bases, and the hex nodal forces summed per quad node as (f.e_r, f_y, r f.e_theta) /
// dtheta against (f_r, f_y, M). Returns the relative differences {F, forces, moments}.
std::array<double, 3> wedge_versus_axisym(double size_factor, double dtheta) {
  Quad X;
  const Quad big = distorted_quad();
  for (int i = 0; i < 4; ++i) {
    X.x[i][0] = 0.1 + size_factor * (big.x[i][0] - 0.106);
    X.x[i][1] = 0.02 + size_factor * (big.x[i][1] - 0.006);
  }
  const Quad4AxiReference ref = quad4axi_reference(X.x);
  const Host m = belt_host(20.0);
  Eigen::Matrix2d A;
  A << 1.03, 0.02, -0.01, 0.98;
  const double a = 0.5, b = -0.8, c = 0.4;  // phi = c + a R + b Y: shears ~ 0.05-0.08
  Quad x;
  double phi[4], phi_c = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d p = A * Eigen::Vector2d(X.x[i][0], X.x[i][1]) + Eigen::Vector2d(0.002, 0.001);
    x.x[i][0] = p[0], x.x[i][1] = p[1];
    phi[i] = c + a * X.x[i][0] + b * X.x[i][1];
    phi_c += 0.25 * phi[i];
  }
  double f[4][2], moment[4];
  twisted_quad_forces(ref, m, x, phi, f, moment, 0.0);
  const Eigen::Matrix3d F_axi = quad4axi_deformation_gradient(ref, x.x, phi);

  const int quad_node[8] = {0, 3, 2, 1, 0, 3, 2, 1};
  auto e_r = [](double th) { return Eigen::Vector3d(std::sin(th), 0.0, std::cos(th)); };
  auto e_theta = [](double th) { return Eigen::Vector3d(std::cos(th), 0.0, -std::sin(th)); };
  Hex X3, x3;
  double angle[8];
  for (int k = 0; k < 8; ++k) {
    const int i = quad_node[k];
    angle[k] = k < 4 ? -0.5 * dtheta : 0.5 * dtheta;
    const Eigen::Vector3d P = X.x[i][0] * e_r(angle[k]) + Eigen::Vector3d(0, X.x[i][1], 0);
    const Eigen::Vector3d p = x.x[i][0] * e_r(angle[k] + phi[i]) + Eigen::Vector3d(0, x.x[i][1], 0);
    for (int d = 0; d < 3; ++d) X3.x[k][d] = P[d], x3.x[k][d] = p[d];
  }
  const Hex8Reference ref3 = hex8_reference(X3.x);
  const Eigen::Matrix3d F3 = hex8_deformation_gradient(ref3, x3.x);
  Eigen::Matrix3d Q_ref, Q_cur;  // columns e_r, e_y, e_theta at the wedge's centre
  Q_ref << e_r(0.0), Eigen::Vector3d::UnitY(), e_theta(0.0);
  Q_cur << e_r(phi_c), Eigen::Vector3d::UnitY(), e_theta(phi_c);
  const Eigen::Matrix3d F_local = Q_cur.transpose() * F3 * Q_ref;

  double W = 0.0, f3[8][3];
  const Eigen::Matrix3d tau3 = host_stress(m, F3, Q_ref * m.a0, &W);
  hex8_internal_forces(ref3, x3.x, F3, tau3, 0.0, m.solid.shear_modulus_Pa(), f3);
  double from_hex[4][3] = {};
  for (int k = 0; k < 8; ++k) {
    const int i = quad_node[k];
    const Eigen::Vector3d fk(f3[k][0], f3[k][1], f3[k][2]);
    from_hex[i][0] += fk.dot(e_r(angle[k] + phi[i])) / dtheta;
    from_hex[i][1] += fk[1] / dtheta;
    from_hex[i][2] += x.x[i][0] * fk.dot(e_theta(angle[k] + phi[i])) / dtheta;
  }
  double scale = 0.0, force_error = 0.0, moment_error = 0.0;
  for (int i = 0; i < 4; ++i) {
    scale += std::hypot(f[i][0], f[i][1]) + std::abs(moment[i]) / ref.radius_m;
    force_error += std::hypot(from_hex[i][0] - f[i][0], from_hex[i][1] - f[i][1]);
    moment_error += std::abs(from_hex[i][2] - moment[i]) / ref.radius_m;
    EXPECT_GT(from_hex[i][2] * moment[i], 0.0) << "node " << i;  // same sense of the moments
  }
  return {(F_local - F_axi).norm() / (F_axi - Eigen::Matrix3d::Identity()).norm(), force_error / scale,
          moment_error / scale};
}

TEST(Quad4AxiTwist, RevolvedHexWedgeConvergesToTheAxisymElement) {
  // The transfer to 3D (affine in-plane map, linear twist field, no hourglass). The
  // two one-point elements are different discretisations: the hex integrates the
  // weight R over the section exactly, the axisym element takes V = A R_c with R_c the
  // mean node radius and N_i = 1/4 in the hoop terms, which differ by O(h/R) on a
  // distorted quad. The differences must vanish linearly as h/R -> 0 (a wrong sense of
  // phi, a missing coupling term or a wrong factor would leave O(1) differences).
  const auto coarse = wedge_versus_axisym(0.1, 1e-3);  // h/R ~ 0.015
  const auto fine = wedge_versus_axisym(0.05, 1e-3);   // h/R ~ 0.0075
  std::printf("  hex wedge vs axisym, h/R 0.015 -> 0.0075: F %.2e -> %.2e, forces %.2e -> %.2e, "
              "moments %.2e -> %.2e\n", coarse[0], fine[0], coarse[1], fine[1], coarse[2], fine[2]);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LE(coarse[k], 3e-3);
    EXPECT_LE(fine[k], 0.55 * coarse[k]);
  }
}

// Largest eigenvalue of M^-1 K of the axisymmetric quad with twist in the coordinates
// (u_r, u_y, w = R phi) with lumped mass m each (K by central differences at the
// reference state); the twist of nodes on the axis is held.
double quad_max_omega_sq(const Quad& X, const Quad4AxiReference& ref, const SolidMaterial& m) {
  std::vector<int> dofs;  // 3 i + c
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c)
      if (c < 2 || X.x[i][0] > 0.0) dofs.push_back(3 * i + c);
  const int n = static_cast<int>(dofs.size());
  const double L = ref.characteristic_length_m, step = 1e-7 * L;
  auto forces = [&](int dof, double dx) {
    Quad x = X;
    double phi[4] = {0, 0, 0, 0}, f[4][2], moment[4];
    if (dof % 3 < 2) x.x[dof / 3][dof % 3] += dx;
    else phi[dof / 3] += dx / X.x[dof / 3][0];
    twisted_quad_forces(ref, Host{m}, x, phi, f, moment);
    Eigen::VectorXd out(n);
    for (int a = 0; a < n; ++a) {
      const int i = dofs[a] / 3, c = dofs[a] % 3;
      out[a] = c < 2 ? f[i][c] : moment[i] / X.x[i][0];
    }
    return out;
  };
  Eigen::MatrixXd K(n, n);
  for (int j = 0; j < n; ++j) K.col(j) = (forces(dofs[j], step) - forces(dofs[j], -step)) / (2 * step);
  const Eigen::MatrixXd symmetric = 0.5 * (K + K.transpose()) / (m.density_kg_per_m3() * ref.volume_per_rad_m3 / 4);
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(symmetric).eigenvalues().maxCoeff();
}

TEST(Quad4Axi, StableStepBoundsTheElementFrequencies) {
  // Rubber (K0 = 1000 G: the volumetric modes govern) and a compressible solid with
  // K0 = G, where the twist (shear) modes are relatively stiffer.
  SolidMaterial soft;
  soft.kind = SolidMaterial::Kind::elastic;
  soft.elastic = ElasticSolid{5.0e6, 0.125, 1000.0};
  const Quad on_axis{{{0.0, 0.0}, {0.01, 0.0}, {0.01, 0.01}, {0.0, 0.01}}};
  // Near the axis R_c / R_i = 6 on the inner nodes: the twist modes of those nodes
  // (inertia m R_i^2) govern the step.
  const Quad near_axis{{{0.001, 0.0}, {0.011, 0.0}, {0.011, 0.01}, {0.001, 0.01}}};
  for (const SolidMaterial& m : {rubber(1000.0), soft}) {
    const double rho = m.density_kg_per_m3(), K = m.bulk_modulus_Pa(), G = m.shear_modulus_Pa();
    for (const Quad& X : {distorted_quad(), on_axis, near_axis}) {
      const Quad4AxiReference ref = quad4axi_reference(X.x);
      const double exact = 2.0 / std::sqrt(quad_max_omega_sq(X, ref, m));
      const double bound = quad4axi_stable_time_step_s(ref, rho, K, G, kHourglass);
      std::printf("  quad (K/G = %.0f): bound / exact critical step = %.4f\n", K / G, bound / exact);
      EXPECT_LE(bound, exact * (1 + 1e-6));
      EXPECT_GE(bound, 0.5 * exact);
    }
  }
}

}  // namespace
