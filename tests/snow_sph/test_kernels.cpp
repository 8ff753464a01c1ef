// Kernels: normalisation (the integral of W is 1), gradients summing to zero
// on a symmetric lattice, and the gradient matching the derivative of W.
#include <gtest/gtest.h>

#include <cmath>

#include "snow_sph/gradient_correction.hpp"
#include "snow_sph/kernels.hpp"

using snow_sph::Kernel;
using snow_sph::KernelType;

namespace {
// Lattice sums with h = 1.2 dx approximate the integral to O(round-off)
// for smooth kernels; the quadratic kernel's cusp at r = 0 costs ~1e-3.
constexpr double kNormalisationTolerance = 2e-3;
constexpr double kGradientSumTolerance = 1e-12;

class KernelTest : public ::testing::TestWithParam<KernelType> {};

TEST_P(KernelTest, IntegratesToOne) {
  const double dx = 0.01;
  const Kernel k = Kernel::make(GetParam(), 1.2 * dx);
  const int n = static_cast<int>(std::ceil(k.support / dx)) + 1;
  // Sum over a lattice shifted by an arbitrary offset (not a particle site).
  double sum = 0.0;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int l = -n; l <= n; ++l) {
        const double x = (i + 0.31) * dx, y = (j + 0.17) * dx, z = (l - 0.23) * dx;
        sum += k.value(std::sqrt(x * x + y * y + z * z)) * dx * dx * dx;
      }
  EXPECT_NEAR(sum, 1.0, kNormalisationTolerance);
}

TEST_P(KernelTest, GradientsSumToZeroOnSymmetricLattice) {
  const double dx = 0.01;
  const Kernel k = Kernel::make(GetParam(), 1.3 * dx);
  const int n = static_cast<int>(std::ceil(k.support / dx)) + 1;
  double gx = 0, gy = 0, gz = 0, magnitude = 0;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int l = -n; l <= n; ++l) {
        if (i == 0 && j == 0 && l == 0) continue;
        const double x = -i * dx, y = -j * dx, z = -l * dx;  // x_i - x_j with x_i = 0
        const double f = k.gradient_over_r(std::sqrt(x * x + y * y + z * z));
        gx += x * f, gy += y * f, gz += z * f;
        magnitude += std::abs(x * f);
      }
  ASSERT_GT(magnitude, 0.0);
  EXPECT_LT(std::abs(gx) / magnitude, kGradientSumTolerance);
  EXPECT_LT(std::abs(gy) / magnitude, kGradientSumTolerance);
  EXPECT_LT(std::abs(gz) / magnitude, kGradientSumTolerance);
}

TEST_P(KernelTest, GradientIsDerivativeOfValue) {
  const Kernel k = Kernel::make(GetParam(), 0.012);
  for (double r = 0.001; r < k.support; r += 0.00073) {
    const double eps = 1e-7;
    const double dwdr = (k.value(r + eps) - k.value(r - eps)) / (2 * eps);
    EXPECT_NEAR(k.gradient_over_r(r) * r, dwdr, 1e-6 * std::abs(k.value(0.0)) / k.h) << "r = " << r;
  }
  EXPECT_EQ(k.value(k.support), 0.0);
  EXPECT_EQ(k.gradient_over_r(k.support * 1.0001), 0.0);
}

TEST_P(KernelTest, CorrectedGradientIsExactForALinearFieldAtAFreeSurface) {
  // A particle on the top face of a half-space lattice (no neighbours above it) in
  // the linear field v = A x. The plain SPH sum loses about half of every
  // z-derivative there (the kernel's support is cut in half); the corrected
  // gradient (Bonet & Lok 1999) reproduces A exactly for any linear field, so only
  // round-off remains (1e-10 of |A|). The plain sum must be off by more than 30 %
  // in dv_z/dz, or the test would not show the correction doing anything.
  const double dx = 0.01, rho = 180.0, mass = rho * dx * dx * dx;
  const Kernel k = Kernel::make(GetParam(), 1.2 * dx);
  const double A[3][3] = {{0.3, -1.1, 0.7}, {0.2, 0.5, -0.4}, {-0.9, 0.6, -1.3}};
  const int n = static_cast<int>(std::ceil(k.support / dx)) + 1;
  double l[9] = {0}, m[6] = {0};
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int q = -n; q <= 0; ++q) {  // the particle at the origin, the lattice below it
        const double x[3] = {i * dx, j * dx, q * dx};
        const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (r == 0.0 || r >= k.support) continue;
        // grad_i W(x_i - x_j) with x_i = 0: -x_j W'(r) / r.
        const double f = k.gradient_over_r(r);
        const double g[3] = {-x[0] * f * mass, -x[1] * f * mass, -x[2] * f * mass};
        for (int a = 0; a < 3; ++a) {
          const double dv = A[a][0] * x[0] + A[a][1] * x[1] + A[a][2] * x[2];  // v_j - v_i
          for (int b = 0; b < 3; ++b) l[3 * a + b] += dv * g[b];
        }
        m[0] += x[0] * g[0], m[1] += x[0] * g[1], m[2] += x[0] * g[2];
        m[3] += x[1] * g[1], m[4] += x[1] * g[2], m[5] += x[2] * g[2];
      }
  const double plain_zz = l[8] / rho;
  EXPECT_GT(std::abs(plain_zz / A[2][2] - 1.0), 0.3) << "plain dvz/dz " << plain_zz;
  ASSERT_TRUE(snow_sph::correct_velocity_gradient(l, rho, m));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(l[3 * a + b] / rho, A[a][b], 1e-10) << a << b;
}

INSTANTIATE_TEST_SUITE_P(AllKernels, KernelTest,
                         ::testing::Values(KernelType::cubic, KernelType::quadratic, KernelType::quintic));
}  // namespace
