#include "tyre_fe/terrain_port.hpp"

#include <unordered_map>

#include "tyre_fe/solver3d.hpp"

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
  for (int n : surface.node_ids)
    surface.x_m.push_back(mesh.nodes[n][0]), surface.y_m.push_back(mesh.nodes[n][1]), surface.z_m.push_back(mesh.nodes[n][2]);
  return surface;
}

ContactSurfaceDef make_contact_surface(const Model3d& model, const State3d& s) {
  ContactSurfaceDef surface = make_contact_surface(model.mesh);
  for (std::size_t k = 0; k < surface.node_ids.size(); ++k) {
    const int n = surface.node_ids[k];
    surface.x_m[k] = s.x[n], surface.y_m[k] = s.y[n], surface.z_m[k] = s.z[n];
    surface.node_mass_kg.push_back(model.node_mass_kg[n]);
  }
  return surface;
}

void surface_near_terrain(const ContactSurfaceDef& surface, const State3d& s, double band_m,
                          cosim::SurfaceState& out) {
  out.exchange = s.terrain.exchange;
  out.time_s = s.time_s;
  out.nodes.clear(), out.facets.clear(), out.friction_coefficient.clear();
  out.x_m.clear(), out.y_m.clear(), out.z_m.clear(), out.vx_mps.clear(), out.vy_mps.clear(), out.vz_mps.clear();
  std::vector<char> included(surface.node_ids.size(), 0);
  for (std::size_t f = 0; f < surface.facet_count(); ++f) {
    const std::uint32_t* fn = &surface.facet_nodes[4 * f];
    bool near = false;
    for (int a = 0; a < 4; ++a) near = near || s.z[surface.node_ids[fn[a]]] < band_m;
    if (!near) continue;
    out.facets.push_back(static_cast<std::uint32_t>(f));
    for (int a = 0; a < 4; ++a) included[fn[a]] = 1;
  }
  for (std::size_t j = 0; j < surface.node_ids.size(); ++j) {
    if (!included[j]) continue;
    const int i = surface.node_ids[j];
    out.nodes.push_back(static_cast<std::uint32_t>(j));
    out.x_m.push_back(s.x[i]), out.y_m.push_back(s.y[i]), out.z_m.push_back(s.z[i]);
    out.vx_mps.push_back(s.vx[i]), out.vy_mps.push_back(s.vy[i]), out.vz_mps.push_back(s.vz[i]);
  }
}

}  // namespace tyre_fe
