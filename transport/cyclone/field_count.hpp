#pragma once
// Number of fields of an aggregate, found by brace-initialising it with more
// and more "any" values until that fails. Used to check at compile time that
// each neutral topic struct has exactly as many fields as the C struct idlc
// generates from idl/cosim_topics.idl, so neither can gain or lose a field
// without the other (and the conversions) being updated.
#include <cstddef>
#include <utility>

namespace cosim::transport::cyclone {

struct AnyField {
  template <class T>
  constexpr operator T() const noexcept;  // declared only: unevaluated contexts
};

template <class T, class... A>
constexpr auto brace_initialisable(int) -> decltype(T{std::declval<A>()...}, true) { return true; }
template <class T, class... A>
constexpr bool brace_initialisable(...) { return false; }

template <class T, class... A>
constexpr std::size_t field_count() {
  if constexpr (brace_initialisable<T, A..., AnyField>(0))
    return field_count<T, A..., AnyField>();
  else
    return sizeof...(A);
}

}  // namespace cosim::transport::cyclone
