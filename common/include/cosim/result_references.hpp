#pragma once
// A run's results beside the published values its scene names (Scene.references,
// configs/schema/scene.proto): the comparison summary.json keeps and the lines a
// run prints last, e.g.
//   plate_displacement_m = 0.187, laboratory (Haehnel & Shoop 2004) 0.200, -6.5 %
#include <string>

#include <nlohmann/json.hpp>

#include "scene.pb.h"

namespace cosim {

// One entry per reference: {result, value (null when the run has no such
// result), reference, source, relative_difference (null likewise)}. A dotted
// result ("tyre.sinkage_m") looks into nested objects.
using ResultReferences = google::protobuf::RepeatedPtrField<scene::ResultReference>;

// The result at a dotted path ("tyre.rm2_Nm") in a summary's "results"; null
// when there is none.
const nlohmann::json* result_at(const nlohmann::json& results, const std::string& path);
nlohmann::json compare_with_references(const ResultReferences& references, const nlohmann::json& results);

// The comparison as text, one line per entry; empty when there is none.
std::string reference_lines(const nlohmann::json& comparison);

// What a program prints at the end of a run: summary "results" as JSON, then
// the lines of its "comparison" (if any).
void print_results(const nlohmann::json& summary);

}  // namespace cosim
