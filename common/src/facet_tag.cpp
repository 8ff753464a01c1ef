#include "cosim/facet_tag.hpp"

#include "cosim/strings.hpp"

namespace cosim {

const char* facet_tag_name(FacetTag tag) {
  switch (tag) {
    case FacetTag::tread_top: return "tread_top";
    case FacetTag::groove_wall: return "groove_wall";
    case FacetTag::groove_bottom: return "groove_bottom";
    case FacetTag::sipe_wall: return "sipe_wall";
    case FacetTag::shoulder: return "shoulder";
    case FacetTag::sidewall: return "sidewall";
    case FacetTag::inner_liner: return "inner_liner";
    case FacetTag::rim_contact: return "rim_contact";
    case FacetTag::other: return "other";
  }
  return "unknown";
}

FacetTag facet_tag_from_name(const std::string& name) {
  return value_from_name(name, kAllFacetTags, facet_tag_name, "facet tag");
}

}  // namespace cosim
