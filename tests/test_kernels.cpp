// Kernels: normalisation (the integral of W is 1), gradients summing to zero
// on a symmetric lattice, and the gradient matching the derivative of W.
#include <gtest/gtest.h>

#include <cmath>

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

INSTANTIATE_TEST_SUITE_P(AllKernels, KernelTest,
                         ::testing::Values(KernelType::cubic, KernelType::quadratic, KernelType::quintic));
}  // namespace
