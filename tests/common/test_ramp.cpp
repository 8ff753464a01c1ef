// The shared load ramp (common/include/cosim/ramp.hpp): values worked by hand,
// the end conditions each curve is chosen for, and the mean value of 1/2.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/ramp.hpp"

namespace {

using cosim::RampCurve;
using cosim::ramp;

TEST(Ramp, ValuesWorkedByHand) {
  // u = 1/4: smoothstep 3/16 - 2/64 = 0.15625; smootherstep 10/64 - 15/256 + 6/1024
  // = 0.103515625; both exact in binary, so only the last rounding can differ.
  EXPECT_DOUBLE_EQ(ramp(RampCurve::smoothstep, 0.5, 2.0), 0.15625);
  EXPECT_DOUBLE_EQ(ramp(RampCurve::smootherstep, 0.5, 2.0), 0.103515625);
  // Both are symmetric about the middle: 1/2 there.
  EXPECT_DOUBLE_EQ(ramp(RampCurve::smoothstep, 1.0, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(ramp(RampCurve::smootherstep, 1.0, 2.0), 0.5);
  // Scaled: 4000 N at u = 1/4 of a smoothstep is 625 N.
  EXPECT_DOUBLE_EQ(ramp(RampCurve::smoothstep, 0.5, 2.0, 4000.0), 625.0);
}

TEST(Ramp, StartsAtZeroAndHoldsTheFullValue) {
  for (RampCurve c : {RampCurve::smoothstep, RampCurve::smootherstep}) {
    EXPECT_EQ(ramp(c, 0.0, 0.3, 7.0), 0.0);
    EXPECT_EQ(ramp(c, 0.3, 0.3, 7.0), 7.0);
    EXPECT_EQ(ramp(c, 5.0, 0.3, 7.0), 7.0);
    EXPECT_EQ(ramp(c, 0.1, 0.0, 7.0), 7.0);  // no ramp: full at once
  }
}

TEST(Ramp, EndConditions) {
  // One-sided differences at both ends with step h = 1e-4 of the ramp:
  // slope ~ 3h (smoothstep) and ~ 10 h^2 (smootherstep), so zero within 1e-3;
  // the second difference shows smoothstep's end curvature 6 and smootherstep's 0
  // (60 h there), each within 1e-2.
  const double T = 1.0, h = 1e-4;
  for (double end : {0.0, 1.0}) {
    const double s = end == 0.0 ? 1.0 : -1.0;  // step into the ramp
    for (RampCurve c : {RampCurve::smoothstep, RampCurve::smootherstep}) {
      const double f0 = ramp(c, end, T), f1 = ramp(c, end + s * h, T), f2 = ramp(c, end + 2 * s * h, T);
      EXPECT_NEAR((f1 - f0) / h, 0.0, 1e-3);
      const double curvature = (f2 - 2 * f1 + f0) / (h * h);
      if (c == RampCurve::smoothstep)
        EXPECT_NEAR(std::abs(curvature), 6.0, 1e-2);
      else
        EXPECT_NEAR(curvature, 0.0, 1e-2);
    }
  }
}

TEST(Ramp, MeanValueIsOneHalfAndMonotone) {
  // int_0^1 (3u^2 - 2u^3) du = 1 - 1/2 and int_0^1 (10u^3 - 15u^4 + 6u^5) du = 5/2 - 3 + 1:
  // both 1/2. Simpson's rule with 1000 panels is exact for the cubic and within
  // ~1e-13 for the quintic (error ~ f'''' / 180 h^4).
  const int n = 1000;
  for (RampCurve c : {RampCurve::smoothstep, RampCurve::smootherstep}) {
    double sum = 0.0, previous = -1.0;
    for (int i = 0; i <= n; ++i) {
      const double f = ramp(c, static_cast<double>(i) / n, 1.0);
      sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
      EXPECT_GE(f, previous);
      previous = f;
    }
    EXPECT_NEAR(sum / (3.0 * n), 0.5, 1e-12);
  }
}

}  // namespace
