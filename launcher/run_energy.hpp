#pragma once
// Where a coupled run's work went (docs/force_decomposition.md, "Where the work
// goes"): the terrain's and the tyre's energy splits side by side in the run's
// summary.json, and the motion resistance's work F1 dx beside the terrain's
// plastic work over the same travel.
#include <string>

#include <nlohmann/json.hpp>

namespace cosim {

// The run's `energy`: the terrain's and the tyre's `energy` objects, the
// motion resistance's work and the distance the rim travelled (the coupler's
// results), and the terrain's plastic work (cap and shear) over the whole run
// and from the start of the rim's travel (read from terrain/energy.csv in
// `run_dir`). Null without a coupler's motion resistance work.
nlohmann::json coupled_run_energy(const std::string& run_dir, const nlohmann::json& coupler,
                                  const nlohmann::json& terrain, const nlohmann::json& tyre);

// The tables of the terrain and the tyre and the motion resistance's line, as a run prints them.
std::string coupled_run_energy_text(const nlohmann::json& energy);

}  // namespace cosim
