// Names of tyre regions and surface tags (used in input decks, configs and outputs).
#include "tyre_fe/mesh.hpp"

#include <algorithm>
#include <cctype>

#include "cosim/error.hpp"

namespace tyre_fe {

// The canonical lower-case name of a region, as used in configs and output files.
const char* region_name(Region r) {
  switch (r) {
    case Region::tread: return "tread";
    case Region::sidewall: return "sidewall";
    case Region::inner_liner: return "inner_liner";
    case Region::ply: return "ply";
    case Region::belt_1: return "belt_1";
    case Region::belt_2: return "belt_2";
    case Region::bead: return "bead";
    case Region::filler: return "filler";
    case Region::rim_strip: return "rim_strip";
    case Region::count: break;
  }
  return "unknown";
}

// Inverse of region_name. Matching is case-insensitive so that names written by
// hand ("Tread", "BELT_1") are accepted; anything else is a configuration error.
Region region_from_name(const std::string& name) {
  std::string lower;
  lower.reserve(name.size());
  for (char c : name) lower.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  for (int i = 0; i < kRegionCount; ++i) {
    const auto r = static_cast<Region>(i);
    if (lower == region_name(r)) return r;
  }
  throw cosim::Error("unknown tyre region '" + name +
                     "' (expected tread, sidewall, inner_liner, ply, belt_1, belt_2, bead, "
                     "filler or rim_strip)");
}

void tie_region_to_rim(CrossSection& section, Region region) {
  std::vector<int>& rim = section.rim_nodes;
  for (std::size_t q = 0; q < section.quads.size(); ++q)
    if (section.quad_region[q] == region) rim.insert(rim.end(), section.quads[q].begin(), section.quads[q].end());
  std::sort(rim.begin(), rim.end());
  rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
}

}  // namespace tyre_fe
