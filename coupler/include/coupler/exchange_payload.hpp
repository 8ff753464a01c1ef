#pragma once
// What crossed the coupler over a run: the wall time it spent forwarding the
// samples and the sizes of what it forwarded (summary "payload"; the transport's
// share of a window, docs/coupling.md "Figures").
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/checkpoint.hpp"

namespace coupler {

struct ExchangePayload {
  double forwarding_s = 0.0;  // writing the samples on to the peers
  double nodes_sent = 0.0, facets_sent = 0.0;  // surface nodes and facets to the terrain
  double loaded_nodes = 0.0;                   // loaded nodes to the tyre

  // Each a named field under `prefix` ("<prefix>forwarding_s", ...), and back.
  void save(cosim::CheckpointWriter& out, const std::string& prefix) const;
  void restore(const cosim::CheckpointReader& in, const std::string& prefix);
  // The means per exchange over `exchanges` (0: all 0).
  nlohmann::json per_exchange(std::uint64_t exchanges) const;
};

}  // namespace coupler
