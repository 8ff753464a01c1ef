#include "cosim/result_references.hpp"

#include <cmath>
#include <cstdio>

namespace cosim {

const nlohmann::json* result_at(const nlohmann::json& results, const std::string& path) {
  const nlohmann::json* node = &results;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!node->is_object() || !node->contains(key)) return nullptr;
    node = &(*node)[key];
    if (dot == std::string::npos) return node;
    start = dot + 1;
  }
}

nlohmann::json compare_with_references(const ResultReferences& references, const nlohmann::json& results) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& r : references) {
    nlohmann::json entry = {{"result", r.result()}, {"reference", r.value()}, {"source", r.source()},
                            {"value", nullptr}, {"relative_difference", nullptr}};
    const nlohmann::json* value = result_at(results, r.result());
    if (value && value->is_number()) {
      entry["value"] = value->get<double>();
      if (r.value() != 0.0) entry["relative_difference"] = value->get<double>() / r.value() - 1.0;
    }
    out.push_back(entry);
  }
  return out;
}

std::string reference_lines(const nlohmann::json& comparison) {
  std::string text;
  if (!comparison.is_array()) return text;
  for (const auto& e : comparison) {
    char line[512];
    const std::string name = e.value("result", ""), source = e.value("source", "");
    const double reference = e.value("reference", 0.0);
    if (!e["value"].is_number()) {
      std::snprintf(line, sizeof line, "%s: not reported by this run (%s %.4g)\n", name.c_str(), source.c_str(),
                    reference);
    } else if (e["relative_difference"].is_number()) {
      std::snprintf(line, sizeof line, "%s = %.4g, %s %.4g, %+.1f %%\n", name.c_str(), e["value"].get<double>(),
                    source.c_str(), reference, 100.0 * e["relative_difference"].get<double>());
    } else {
      std::snprintf(line, sizeof line, "%s = %.4g, %s %.4g\n", name.c_str(), e["value"].get<double>(),
                    source.c_str(), reference);
    }
    text += line;
  }
  return text;
}

void print_results(const nlohmann::json& summary) {
  std::printf("%s\n%s", summary.value("results", nlohmann::json::object()).dump(2).c_str(),
              reference_lines(summary.value("comparison", nlohmann::json())).c_str());
}

}  // namespace cosim
