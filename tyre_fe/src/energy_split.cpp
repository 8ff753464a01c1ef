// Where the work done on the tyre goes; see energy_split.hpp.
#include "tyre_fe/energy_split.hpp"

namespace tyre_fe {

std::vector<cosim::EnergyValue> energy_split(const Energies& e) {
  const double initial_kinetic_J = e.initial_J - e.initial_internal_J;
  return {{"rim_work_J", e.external_work_J - e.pressure_work_J},
          {"pressure_work_J", e.pressure_work_J},
          {"contact_work_J", e.contact_work_J},
          {"work_on_tyre_J", e.external_work_J + e.contact_work_J},
          {"strain_energy_J", e.internal_J - e.hourglass_J},
          {"strain_energy_change_J", e.internal_J - e.hourglass_J - (e.initial_internal_J - e.initial_hourglass_J)},
          {"hourglass_change_J", e.hourglass_J - e.initial_hourglass_J},
          {"kinetic_change_J", e.kinetic_J - initial_kinetic_J},
          {"bulk_viscous_dissipation_J", -e.bulk_viscous_work_J},
          {"mass_damping_dissipation_J", -(e.damping_work_J - e.bulk_viscous_work_J)},
          {"balance_J", e.balance_J()}};
}

const cosim::EnergySplit& tyre_energy_split() {
  static const cosim::EnergySplit split{"Where the work done on the tyre went",
                                        {{"rim_work_J", "rim: wheel load, drive torque, prescribed motion"},
                                         {"pressure_work_J", "inflation pressure"},
                                         {"contact_work_J", "contact forces (road and terrain)"}},
                                        {"work_on_tyre_J", "total"},
                                        {{"strain_energy_change_J", "strain energy"},
                                         {"hourglass_change_J", "hourglass energy"},
                                         {"kinetic_change_J", "kinetic energy"},
                                         {"bulk_viscous_dissipation_J", "bulk viscosity"},
                                         {"mass_damping_dissipation_J", "mass damping (and velocity resets)"}},
                                        {"balance_J", "balance (went to less done)"}};
  return split;
}

std::string tyre_energy_table(const nlohmann::json& energy) { return cosim::energy_table(tyre_energy_split(), energy); }

}  // namespace tyre_fe
