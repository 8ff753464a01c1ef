#pragma once
// `cosim run` for a coupled scene: starts tyre_fe, snow_sph and the coupler on
// this machine with one run id and DDS domain, each on the vendor asked for
// (--dds tyre=fast,terrain=cyclone,coupler=cyclone), waits for all three and
// writes the run's summary.json from theirs.
#include <map>
#include <string>

#include "cosim/scene_io.hpp"
#include "cosim_transport/transport.hpp"

namespace cosim {

struct RunRequest;

// "fast" / "cyclone" (every process) or "tyre=fast,terrain=cyclone,coupler=cyclone"
// (roles not named get cyclone). Throws cosim::Error naming a bad role or vendor.
std::map<std::string, transport::Vendor> parse_vendor_map(const std::string& text);

// Runs the three processes; returns the launcher's exit code (0 if all succeeded).
int run_coupled(const RunRequest& request, const LoadedScene& scene);

}  // namespace cosim
