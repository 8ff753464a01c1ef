// Neutral structs <-> idlc's C structs, field by field in IDL order.
#include "cyclone_convert.hpp"

#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include "field_count.hpp"

namespace cosim::transport::cyclone {

// Drift checks: same number of fields as the IDL, same enumeration numbering.
#define COSIM_SAME_FIELDS(T)                                                         \
  static_assert(field_count<T>() == field_count<cosim_wire_##T>(),                   \
                "cosim::transport::" #T " and idl/cosim_topics.idl's " #T            \
                " have different fields: update cosim/wire_fields.hpp with the IDL");
COSIM_WIRE_STRUCTS(COSIM_SAME_FIELDS)
#undef COSIM_SAME_FIELDS
// Every facet tag (cosim/facet_tag.hpp) has the IDL's value.
static_assert(cosim_wire_TAG_TREAD_TOP == static_cast<int>(FacetTag::tread_top));
static_assert(cosim_wire_TAG_GROOVE_WALL == static_cast<int>(FacetTag::groove_wall));
static_assert(cosim_wire_TAG_GROOVE_BOTTOM == static_cast<int>(FacetTag::groove_bottom));
static_assert(cosim_wire_TAG_SIPE_WALL == static_cast<int>(FacetTag::sipe_wall));
static_assert(cosim_wire_TAG_SHOULDER == static_cast<int>(FacetTag::shoulder));
static_assert(cosim_wire_TAG_SIDEWALL == static_cast<int>(FacetTag::sidewall));
static_assert(cosim_wire_TAG_INNER_LINER == static_cast<int>(FacetTag::inner_liner));
static_assert(cosim_wire_TAG_RIM_CONTACT == static_cast<int>(FacetTag::rim_contact));
static_assert(cosim_wire_TAG_OTHER == static_cast<int>(FacetTag::other));
static_assert(kFacetTagCount == cosim_wire_TAG_OTHER + 1);
static_assert(cosim_wire_ROLE_MONITOR == static_cast<int>(Role::monitor) && kRoleCount == cosim_wire_ROLE_MONITOR + 1);
static_assert(cosim_wire_CONTROL_CHECKPOINT_AT == static_cast<int>(ControlKind::checkpoint_at) &&
              kControlKindCount == cosim_wire_CONTROL_CHECKPOINT_AT + 1);

namespace {

// One overload per kind of field, chosen by the neutral type. view_field
// points the C sequences at the neutral vectors (no copy); from_field copies
// out of the loaned C sample.
template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
void view_field(T s, T& w, Scratch&) { w = s; }
template <class Seq, class E>
void view_field(const std::vector<E>& v, Seq& q, Scratch&) {
  static_assert(std::is_same_v<std::remove_pointer_t<decltype(q._buffer)>, E>, "element type differs from the IDL");
  q._maximum = q._length = static_cast<uint32_t>(v.size());
  q._buffer = const_cast<E*>(v.data());
  q._release = false;
}
void view_field(const std::vector<FacetTag>& s, dds_sequence_cosim_wire_FacetTag& w, Scratch& scratch) {
  std::vector<cosim_wire_FacetTag>& tags = scratch.next_facet_tags();
  tags.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) tags[i] = static_cast<cosim_wire_FacetTag>(s[i]);
  view_field(tags, w, scratch);
}
void view_field(ControlKind s, cosim_wire_ControlKind& w, Scratch&) { w = static_cast<cosim_wire_ControlKind>(s); }
void view_field(Role s, cosim_wire_Role& w, Scratch&) { w = static_cast<cosim_wire_Role>(s); }
void view_field(const std::string& s, char*& w, Scratch&) { w = const_cast<char*>(s.c_str()); }

template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
void from_field(T w, T& s) { s = w; }
template <class Seq, class E>
void from_field(const Seq& q, std::vector<E>& v) {
  static_assert(std::is_same_v<std::remove_pointer_t<decltype(q._buffer)>, E>, "element type differs from the IDL");
  v.assign(q._buffer, q._buffer + q._length);
}
void from_field(const dds_sequence_cosim_wire_FacetTag& w, std::vector<FacetTag>& s) {
  s.resize(w._length);
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = static_cast<FacetTag>(w._buffer[i]);
}
void from_field(cosim_wire_ControlKind w, ControlKind& s) { s = static_cast<ControlKind>(w); }
void from_field(cosim_wire_Role w, Role& s) { s = static_cast<Role>(w); }
void from_field(const char* w, std::string& s) { s = w ? w : ""; }

#define COSIM_VIEW_FIELD(type, name, init) view_field(s.name, w.name, scratch);
#define COSIM_FROM_FIELD(type, name, init) from_field(w.name, s.name);

void view_field(const SampleHeader& s, cosim_wire_SampleHeader& w, Scratch& scratch) {
  COSIM_WIRE_FIELDS_SampleHeader(COSIM_VIEW_FIELD)
}
void from_field(const cosim_wire_SampleHeader& w, SampleHeader& s) { COSIM_WIRE_FIELDS_SampleHeader(COSIM_FROM_FIELD) }

}  // namespace

// Field by field from the table of the IDL's fields (cosim/wire_fields.hpp).
#define COSIM_CONVERSIONS(T)                                         \
  void view(const T& s, cosim_wire_##T& w, Scratch& scratch) {       \
    scratch.facet_tags_used = 0;                                     \
    view_field(s.header, w.header, scratch);                         \
    COSIM_WIRE_FIELDS_##T(COSIM_VIEW_FIELD)                          \
  }                                                                  \
  void from_wire(const cosim_wire_##T& w, T& s) {                    \
    from_field(w.header, s.header);                                  \
    COSIM_WIRE_FIELDS_##T(COSIM_FROM_FIELD)                          \
  }
COSIM_WIRE_TOPICS(COSIM_CONVERSIONS)
#undef COSIM_CONVERSIONS
#undef COSIM_VIEW_FIELD
#undef COSIM_FROM_FIELD

}  // namespace cosim::transport::cyclone
