#pragma once
// `cosim run` for a coupled scene: starts tyre_fe, snow_sph and the coupler on
// this machine with one run id and DDS domain, each on the vendor asked for
// (--dds tyre=fast,terrain=cyclone,coupler=cyclone), waits for all three and
// writes the run's summary.json from theirs.
#include <array>
#include <cstdint>
#include <map>
#include <string>

#include "cosim/scene_io.hpp"
#include "cosim_transport/transport.hpp"

namespace cosim {

struct RunRequest;

// The three processes of a coupled run: each one's role (its name in --dds and
// its folder in the run's output) and its program, in the order they start.
struct CoupledProcess {
  const char* role;
  const char* program;
};
inline constexpr std::array<CoupledProcess, 3> coupled_processes{
    {{"coupler", "coupler"}, {"terrain", "snow_sph"}, {"tyre", "tyre_fe"}}};

// The newest exchange of which every process of the run in `out` has a
// checkpoint (0: none); `listing` says which each has.
std::uint64_t newest_common_checkpoint(const std::string& out, std::string& listing);

// "fast" / "cyclone" (every process) or "tyre=fast,terrain=cyclone,coupler=cyclone"
// (roles not named get cyclone). Throws cosim::Error naming a bad role or vendor.
std::map<std::string, transport::Vendor> parse_vendor_map(const std::string& text);

// Runs the three processes; returns the launcher's exit code (0 if all succeeded).
int run_coupled(const RunRequest& request, const LoadedScene& scene);

}  // namespace cosim
