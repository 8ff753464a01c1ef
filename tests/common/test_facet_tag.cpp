// The one facet-tag enum (cosim/facet_tag.hpp) against the wire schema that
// other programs read: idl/cosim_topics.idl, enum FacetTag. The IDL file is
// parsed as text here, independently of both code generators, so a tag added,
// removed or reordered on one side only fails this test (the vendors' own
// compile-time checks see only the generated code). Exact comparison: these
// are names and positions, nothing numerical.
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cosim/error.hpp"
#include "cosim/facet_tag.hpp"

namespace {

// The enumerators of `enum FacetTag { ... }` in the IDL, in order, comments removed.
std::vector<std::string> idl_facet_tags() {
  const char* root = std::getenv("COSIM_SOURCE_DIR");
  const std::string path = std::string(root ? root : ".") + "/idl/cosim_topics.idl";
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::stringstream text;
  std::string line;
  while (std::getline(in, line)) text << line.substr(0, line.find("//")) << '\n';
  const std::string idl = text.str();
  const auto start = idl.find("enum FacetTag");
  EXPECT_NE(start, std::string::npos) << path << " has no enum FacetTag";
  const auto open = idl.find('{', start), close = idl.find('}', start);
  std::vector<std::string> names;
  std::string name;
  for (std::size_t i = open + 1; i <= close; ++i) {
    const char c = idl[i];
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      name += c;
    } else if (!name.empty()) {
      names.push_back(name);
      name.clear();
    }
  }
  return names;
}

std::string wire_name(cosim::FacetTag tag) {
  std::string upper = "TAG_";
  for (const char* c = cosim::facet_tag_name(tag); *c; ++c) upper += static_cast<char>(std::toupper(*c));
  return upper;
}

}  // namespace

TEST(FacetTag, SameNamesInTheSameOrderAsTheIdl) {
  const auto idl = idl_facet_tags();
  ASSERT_EQ(idl.size(), static_cast<std::size_t>(cosim::kFacetTagCount));
  for (int k = 0; k < cosim::kFacetTagCount; ++k) {
    EXPECT_EQ(static_cast<int>(cosim::kAllFacetTags[k]), k) << "kAllFacetTags is in enum order";
    EXPECT_EQ(wire_name(cosim::kAllFacetTags[k]), idl[k]) << "position " << k;
  }
}

TEST(FacetTag, NamesRoundTripAndUnknownNamesSayTheClosest) {
  for (cosim::FacetTag t : cosim::kAllFacetTags) EXPECT_EQ(cosim::facet_tag_from_name(cosim::facet_tag_name(t)), t);
  try {
    cosim::facet_tag_from_name("grove_bottom");
    FAIL() << "an unknown tag was accepted";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("Did you mean 'groove_bottom'?"), std::string::npos) << e.what();
  }
}
