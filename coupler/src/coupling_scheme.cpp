// The coupling window from the peers' stable steps; see coupling_scheme.hpp.
#include "coupler/coupling_scheme.hpp"

#include <algorithm>
#include <string>

#include "cosim/coupling_window.hpp"
#include "cosim/error.hpp"

namespace coupler {

CouplingWindow choose_coupling_window(double tyre_proposed_dt_s, double terrain_proposed_dt_s,
                                      cosim::scene::CouplingScheme scheme) {
  const double tyre_dt = tyre_proposed_dt_s, terrain_dt = terrain_proposed_dt_s;
  if (!(tyre_dt > 0) || !(terrain_dt > 0))
    throw cosim::Error("the tyre (" + cosim::number_text(tyre_dt) + " s) and the terrain (" +
                       cosim::number_text(terrain_dt) + " s) must both propose a stable step");
  CouplingWindow w;
  w.tyre_proposed_dt_s = tyre_dt, w.terrain_proposed_dt_s = terrain_dt;
  w.common_step = scheme == cosim::scene::COMMON_STEP;
  w.window_s = w.common_step ? std::min(tyre_dt, terrain_dt) : terrain_dt;
  w.tyre_substeps = cosim::substeps_per_window(w.window_s, tyre_dt);
  return w;
}

const char* coupling_window_reason(const CouplingWindow& window) {
  return window.common_step ? "common step: the smaller stable step"
                            : "multi-rate: the terrain's step, the tyre sub-cycles";
}

nlohmann::json time_step_summary(const CouplingWindow& w) {
  return {{"agreed_dt_s", w.window_s},
          {"coupling_window_s", w.window_s},
          {"tyre_substeps", w.tyre_substeps},
          {"tyre_proposed_dt_s", w.tyre_proposed_dt_s},
          {"terrain_proposed_dt_s", w.terrain_proposed_dt_s},
          {"scheme", w.common_step ? "common step: one step for both, every step exchanged"
                                   : "multi-rate: one exchange per terrain step, the tyre sub-cycles "
                                     "with the terrain's loads held"}};
}

}  // namespace coupler
