// cosim::centred_moving_mean (common/include/cosim/signal.hpp), the line drawn
// over the coupled forces' per-step signal. Analytic references:
// - the mean of a straight line over a window symmetric about t is its value at
//   t, so inside the series the mean reproduces the line (to round-off: 1e-12
//   relative, a sum of ~1e3 terms of order 1);
// - the moving mean of a sampled sine is the sine times the moving average's
//   transfer function (the Dirichlet kernel), 1/99 for 99 samples of a
//   100-sample period: the swing is removed to 1 % (to round-off, 1e-9 of 1000);
// - at the ends the window holds fewer samples: the first output of a line is
//   the mean of the samples within half a window of it, computed here by hand
//   for a 4-sample case.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/error.hpp"
#include "cosim/signal.hpp"

namespace {

TEST(CentredMovingMean, ReproducesAStraightLineInside) {
  std::vector<double> t, v;
  for (int i = 0; i < 2000; ++i) t.push_back(1e-4 * i), v.push_back(3.0 + 250.0 * t.back());
  // 50 samples a side; the half-window (0.005025 s) falls between samples, so
  // that rounding of the sample times cannot make the window lopsided.
  const double window = 0.01005;
  const auto m = cosim::centred_moving_mean(t, v, window);
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] > window && t[i] < t.back() - window) {
      EXPECT_NEAR(m[i], v[i], 1e-12 * std::fabs(v[i])) << i;
    }
}

TEST(CentredMovingMean, ASineIsDampedByTheMovingAveragesTransferFunction) {
  const double period = 0.01;
  std::vector<double> t, v;
  for (int i = 0; i < 1000; ++i) t.push_back(period / 100 * i + period / 200), v.push_back(1000.0 * std::sin(2 * M_PI * t.back() / period));
  // A window just under one period holds 2k + 1 = 99 samples (k = 49 a side);
  // the mean of 2k + 1 samples of sin(w t) spaced d about t_i is
  // sin(w t_i) sin((2k + 1) w d / 2) / ((2k + 1) sin(w d / 2)), here with
  // w d = 2 pi / 100: sin(99 pi / 100) / (99 sin(pi / 100)) = 1 / 99.
  const auto m = cosim::centred_moving_mean(t, v, period * 0.999);
  for (std::size_t i = 60; i + 60 < t.size(); ++i) EXPECT_NEAR(m[i], v[i] / 99.0, 1e-9) << i;
}

TEST(CentredMovingMean, FewerSamplesAtTheEnds) {
  const std::vector<double> t{0.0, 1.0, 2.0, 3.0}, v{1.0, 2.0, 4.0, 8.0};
  const auto m = cosim::centred_moving_mean(t, v, 2.0);  // +-1 s
  EXPECT_DOUBLE_EQ(m[0], (1.0 + 2.0) / 2);
  EXPECT_DOUBLE_EQ(m[1], (1.0 + 2.0 + 4.0) / 3);
  EXPECT_DOUBLE_EQ(m[3], (4.0 + 8.0) / 2);
  EXPECT_EQ(cosim::centred_moving_mean(t, v, 0.0), v);  // no window: the signal
  EXPECT_THROW(cosim::centred_moving_mean(t, {1.0}, 1.0), cosim::Error);
}

}  // namespace
