#pragma once
// Where the work done on the terrain goes (docs/sph.md, "Energy balance"):
// each term of EnergyBalance under its summary key, as summary.json's
// `energy`, energy.csv's columns, the table a run prints and the stacked
// plot (energy_split.png) show it.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/energy_table.hpp"
#include "snow_sph/step_state.hpp"

namespace snow_sph {

using cosim::EnergyValue;

// The split's terms beyond energy.csv's first columns: the work done by
// source and in total, each part of the lumped dissipations, the changes of
// the stored energies, and the balance. Within rounding,
//   sum of terrain_energy_split().went_to - work_on_terrain_J = balance_J.
std::vector<EnergyValue> energy_split(const EnergyBalance& e);

// The rows of the printed table, in the order the stacked plot stacks them.
const cosim::EnergySplit& terrain_energy_split();

// The table of a terrain summary's `energy` object.
std::string terrain_energy_table(const nlohmann::json& energy);

}  // namespace snow_sph
