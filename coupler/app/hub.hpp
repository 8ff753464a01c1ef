#pragma once
// The coupler's step loop: the synchronising hub of a coupled run. Each step it
// takes the tyre's surface kinematics, attaches the friction coefficient of
// every facet (the one place friction is decided, coupler/friction.hpp), hands
// them to the terrain, takes the terrain's contact loads, hands them to the
// tyre and publishes the force decomposition (coupler/forces.hpp).
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "cosim_coupling/session.hpp"
#include "cosim/scene_io.hpp"

namespace coupler {

using cosim::coupling::Session;
namespace tp = cosim::transport;
using cosim::coupling::channel_qos;
using cosim::coupling::kTerrainChannel;
using cosim::coupling::kTyreChannel;

struct HubOptions {
  std::string out_dir;
  bool quiet = false;
  bool restart = false;                     // continue from a checkpoint in out_dir
  std::optional<std::uint64_t> restart_at;  // that of this exchange (else the newest)
};

// Runs until the tyre stops the run; writes forces.csv and summary.json to
// out_dir. On failure tells the peers, keeps forces.csv up to the last
// completed step, writes summary.json with "status": "failed" and rethrows.
nlohmann::json run_hub(Session& session, const cosim::LoadedScene& scene, const HubOptions& options);

}  // namespace coupler
