// Where a coupled run's work went; see run_energy.hpp.
#include "run_energy.hpp"

#include <cstdio>
#include <exception>

#include "cosim/csv.hpp"
#include "snow_sph/energy_split.hpp"
#include "tyre_fe/energy_split.hpp"

namespace cosim {
namespace {

double number_at(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_number() ? object[key].get<double>() : 0.0;
}

// The terrain's plastic work (total, cap, shear) at time t, linear between
// energy.csv's rows; false if the file or its columns are missing.
bool plastic_work_at(const std::string& csv_path, double t, double out[3]) {
  try {
    const CsvTable table = read_csv(csv_path);
    const char* const keys[3] = {"plastic_dissipation_J", "plastic_cap_J", "plastic_shear_J"};
    double before_t = 0.0, before[3] = {0, 0, 0};
    for (const CsvTable::Row& row : table.rows) {
      const double rt = std::stod(table.field(row, "time_s"));
      double v[3];
      for (int k = 0; k < 3; ++k) v[k] = std::stod(table.field(row, keys[k]));
      if (rt >= t) {
        const double w = rt > before_t ? (t - before_t) / (rt - before_t) : 1.0;
        for (int k = 0; k < 3; ++k) out[k] = before[k] + w * (v[k] - before[k]);
        return true;
      }
      before_t = rt;
      for (int k = 0; k < 3; ++k) before[k] = v[k];
    }
  } catch (const std::exception&) {
  }
  return false;
}

}  // namespace

nlohmann::json coupled_run_energy(const std::string& run_dir, const nlohmann::json& coupler,
                                  const nlohmann::json& terrain, const nlohmann::json& tyre) {
  const nlohmann::json results = coupler.is_object() ? coupler.value("results", nlohmann::json()) : nlohmann::json();
  if (!results.is_object() || !results.contains("motion_resistance_work_J")) return nullptr;
  const nlohmann::json terrain_energy = terrain.is_object() ? terrain.value("energy", nlohmann::json()) : nullptr;
  nlohmann::json energy = {
      {"motion_resistance_work_J", results["motion_resistance_work_J"]},
      {"motion_resistance_distance_m", number_at(results, "motion_resistance_distance_m")},
      {"terrain_plastic_work_J", number_at(terrain_energy, "plastic_dissipation_J")},
      {"terrain_plastic_cap_J", number_at(terrain_energy, "plastic_cap_J")},
      {"terrain_plastic_shear_J", number_at(terrain_energy, "plastic_shear_J")},
      {"terrain", terrain_energy},
      {"tyre", tyre.is_object() ? tyre.value("energy", nlohmann::json()) : nullptr},
      {"note",
       "motion_resistance_work_J = integral F1 dx_rim over the run; the terrain's plastic work over the "
       "whole run (loading included) and over the rim's travel (from rim_travel_start_s)"}};
  double at_start[3];
  if (results.contains("rim_travel_start_s") &&
      plastic_work_at(run_dir + "/terrain/energy.csv", results["rim_travel_start_s"].get<double>(), at_start)) {
    energy["rim_travel_start_s"] = results["rim_travel_start_s"];
    energy["terrain_plastic_work_over_travel_J"] = number_at(terrain_energy, "plastic_dissipation_J") - at_start[0];
    energy["terrain_plastic_cap_over_travel_J"] = number_at(terrain_energy, "plastic_cap_J") - at_start[1];
    energy["terrain_plastic_shear_over_travel_J"] = number_at(terrain_energy, "plastic_shear_J") - at_start[2];
  }
  return energy;
}

std::string coupled_run_energy_text(const nlohmann::json& energy) {
  if (!energy.is_object()) return "";
  std::string text = snow_sph::terrain_energy_table(energy.value("terrain", nlohmann::json())) +
                     tyre_fe::tyre_energy_table(energy.value("tyre", nlohmann::json()));
  char line[256];
  std::snprintf(line, sizeof line,
                "\nThe motion resistance's work beside the terrain's plastic work:\n"
                "    %-46s %12.2f J\n",
                "F1 dx over the rim's travel", number_at(energy, "motion_resistance_work_J"));
  text += line;
  std::snprintf(line, sizeof line, "    %-46s %12.3f m\n", "the rim's travel",
                number_at(energy, "motion_resistance_distance_m"));
  text += line;
  if (energy.contains("terrain_plastic_work_over_travel_J")) {
    std::snprintf(line, sizeof line, "    %-46s %12.2f J (cap %.2f, shear %.2f)\n", "plastic work over the travel",
                  number_at(energy, "terrain_plastic_work_over_travel_J"),
                  number_at(energy, "terrain_plastic_cap_over_travel_J"),
                  number_at(energy, "terrain_plastic_shear_over_travel_J"));
    text += line;
  }
  std::snprintf(line, sizeof line, "    %-46s %12.2f J (cap %.2f, shear %.2f)\n", "plastic work over the run",
                number_at(energy, "terrain_plastic_work_J"), number_at(energy, "terrain_plastic_cap_J"),
                number_at(energy, "terrain_plastic_shear_J"));
  return text + line;
}

}  // namespace cosim
