#pragma once
// Where a run's work went, as the short table a run prints at its end: the
// work done on a body term by term, where it went with each term's share of
// it, and the balance (docs/sph.md and docs/tyre.md, "Energy balance").
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cosim {

// A term's key and value, as a run books it.
struct EnergyValue {
  const char* key;
  double value;
};

// A line of the table: a key of the summary's `energy` object (the unit in its
// name) and what the term is.
struct EnergyTerm {
  const char* key;
  const char* label;
};

// The work done (its sources and their total), where it went, and the balance
// (went to less done).
struct EnergySplit {
  std::string title;
  std::vector<EnergyTerm> work_done;
  EnergyTerm total;
  std::vector<EnergyTerm> went_to;
  EnergyTerm balance;
};

// The table of `energy`'s values, in J and as shares of the total work done;
// terms the object lacks or that are exactly 0 are left out. Empty if the
// object has no total.
std::string energy_table(const EnergySplit& split, const nlohmann::json& energy);

}  // namespace cosim
