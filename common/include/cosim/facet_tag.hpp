#pragma once
// The one facet-tag enum of the project: the region of the tyre's surface a
// facet belongs to. tyre_fe tags its boundary facets with it, the wire carries
// it (idl/cosim_topics.idl, enum FacetTag: TAG_ + the upper-case name, in this
// order; both DDS backends check every value at compile time and
// tests/common/test_facet_tag.cpp checks the names and order against the IDL file),
// and the coupler chooses friction by it (thesis 4.4, 6.1).
#include <cstdint>
#include <string>

namespace cosim {

enum class FacetTag : std::uint8_t {
  tread_top,      // ground-contacting top of the tread (ribs, blocks, smooth cap)
  groove_wall,    // side walls of circumferential and lateral grooves
  groove_bottom,  // floor of the grooves
  sipe_wall,      // the two faces of each sipe (slit)
  shoulder,       // outer surface of the tread beyond the tread width
  sidewall,       // outer surface of the sidewall
  inner_liner,    // inside of the tyre: carries the inflation pressure
  rim_contact,    // bead seat / rim strip faces held by the rim
  other,          // any other boundary facet
};
constexpr int kFacetTagCount = 9;
constexpr FacetTag kAllFacetTags[kFacetTagCount] = {
    FacetTag::tread_top, FacetTag::groove_wall, FacetTag::groove_bottom, FacetTag::sipe_wall,  FacetTag::shoulder,
    FacetTag::sidewall,  FacetTag::inner_liner, FacetTag::rim_contact,   FacetTag::other};

// "tread_top", "groove_wall", ...: the IDL name without its TAG_ prefix, in lower case.
const char* facet_tag_name(FacetTag tag);
// Throws cosim::Error naming the known tags and the closest one ("Did you mean ...?").
FacetTag facet_tag_from_name(const std::string& name);

}  // namespace cosim
