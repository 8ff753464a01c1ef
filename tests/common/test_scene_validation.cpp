// Bad input is refused before anything runs, with a message that names the
// file, the line and the field.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "cosim/error.hpp"
#include "test_support.hpp"
#include "tyre_fe/scene.hpp"

namespace {

const char* kValid = R"(name: "small"
time { end_time_s: 0.01 cfl: 0.3 }
sph {
  kernel: CUBIC
  particle_spacing_m: 0.02
  smoothing_length_ratio: 1.2
  gravity_m_per_s2 { z: -9.81 }
  container { min { x: 0 y: 0 z: 0 } max { x: 0.2 y: 0.2 z: 0.2 } }
  blocks {
    region { min { x: 0 y: 0 z: 0 } max { x: 0.2 y: 0.2 z: 0.1 } }
    material { material_file: "MATERIAL" }
  }
  artificial_viscosity { alpha: 1 beta: 1 }
}
)";

std::string write_scene(const std::string& name, std::string text) {
  const std::string dir = test_support::scratch("validation_" + name);
  const std::string material = test_support::source_dir() + "/configs/materials/snow_soft.textproto";
  text = std::regex_replace(text, std::regex("MATERIAL"), material);
  const std::string path = dir + "/scene.textproto";
  std::ofstream(path) << text;
  return path;
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

// Loads and validates; returns the error message ("" if accepted).
std::string error_of(const std::string& path, const std::vector<std::string>& sets = {}) {
  try {
    const auto scene = cosim::load_scene(path, sets);
    cosim::ValidationReport report;
    snow_sph::validate_sph_scene(*scene, report);
    tyre_fe::validate_tyre_scene(*scene, report);
    report.throw_if_failed();
    return "";
  } catch (const cosim::Error& e) {
    return e.what();
  }
}

struct EditedScene {
  std::string path, error;
};

// kValid with `from` replaced by `to`, written as the scene `name`, and its error ("" if accepted).
EditedScene validate_edited(const std::string& name, const std::string& from, const std::string& to) {
  const auto path = write_scene(name, replace(kValid, from, to));
  return {path, error_of(path)};
}

TEST(SceneValidation, ValidSceneIsAccepted) {
  EXPECT_EQ(error_of(write_scene("valid", kValid)), "");
}

TEST(SceneValidation, EveryShippedSceneIsValid) {
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test_support::source_dir() + "/configs/scenes"))
    if (entry.path().extension() == ".textproto") {
      EXPECT_EQ(error_of(entry.path().string()), "") << entry.path();
    }
}

TEST(SceneValidation, UnknownFieldNamesLineAndSuggests) {
  const auto [path, e] = validate_edited("unknown", "particle_spacing_m: 0.02", "particle_spacing: 0.02");
  EXPECT_NE(e.find(path + ":5:"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown field \"particle_spacing\""), std::string::npos) << e;
  EXPECT_NE(e.find("Did you mean \"particle_spacing_m\""), std::string::npos) << e;
}

TEST(SceneValidation, WrongTypeNamesLine) {
  const auto [path, e] = validate_edited("type", "particle_spacing_m: 0.02", "particle_spacing_m: \"fine\"");
  EXPECT_NE(e.find(path + ":5:"), std::string::npos) << e;
}

TEST(SceneValidation, MissingValueIsNamed) {
  const std::string e = validate_edited("missing", "  particle_spacing_m: 0.02\n", "").error;
  EXPECT_NE(e.find("sph.particle_spacing_m (not set in the file): must be > 0"), std::string::npos) << e;
}

TEST(SceneValidation, NonPositiveSpacingNamesLineAndField) {
  const auto [path, e] = validate_edited("spacing", "particle_spacing_m: 0.02", "particle_spacing_m: -0.01");
  EXPECT_NE(e.find(path + ":5:3: sph.particle_spacing_m: must be > 0"), std::string::npos) << e;
}

TEST(SceneValidation, NegativeDensityInMaterialFileIsTracedToThatFile) {
  const auto path = write_scene("density", kValid);
  const std::string e = error_of(path, {"sph.blocks[0].material.snow.density_kg_per_m3=-180"});
  EXPECT_NE(e.find("--set sph.blocks[0].material.snow.density_kg_per_m3=-180: must be > 0"), std::string::npos) << e;
  // The same error written in the scene file points at its line.
  const auto inline_path = write_scene("density_inline",
      replace(kValid, "material { material_file: \"MATERIAL\" }",
              "material { material_file: \"MATERIAL\"\n snow { density_kg_per_m3: -180 } }"));
  const std::string e2 = error_of(inline_path);
  EXPECT_NE(e2.find(inline_path + ":12:"), std::string::npos) << e2;
  EXPECT_NE(e2.find("density_kg_per_m3: must be > 0"), std::string::npos) << e2;
}

TEST(SceneValidation, PoissonRatioOfOneHalfIsRefused) {
  const auto path = write_scene("poisson", kValid);
  const std::string e = error_of(path, {"sph.blocks[0].material.snow.poisson_ratio=0.5"});
  EXPECT_NE(e.find("poisson_ratio=0.5: must be in [0, 0.5)"), std::string::npos) << e;
  // In the material file itself: the file and line of the field are named.
  const std::string material = test_support::scratch("poisson_material") + "/m.textproto";
  std::ofstream(material) << "snow {\n  density_kg_per_m3: 180\n  youngs_modulus_Pa: 1e7\n  poisson_ratio: 0.5\n}\n";
  const auto path2 = write_scene("poisson2", replace(kValid, "MATERIAL", material));
  const std::string e2 = error_of(path2);
  EXPECT_NE(e2.find(material + ":4:3: sph.blocks[0].material.snow.poisson_ratio: must be in [0, 0.5)"), std::string::npos) << e2;
}

TEST(SceneValidation, BoxSmallerThanBlockIsRefused) {
  const auto [path, e] = validate_edited("box", "max { x: 0.2 y: 0.2 z: 0.1 }", "max { x: 0.3 y: 0.2 z: 0.1 }");
  EXPECT_NE(e.find(path + ":10:"), std::string::npos) << e;
  EXPECT_NE(e.find("block does not fit in the container along x"), std::string::npos) << e;
}

TEST(SceneValidation, TimeStepAboveStableLimitIsRefusedWithTheLimit) {
  const auto [path, e] = validate_edited("dt", "cfl: 0.3", "cfl: 0.3 fixed_dt_s: 1e-3");
  EXPECT_NE(e.find(path + ":2:"), std::string::npos) << e;
  EXPECT_NE(e.find("time.fixed_dt_s: time step 0.001 s is above the stable limit h / c = "), std::string::npos) << e;
}

TEST(SceneValidation, CommandLineOverridesAreChecked) {
  const auto path = write_scene("override", kValid);
  EXPECT_NE(error_of(path, {"sph.particle_spacing=0.01"}).find("Did you mean \"particle_spacing_m\""), std::string::npos);
  EXPECT_NE(error_of(path, {"sph.particle_spacing_m=abc"}).find("is not a valid double"), std::string::npos);
  EXPECT_NE(error_of(path, {"sph.kernel=CUBICAL"}).find("--set sph.kernel=CUBICAL"), std::string::npos);
  EXPECT_EQ(error_of(path, {"sph.kernel=QUINTIC", "sph.particle_spacing_m=0.025"}), "");
}

// The container's contact with the snow: a Coulomb coefficient only with
// COULOMB, and there finite and > 0; each problem names its field.
TEST(SceneValidation, ContainerWallContactNamesTheField) {
  const auto path = write_scene("wall_contact", kValid);
  EXPECT_EQ(error_of(path, {"sph.container.floor.kind=COULOMB", "sph.container.floor.friction_coefficient=0.57"}), "");
  EXPECT_EQ(error_of(path, {"sph.container.side_walls.kind=NO_SLIP"}), "");
  const std::string zero = error_of(path, {"sph.container.floor.kind=COULOMB"});
  EXPECT_NE(zero.find("sph.container.floor.friction_coefficient (not set in the file): COULOMB needs a finite "
                      "coefficient > 0 (got 0)"),
            std::string::npos)
      << zero;
  const std::string negative =
      error_of(path, {"sph.container.side_walls.kind=COULOMB", "sph.container.side_walls.friction_coefficient=-0.2"});
  EXPECT_NE(negative.find("sph.container.side_walls.friction_coefficient"), std::string::npos) << negative;
  const std::string stray = error_of(path, {"sph.container.floor.friction_coefficient=0.3"});
  EXPECT_NE(stray.find("--set sph.container.floor.friction_coefficient=0.3: only kind COULOMB takes a friction "
                       "coefficient (got 0.3 with kind FRICTIONLESS)"),
            std::string::npos)
      << stray;
}

// A repeated number is set by index: an entry replaced in place, the next index appended.
TEST(SceneValidation, RepeatedNumbersAreSetByIndex) {
  const auto path = write_scene("repeated", kValid);
  const auto scene = cosim::load_scene(path, {"sph.symmetry_planes[0]=Y_MIN", "sph.symmetry_planes[1]=Y_MAX",
                                              "sph.symmetry_planes[0]=X_MIN"});
  ASSERT_EQ(scene->message.sph().symmetry_planes_size(), 2);
  EXPECT_EQ(scene->message.sph().symmetry_planes(0), cosim::scene::X_MIN);
  EXPECT_EQ(scene->message.sph().symmetry_planes(1), cosim::scene::Y_MAX);
  EXPECT_NE(error_of(path, {"sph.symmetry_planes[1]=Y_MIN"}).find("index 1 out of range"), std::string::npos);
  EXPECT_NE(error_of(path, {"sph.symmetry_planes=Y_MIN"}).find("give an index"), std::string::npos);
}

TEST(SceneValidation, AllProblemsAreReportedAtOnce) {
  auto text = replace(kValid, "particle_spacing_m: 0.02", "particle_spacing_m: 0");
  text = replace(text, "end_time_s: 0.01", "end_time_s: -1");
  const std::string e = error_of(write_scene("many", text));
  EXPECT_NE(e.find("end_time_s"), std::string::npos) << e;
  EXPECT_NE(e.find("particle_spacing_m"), std::string::npos) << e;
}
}  // namespace

namespace {

std::string tyre_scene() { return test_support::source_dir() + "/configs/scenes/tyre_inflation.textproto"; }

TEST(TyreSceneValidation, BadSizeAndNegativePressureNameTheField) {
  const std::string e = error_of(tyre_scene(), {"tyre.size=235-75R15", "tyre.inflation_pressure_Pa=-1"});
  EXPECT_NE(e.find("tyre.size"), std::string::npos) << e;
  EXPECT_NE(e.find("--set tyre.inflation_pressure_Pa=-1: must be >= 0"), std::string::npos) << e;
}

TEST(TyreSceneValidation, UnknownRegionInMaterialsFileNamesFileAndLine) {
  const std::string dir = test_support::scratch("validation_tyre_materials");
  std::ifstream in(test_support::source_dir() + "/configs/materials/tyre_235_75R15.textproto");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = replace(text, "region: \"tread\"", "region: \"treed\"");
  std::ofstream(dir + "/materials.textproto") << text;
  const std::string e = error_of(tyre_scene(), {"tyre.materials_file=" + dir + "/materials.textproto"});
  EXPECT_NE(e.find(dir + "/materials.textproto:"), std::string::npos) << e;
  EXPECT_NE(e.find("treed"), std::string::npos) << e;
  EXPECT_NE(e.find("no material for region 'tread'"), std::string::npos) << e;
}

TEST(TyreSceneValidation, ImpossibleMaterialValuesAreRefused) {
  const std::string e = error_of(tyre_scene(), {"tyre.materials[0].region=bead",
                                                "tyre.materials[0].elastic.density_kg_per_m3=7570",
                                                "tyre.materials[0].elastic.youngs_modulus_Pa=206e9",
                                                "tyre.materials[0].elastic.poisson_ratio=0.5"});
  EXPECT_NE(e.find("poisson_ratio"), std::string::npos) << e;
  EXPECT_NE(e.find("must be in [0, 0.5)"), std::string::npos) << e;
}

}  // namespace
