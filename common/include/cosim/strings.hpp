#pragma once
// Small text helpers shared by the input checks of every component.
#include <cstddef>
#include <sstream>
#include <string>

#include "cosim/error.hpp"

namespace cosim {

// Levenshtein distance (insertions, deletions, substitutions), for
// "did you mean ...?" hints on unknown names.
std::size_t edit_distance(const std::string& a, const std::string& b);

// The value of `all` whose name_of(value) is `name`; otherwise throws
// cosim::Error "unknown <what> '<name>'; known: ... Did you mean '<closest>'?".
template <class T, std::size_t N, class NameFn>
T value_from_name(const std::string& name, const T (&all)[N], NameFn name_of, const char* what) {
  for (T t : all)
    if (name == name_of(t)) return t;
  std::ostringstream msg;
  msg << "unknown " << what << " '" << name << "'; known:";
  const char* closest = name_of(all[0]);
  for (T t : all) {
    msg << ' ' << name_of(t);
    if (edit_distance(name, name_of(t)) < edit_distance(name, closest)) closest = name_of(t);
  }
  msg << ". Did you mean '" << closest << "'?";
  throw Error(msg.str());
}

}  // namespace cosim
