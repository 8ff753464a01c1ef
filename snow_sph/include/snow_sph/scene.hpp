#pragma once
// From a scene to a runtime model: validation with file:line:field messages
// and model building (particle lattices, materials, walls, bodies).
#include "cosim/scene_io.hpp"
#include "snow_sph/model.hpp"

namespace snow_sph {

// Checks every SPH field of the scene: ranges, physical admissibility and
// cross-field rules (bodies inside the box, a fixed time step within the
// stable limit, ...). Adds one line per problem to `report`.
void validate_sph_scene(const cosim::LoadedScene& scene, cosim::ValidationReport& report);

// load_scene with the overrides, then validate_sph_scene; throws cosim::Error
// listing every problem with its file:line:field.
std::unique_ptr<cosim::LoadedScene> load_sph_scene(const std::string& path, const std::vector<std::string>& sets);

MaterialModel material_from_scene(const cosim::scene::Material& material);

// Builds the model of a validated scene.
Model build_model(const cosim::scene::Scene& scene);

// Largest elastic wave speed of the scene's materials at rest [m/s].
double max_sound_speed(const cosim::scene::SphTerrain& sph);

}  // namespace snow_sph
