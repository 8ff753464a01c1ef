#include "cosim/energy_table.hpp"

#include <cmath>
#include <cstdio>

namespace cosim {
namespace {

bool has_number(const nlohmann::json& energy, const char* key) {
  return energy.is_object() && energy.contains(key) && energy[key].is_number();
}

std::string line(const char* label, double value_J, const double* total_J) {
  char text[160];
  if (total_J && *total_J != 0.0)
    std::snprintf(text, sizeof text, "    %-46s %12.2f J %7.1f %%\n", label, value_J, 100.0 * value_J / *total_J);
  else
    std::snprintf(text, sizeof text, "    %-46s %12.2f J\n", label, value_J);
  return text;
}

}  // namespace

std::string energy_table(const EnergySplit& split, const nlohmann::json& energy) {
  if (!has_number(energy, split.total.key)) return "";
  const double total = energy[split.total.key].get<double>();
  std::string text = "\n" + split.title + " (J, share of the work done):\n  work done:\n";
  for (const EnergyTerm& t : split.work_done)
    if (has_number(energy, t.key) && energy[t.key].get<double>() != 0.0)
      text += line(t.label, energy[t.key].get<double>(), nullptr);
  text += line(split.total.label, total, nullptr) + "  went to:\n";
  for (const EnergyTerm& t : split.went_to)
    if (has_number(energy, t.key) && energy[t.key].get<double>() != 0.0)
      text += line(t.label, energy[t.key].get<double>(), &total);
  if (has_number(energy, split.balance.key))
    text += line(split.balance.label, energy[split.balance.key].get<double>(), &total);
  return text;
}

}  // namespace cosim
