// What crossed the coupler over a run; see exchange_payload.hpp.
#include "coupler/exchange_payload.hpp"

namespace coupler {

void ExchangePayload::save(cosim::CheckpointWriter& out, const std::string& prefix) const {
  out.put_value(prefix + "forwarding_s", forwarding_s);
  out.put_value(prefix + "nodes_sent", nodes_sent);
  out.put_value(prefix + "facets_sent", facets_sent);
  out.put_value(prefix + "loaded_nodes", loaded_nodes);
}

void ExchangePayload::restore(const cosim::CheckpointReader& in, const std::string& prefix) {
  forwarding_s = in.get_value<double>(prefix + "forwarding_s");
  nodes_sent = in.get_value<double>(prefix + "nodes_sent");
  facets_sent = in.get_value<double>(prefix + "facets_sent");
  loaded_nodes = in.get_value<double>(prefix + "loaded_nodes");
}

nlohmann::json ExchangePayload::per_exchange(std::uint64_t exchanges) const {
  const double steps = static_cast<double>(exchanges);
  return {{"mean_surface_nodes_per_step", exchanges ? nodes_sent / steps : 0.0},
          {"mean_surface_facets_per_step", exchanges ? facets_sent / steps : 0.0},
          {"mean_loaded_nodes_per_step", exchanges ? loaded_nodes / steps : 0.0}};
}

}  // namespace coupler
