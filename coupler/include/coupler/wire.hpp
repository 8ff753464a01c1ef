#pragma once
// Between the neutral topic structs (cosim_transport/topics.hpp, mirrors of
// idl/cosim_topics.idl) and the coupler's physics inputs and outputs.
#include <string>

#include "coupler/facet_geometry.hpp"
#include "coupler/forces.hpp"
#include "cosim_transport/topics.hpp"

namespace coupler {

// Per contacted facet of `loads`: its tag, the pressure force -N n from the
// facet's outward normal in `geometry`, the tangential force, centroid and
// contact area. `tags` and `geometry` cover every surface facet (SurfaceMesh;
// geometry from the current node positions). Throws cosim::Error on size
// mismatches or facet indices out of range.
FacetLoads facet_loads_from_contact(const cosim::transport::ContactLoads& loads, const std::vector<FacetTag>& tags,
                                    const FacetGeometry& geometry);

// Throws cosim::Error naming `what` and the field if a value is not finite.
void check_wheel_state(const cosim::transport::WheelState& wheel, const std::string& what);

// The rim state the decomposition needs, with the rolling radius r (eq. 5.1).
WheelInput wheel_input(const cosim::transport::WheelState& wheel, double rolling_radius_m);

// The ForceSummary sample of a decomposition: every field of the topic from the
// decomposition's field of the same name (a topic field the decomposition does
// not compute fails to compile here).
cosim::transport::ForceSummary force_summary(const ForceDecomposition& d, const cosim::transport::SampleHeader& header);

}  // namespace coupler
