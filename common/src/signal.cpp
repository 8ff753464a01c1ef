#include "cosim/signal.hpp"

#include "cosim/error.hpp"

namespace cosim {

std::vector<double> centred_moving_mean(const std::vector<double>& t, const std::vector<double>& v, double window_s) {
  if (t.size() != v.size()) throw Error("centred_moving_mean: times and values differ in length");
  if (window_s <= 0.0) return v;
  const double half = 0.5 * window_s;
  std::vector<double> out(v.size());
  // Two pointers over the window [lo, hi): each sample enters and leaves once.
  std::size_t lo = 0, hi = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    while (hi < v.size() && t[hi] <= t[i] + half) sum += v[hi++];
    while (t[lo] < t[i] - half) sum -= v[lo++];
    out[i] = sum / static_cast<double>(hi - lo);
  }
  return out;
}

}  // namespace cosim
