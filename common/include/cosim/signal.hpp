#pragma once
// Signals of a run's time series.
#include <vector>

namespace cosim {

// Centred moving mean of samples v at times t (ascending): each output is the
// mean of the samples within window_s / 2 on either side of its time (fewer at
// the ends). The coupled forces swing by +-1000 N per step on a coarse scene as
// particles enter and leave contact; this is the line drawn over them.
// window_s <= 0 returns v. Throws cosim::Error if t and v differ in length.
std::vector<double> centred_moving_mean(const std::vector<double>& t, const std::vector<double>& v, double window_s);

}  // namespace cosim
