#include "tyre_fe/terrain_port.hpp"

#include <unordered_map>

namespace tyre_fe {

ContactSurfaceDef make_contact_surface(const Mesh3D& mesh) {
  ContactSurfaceDef surface;
  std::unordered_map<int, std::uint32_t> surface_index;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    const auto& facet = mesh.facets[f];
    // The inner liner faces the inflation gas and the rim faces are held by the rim.
    if (facet.tag == SurfaceTag::inner_liner || facet.tag == SurfaceTag::rim_contact) continue;
    for (int n : facet.nodes) {
      auto [it, added] = surface_index.emplace(n, static_cast<std::uint32_t>(surface.node_ids.size()));
      if (added) surface.node_ids.push_back(n);
      surface.facet_nodes.push_back(it->second);
    }
    surface.facet_tags.push_back(facet.tag);
    surface.mesh_facets.push_back(static_cast<int>(f));
  }
  return surface;
}

ContactSurfaceDef make_contact_surface(const Model3d& model) {
  ContactSurfaceDef surface = make_contact_surface(model.mesh);
  for (int n : surface.node_ids) surface.node_mass_kg.push_back(model.node_mass_kg[n]);
  return surface;
}

}  // namespace tyre_fe
