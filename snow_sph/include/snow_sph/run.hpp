#pragma once
#include <cstdint>
#include <optional>
// Running an SPH scene end to end: model -> step loop -> outputs
// (summary.json, CSV time series, VTK). See docs/outputs.md for the files.
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/scene_io.hpp"
#include "snow_sph/surface_exchange.hpp"

namespace snow_sph {

struct RunOptions {
  std::string out_dir;
  bool quiet = false;       // no progress line
  bool write_vtk = true;    // false: skip VTK even if the scene asks (tests)
  // Continue the run in out_dir from its newest checkpoint (docs/reliability.md).
  bool restart = false;
  // With restart: the checkpoint of this step (a coupled run: this exchange)
  // instead of the newest; `cosim run --restart` gives every process the same.
  std::optional<std::uint64_t> restart_at;
  // Non-null: the terrain of a coupled run; it runs until the surface's owner
  // ends the run, with the common step agreed through the exchange.
  SurfaceExchange* exchange = nullptr;
};

// Runs the scene; returns the summary (also written to out_dir/summary.json).
// On failure the summary is written with "status": "failed" and the error,
// every output written so far is kept, and cosim::Error is rethrown.
nlohmann::json run_scene(const cosim::LoadedScene& scene, const RunOptions& options);

}  // namespace snow_sph
