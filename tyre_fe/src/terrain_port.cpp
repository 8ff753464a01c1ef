#include "tyre_fe/terrain_port.hpp"

#include <unordered_map>

namespace tyre_fe {

ContactSurfaceDef make_contact_surface(const Model3d& model) {
  ContactSurfaceDef surface;
  std::unordered_map<int, std::uint32_t> surface_index;
  for (const auto& facet : model.mesh.facets) {
    // The inner liner faces the inflation gas and the rim faces are held by the rim.
    if (facet.tag == SurfaceTag::inner_liner || facet.tag == SurfaceTag::rim_contact) continue;
    for (int n : facet.nodes) {
      auto [it, added] = surface_index.emplace(n, static_cast<std::uint32_t>(surface.node_ids.size()));
      if (added) surface.node_ids.push_back(n);
      surface.facet_nodes.push_back(it->second);
    }
    surface.facet_tags.push_back(facet.tag);
  }
  return surface;
}

}  // namespace tyre_fe
