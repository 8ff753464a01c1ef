#pragma once
// The coupling window of a coupled run, decided once from the two stable steps
// the peers propose when they join (docs/coupling.md, "A coupling window"):
//  - multi-rate (the default): the window is the terrain's stable step and the
//    tyre, whose step is the smaller, sub-cycles inside it with the terrain's
//    loads held (cosim::substeps_per_window);
//  - common step (the reference): both take the smaller of the two steps and
//    every step is exchanged.
#include <nlohmann/json.hpp>

#include "scene.pb.h"

namespace coupler {

struct CouplingWindow {
  double tyre_proposed_dt_s = 0.0;
  double terrain_proposed_dt_s = 0.0;
  bool common_step = false;  // scene coupling.scheme COMMON_STEP
  double window_s = 0.0;     // one exchange per window
  int tyre_substeps = 1;     // the tyre's steps inside one window
};

// Throws cosim::Error unless both proposed steps are > 0.
CouplingWindow choose_coupling_window(double tyre_proposed_dt_s, double terrain_proposed_dt_s,
                                      cosim::scene::CouplingScheme scheme);

// The one-line reason given to the peers with the window (Session::announce_start).
const char* coupling_window_reason(const CouplingWindow& window);

// The summary's "time_step" section: the window, the sub-steps, what each peer proposed, the scheme.
nlohmann::json time_step_summary(const CouplingWindow& window);

}  // namespace coupler
