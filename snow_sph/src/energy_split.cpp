// Where the work done on the terrain goes; see energy_split.hpp.
#include "snow_sph/energy_split.hpp"

namespace snow_sph {

std::vector<EnergyValue> energy_split(const EnergyBalance& e) {
  const double work = e.work_on_terrain();
  return {{"gravity_work_J", e.gravity_work},
          {"wall_work_J", e.wall_work},
          {"body_work_J", e.body_work},
          {"resting_terrain_work_J", e.resting_terrain_work},
          {"coupled_surface_work_on_particles_J", e.surface_work_on_particles},
          {"coupled_surface_work_J", e.coupled_surface_work()},
          {"work_on_terrain_J", work},
          {"plastic_cap_J", e.plastic_cap},
          {"plastic_shear_J", e.plastic_shear},
          {"artificial_viscous_dissipation_J", e.artificial_viscous},
          {"damping_dissipation_J", e.damping},
          {"water_viscous_dissipation_J", e.water_viscous},
          {"surface_friction_dissipation_J", e.surface_friction},
          {"surface_damping_dissipation_J", e.surface_damping},
          {"surface_contact_elastic_change_J", e.surface_contact_elastic - e.initial_surface_contact_elastic},
          {"contact_elastic_J", e.contact_elastic},
          {"internal_less_plastic_J", e.internal - e.plastic_dissipation},
          {"kinetic_change_J", e.kinetic - e.initial_kinetic},
          {"deactivated_kinetic_J", e.deactivated_kinetic},
          {"drained_kinetic_J", e.drained_kinetic},
          {"balance_J", e.total() - e.initial_total},
          {"artificial_viscous_share", work != 0.0 ? e.artificial_viscous / work : 0.0}};
}

const cosim::EnergySplit& terrain_energy_split() {
  static const cosim::EnergySplit split{"Where the work done on the terrain went",
                                        {{"gravity_work_J", "gravity"},
                                         {"wall_work_J", "the walls' repulsion"},
                                         {"body_work_J", "rigid bodies' loads and prescribed motion"},
                                         {"resting_terrain_work_J", "resting terrain (outside the active domain)"},
                                         {"coupled_surface_work_J", "coupled surface (tyre), at the surface"}},
                                        {"work_on_terrain_J", "total"},
                                        {{"plastic_cap_J", "plastic work on the cap"},
                                         {"plastic_shear_J", "plastic work on the shear/transition surfaces"},
                                         {"artificial_viscous_dissipation_J", "artificial viscosity (Monaghan Pi)"},
                                         {"damping_dissipation_J", "quasi-static damping"},
                                         {"water_viscous_dissipation_J", "water's viscosity"},
                                         {"surface_friction_dissipation_J", "particle-facet friction"},
                                         {"surface_damping_dissipation_J", "particle-facet contact damping"},
                                         {"surface_contact_elastic_change_J", "particle-facet contact springs"},
                                         {"contact_dissipation_J", "rigid bodies' contact, dissipated"},
                                         {"contact_elastic_J", "rigid bodies' contact springs"},
                                         {"internal_less_plastic_J", "elastic (stress power less plastic work)"},
                                         {"kinetic_change_J", "kinetic energy left in the terrain"},
                                         {"deactivated_kinetic_J", "kinetic energy set at rest (active domain)"},
                                         {"drained_kinetic_J", "kinetic energy of drained water"}},
                                        {"balance_J", "balance (went to less done)"}};
  return split;
}

std::string terrain_energy_table(const nlohmann::json& energy) {
  return cosim::energy_table(terrain_energy_split(), energy);
}

}  // namespace snow_sph
