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

// Defaults read in code, each in one place (the schema's `default_value` holds
// the others, configs/schema/scene.proto).
// The FE bodies' time-step safety factor: time.cfl, 0.8 when left out. Not a
// schema default: snow_sph reads the same field and refuses a scene without it
// (snow_sph/src/scene.cpp), which a default would silently accept.
double time_step_safety(const cosim::scene::Scene& scene);
// The rolling stage's averaging window: stages.average_last_s, or the second
// half of the rolling stage when left out (a default taken from another field).
double averaging_window_s(const cosim::scene::TyreStages& stages);
// A rubber's bulk-to-shear ratio K0/mu0: its own, or its body's (the tyre's,
// the tread block's) when left out (a default taken from another field).
double rubber_bulk_to_shear_ratio(const cosim::scene::YeohRubberMaterial& rubber, double body_ratio);

}  // namespace tyre_fe
