// Neutral structs <-> fastddsgen classes, field by field in IDL order.
#include "fast_convert.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace cosim::transport::fast {

// The enumerations keep the IDL's numbering; the last enumerator pins the count.
// Every facet tag (cosim/facet_tag.hpp) has the IDL's value.
static_assert(static_cast<int>(cosim_wire::TAG_TREAD_TOP) == static_cast<int>(FacetTag::tread_top));
static_assert(static_cast<int>(cosim_wire::TAG_GROOVE_WALL) == static_cast<int>(FacetTag::groove_wall));
static_assert(static_cast<int>(cosim_wire::TAG_GROOVE_BOTTOM) == static_cast<int>(FacetTag::groove_bottom));
static_assert(static_cast<int>(cosim_wire::TAG_SIPE_WALL) == static_cast<int>(FacetTag::sipe_wall));
static_assert(static_cast<int>(cosim_wire::TAG_SHOULDER) == static_cast<int>(FacetTag::shoulder));
static_assert(static_cast<int>(cosim_wire::TAG_SIDEWALL) == static_cast<int>(FacetTag::sidewall));
static_assert(static_cast<int>(cosim_wire::TAG_INNER_LINER) == static_cast<int>(FacetTag::inner_liner));
static_assert(static_cast<int>(cosim_wire::TAG_RIM_CONTACT) == static_cast<int>(FacetTag::rim_contact));
static_assert(static_cast<int>(cosim_wire::TAG_OTHER) == static_cast<int>(FacetTag::other));
static_assert(kFacetTagCount == cosim_wire::TAG_OTHER + 1);
static_assert(static_cast<int>(cosim_wire::ROLE_MONITOR) == static_cast<int>(Role::monitor) &&
              kRoleCount == cosim_wire::ROLE_MONITOR + 1);
static_assert(static_cast<int>(cosim_wire::CONTROL_CHECKPOINT_AT) == static_cast<int>(ControlKind::checkpoint_at) &&
              kControlKindCount == cosim_wire::CONTROL_CHECKPOINT_AT + 1);

namespace {

// One overload per kind of field, chosen by the neutral type; fastddsgen's
// accessors return a reference to every member. to_wire copies (reusing the
// wire object's capacity from step to step); from_wire moves the sequences out.
template <class T>
void put(const T& s, T& w) { w = s; }
void put(ControlKind s, cosim_wire::ControlKind& w) { w = static_cast<cosim_wire::ControlKind>(s); }
void put(Role s, cosim_wire::Role& w) { w = static_cast<cosim_wire::Role>(s); }
void put(const std::vector<FacetTag>& s, std::vector<cosim_wire::FacetTag>& w) {
  w.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) w[i] = static_cast<cosim_wire::FacetTag>(s[i]);
}

template <class T>
void take(T& w, T& s) { s = std::move(w); }
void take(cosim_wire::ControlKind w, ControlKind& s) { s = static_cast<ControlKind>(w); }
void take(cosim_wire::Role w, Role& s) { s = static_cast<Role>(w); }
void take(const std::vector<cosim_wire::FacetTag>& w, std::vector<FacetTag>& s) {
  s.resize(w.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = static_cast<FacetTag>(w[i]);
}

#define COSIM_PUT_FIELD(type, name, init) put(s.name, w.name());
#define COSIM_TAKE_FIELD(type, name, init) take(w.name(), s.name);

void put(const SampleHeader& s, cosim_wire::SampleHeader& w) { COSIM_WIRE_FIELDS_SampleHeader(COSIM_PUT_FIELD) }
void take(cosim_wire::SampleHeader& w, SampleHeader& s) { COSIM_WIRE_FIELDS_SampleHeader(COSIM_TAKE_FIELD) }

}  // namespace

// Field by field from the table of the IDL's fields (cosim/wire_fields.hpp).
#define COSIM_CONVERSIONS(T)                            \
  void to_wire(const T& s, cosim_wire::T& w) {          \
    put(s.header, w.header());                          \
    COSIM_WIRE_FIELDS_##T(COSIM_PUT_FIELD)              \
  }                                                     \
  void from_wire(cosim_wire::T& w, T& s) {              \
    take(w.header(), s.header);                         \
    COSIM_WIRE_FIELDS_##T(COSIM_TAKE_FIELD)             \
  }
COSIM_WIRE_TOPICS(COSIM_CONVERSIONS)
#undef COSIM_CONVERSIONS
#undef COSIM_PUT_FIELD
#undef COSIM_TAKE_FIELD

}  // namespace cosim::transport::fast
