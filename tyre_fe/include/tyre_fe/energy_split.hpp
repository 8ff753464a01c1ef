#pragma once
// Where the work done on the tyre goes (docs/tyre_fe.md, "Energy balance"):
// each term of Energies under its summary key, as summary.json's `energy`,
// tyre.csv's last columns, the table a run prints and the stacked plot
// (energy_split.png) show it.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/energy_table.hpp"
#include "tyre_fe/solver3d.hpp"

namespace tyre_fe {

// The work done on the tyre by source and in total (the rim: wheel load, drive
// torque and prescribed motion; the inflation pressure; the road's and the
// terrain's contact forces), the strain energy, and where the work went: the
// changes of strain, hourglass and kinetic energy since the first step, the
// bulk viscosity's and the mass damping's dissipation, and the balance.
// Within rounding, sum of tyre_energy_split().went_to - work_on_tyre_J = balance_J.
std::vector<cosim::EnergyValue> energy_split(const Energies& e);

// The rows of the printed table, in the order the stacked plot stacks them.
const cosim::EnergySplit& tyre_energy_split();

// The table of a tyre summary's `energy` object.
std::string tyre_energy_table(const nlohmann::json& energy);

}  // namespace tyre_fe
