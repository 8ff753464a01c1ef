// Defaults declared once in the schema (configs/schema/scene.proto,
// `[(default_value) = ...]`) reach the loaded scene: a field left out takes the
// value the schema declares, a field set keeps its value (also from --set), and
// a section the scene does not have is not created by a default. The expected
// defaults are read from the schema's descriptor, the declaration users see,
// and compared with what load_scene() gives; exact comparisons (values are
// copied, not computed).
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cosim/scene_io.hpp"
#include "test_paths.hpp"

namespace {

namespace sc = cosim::scene;

double declared_default(const google::protobuf::Descriptor* d, const char* field) {
  const auto* f = d->FindFieldByName(field);
  EXPECT_NE(f, nullptr) << field;
  EXPECT_TRUE(f->options().HasExtension(sc::default_value)) << field << " declares no default";
  return f->options().GetExtension(sc::default_value);
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = test_support::scratch("schema_defaults_" + name) + "/scene.textproto";
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(SchemaDefaults, FieldsLeftOutTakeTheDeclaredDefault) {
  const auto scene = cosim::load_scene(write("left_out", "name: \"d\"\ncoupling { terrain: \"rigid_road\" }\n"
                                                         "tyre { size: \"235/75R15\" }\n"));
  const auto& c = scene->message.coupling();
  const auto* cd = sc::Coupling::descriptor();
  EXPECT_EQ(c.contact_band_m(), declared_default(cd, "contact_band_m"));
  EXPECT_EQ(c.initial_gap_m(), declared_default(cd, "initial_gap_m"));
  EXPECT_EQ(c.rolling_radius_m(), declared_default(cd, "rolling_radius_m"));
  EXPECT_EQ(c.base_friction_coefficient(), declared_default(cd, "base_friction_coefficient"));
  EXPECT_EQ(c.sipe_equivalent_friction_coefficient(), declared_default(cd, "sipe_equivalent_friction_coefficient"));
  EXPECT_EQ(c.contact_stiffness_scale(), declared_default(cd, "contact_stiffness_scale"));
  const auto* td = sc::TyreModel::descriptor();
  EXPECT_EQ(scene->message.tyre().bulk_to_shear_ratio(), declared_default(td, "bulk_to_shear_ratio"));
  EXPECT_EQ(scene->message.tyre().hourglass_coefficient(), declared_default(td, "hourglass_coefficient"));
  // No default creates a section the scene does not have.
  EXPECT_FALSE(scene->message.has_sph());
}

TEST(SchemaDefaults, ValuesSetInTheFileOrOnTheCommandLineAreKept) {
  const auto scene = cosim::load_scene(
      write("set", "name: \"d\"\ncoupling { terrain: \"rigid_road\" contact_band_m: 0.2 }\n"),
      {"coupling.rolling_radius_m=0.4"});
  EXPECT_EQ(scene->message.coupling().contact_band_m(), 0.2);
  EXPECT_EQ(scene->message.coupling().rolling_radius_m(), 0.4);
  EXPECT_FALSE(scene->message.has_tyre());
}
