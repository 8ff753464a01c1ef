#include "cosim/facet_tag.hpp"

#include <sstream>

#include "cosim/error.hpp"
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
  for (FacetTag t : kAllFacetTags)
    if (name == facet_tag_name(t)) return t;
  std::ostringstream msg;
  msg << "unknown facet tag '" << name << "'; known:";
  const char* closest = facet_tag_name(kAllFacetTags[0]);
  for (FacetTag t : kAllFacetTags) {
    msg << ' ' << facet_tag_name(t);
    if (edit_distance(name, facet_tag_name(t)) < edit_distance(name, closest)) closest = facet_tag_name(t);
  }
  msg << ". Did you mean '" << closest << "'?";
  throw Error(msg.str());
}

}  // namespace cosim
