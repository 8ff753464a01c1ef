#pragma once
// The coupling window of a multi-rate coupled run (docs/coupling.md): the
// solver with the smaller stable step takes an integer number of equal
// sub-steps inside each window, so that both solvers meet at every window's
// end and the momentum exchanged over a window balances exactly.
#include <cmath>

#include "cosim/error.hpp"

namespace cosim {

// Sub-steps of at most `stable_dt_s` that fill `window_s` exactly: the
// smallest N with window / N <= stable_dt (1 when the window is the smaller).
inline int substeps_per_window(double window_s, double stable_dt_s) {
  if (!(window_s > 0.0) || !(stable_dt_s > 0.0))
    throw Error("coupling window " + number_text(window_s) + " s and stable step " +
                number_text(stable_dt_s) + " s must both be > 0");
  // The relative 1e-12 keeps a window that is an exact multiple from taking one more.
  const double n = std::ceil(window_s / stable_dt_s * (1.0 - 1e-12));
  if (n > 1e6) throw Error("coupling window holds more than a million sub-steps");
  return n < 1.0 ? 1 : static_cast<int>(n);
}

}  // namespace cosim
