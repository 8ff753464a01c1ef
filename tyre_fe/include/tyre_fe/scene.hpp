#pragma once
// From a scene's `tyre` section to the tyre model: validation with
// file:line:field messages, materials (file + inline), geometry settings.
#include <string>

#include "cosim/scene_io.hpp"
#include "tyre_fe/axisym.hpp"
#include "tyre_fe/geometry.hpp"

namespace tyre_fe {

// Everything the tyre run needs, resolved from the scene.
struct TyreSetup {
  TyreSize size;
  std::string size_designation;
  std::string cross_section_inp;  // resolved path, empty: generated
  CrossSectionMesh mesh;
  TreadPattern pattern;
  TyreMaterials materials;
  std::string materials_source;
  double bulk_to_shear_ratio = 20.0;
  bool bead_tied_to_rim = true;  // scene: tyre.rim.deformable_bead = false
};

// Checks the tyre section: ranges, materials of all regions, tread pattern rules.
void validate_tyre_scene(const cosim::LoadedScene& scene, cosim::ValidationReport& report);

// Resolves a validated scene (throws cosim::Error naming file:line on a bad materials file).
TyreSetup tyre_setup(const cosim::LoadedScene& scene);

// The cross-section of the setup: generated from the size or imported.
CrossSection make_section(const TyreSetup& setup);

}  // namespace tyre_fe
