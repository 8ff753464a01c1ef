#pragma once
// The coupler's outputs beside forces.csv: the contact pressure map of the last
// exchange and the plots of a run (contact_pressure.png, forces.png with its
// filtered series forces_filtered.csv).
#include <string>

#include "coupler/forces.hpp"
#include "cosim/participant.hpp"

namespace coupler {

// contact_pressure.csv: per contacted facet, its centroid, |pressure force| / area and area.
void write_contact_pressure_map(const std::string& path, const FacetLoads& facets);

// contact_pressure.png and forces.png of the run in `record`, read from its
// contact_pressure.csv and forces.csv; a plot that cannot be drawn is left out.
void plot_coupler_outputs(cosim::RunRecord& record, const cosim::scene::Scene& scene);

}  // namespace coupler
