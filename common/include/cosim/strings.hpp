#pragma once
// Small text helpers shared by the input checks of every component.
#include <cstddef>
#include <string>

namespace cosim {

// Levenshtein distance (insertions, deletions, substitutions), for
// "did you mean ...?" hints on unknown names.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace cosim
