#pragma once
#include <cstdint>
#include <optional>
// Running a tyre scene end to end: cross-section -> axisymmetric inflation ->
// revolve (results transfer) -> 3D check at rest -> loading on the road ->
// rolling, with summary.json, CSV time series, VTK and PNG outputs
// (docs/tyre_fe.md lists them).
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/scene_io.hpp"
#include "tyre_fe/terrain_port.hpp"

namespace tyre_fe {

struct RunOptions {
  std::string out_dir;
  bool quiet = false;
  bool write_vtk = true;
  bool mesh_only = false;  // also set by the scene's tyre.mesh_only
  // Continue the run in out_dir from its newest checkpoint (docs/reliability.md).
  bool restart = false;
  // With restart: the checkpoint of this step (a coupled run: this exchange)
  // instead of the newest; `cosim run --restart` gives every process the same.
  std::optional<std::uint64_t> restart_at;
  // Non-null: the tyre runs on this terrain solver instead of its rigid road
  // (the coupled executable passes its DDS port).
  TerrainPort* terrain = nullptr;
};

// Runs the scene; returns the summary (also written to out_dir/summary.json).
// On failure the summary says "status": "failed" with the error, all outputs so
// far are kept, and cosim::Error is rethrown.
nlohmann::json run_tyre_scene(const cosim::LoadedScene& scene, const RunOptions& options);

// The same for a scene's `tread_block` (tread_block.hpp): on a terrain solver only.
nlohmann::json run_tread_block_scene(const cosim::LoadedScene& scene, const RunOptions& options);

// The scene's FE body, whichever it has: the checks of the tyre and of the tread
// block (each passes a scene without its section), and its run.
void validate_fe_body_scene(const cosim::LoadedScene& scene, cosim::ValidationReport& report);
nlohmann::json run_fe_body_scene(const cosim::LoadedScene& scene, const RunOptions& options);

}  // namespace tyre_fe
