// The comparison of a run's results with its scene's references
// (cosim/result_references.hpp): values, nested results, missing ones, and the
// printed lines.
#include <gtest/gtest.h>

#include <google/protobuf/text_format.h>

#include "cosim/result_references.hpp"

namespace {

cosim::scene::Scene scene_with(const std::string& text) {
  cosim::scene::Scene s;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &s));
  return s;
}

TEST(ResultReferences, RelativeDifferenceNestedAndMissing) {
  const auto scene = scene_with(R"(
    references { result: "plate_displacement_m" value: 0.2 source: "laboratory" }
    references { result: "tyre.sinkage_m" value: 0.05 source: "thesis" }
    references { result: "contact_area_m2" value: 0.229 source: "thesis SPH" })");
  const nlohmann::json results = {{"plate_displacement_m", 0.21}, {"tyre", {{"sinkage_m", 0.04}}}};
  const auto c = cosim::compare_with_references(scene.references(), results);
  ASSERT_EQ(c.size(), 3u);
  // (0.21 - 0.2) / 0.2 and (0.04 - 0.05) / 0.05, to round-off.
  EXPECT_NEAR(c[0]["relative_difference"].get<double>(), 0.05, 1e-12);
  EXPECT_NEAR(c[1]["relative_difference"].get<double>(), -0.2, 1e-12);
  EXPECT_TRUE(c[2]["value"].is_null());
  const std::string lines = cosim::reference_lines(c);
  EXPECT_NE(lines.find("plate_displacement_m = 0.21, laboratory 0.2, +5.0 %"), std::string::npos) << lines;
  EXPECT_NE(lines.find("tyre.sinkage_m = 0.04, thesis 0.05, -20.0 %"), std::string::npos) << lines;
  EXPECT_NE(lines.find("contact_area_m2: not reported by this run"), std::string::npos) << lines;
}

TEST(ResultReferences, NoReferencesNoLines) {
  const auto c = cosim::compare_with_references(cosim::scene::Scene().references(), {{"x", 1.0}});
  EXPECT_TRUE(c.empty());
  EXPECT_EQ(cosim::reference_lines(c), "");
}

}  // namespace
