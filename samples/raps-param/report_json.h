// raps-param's JSON report: the settings a run used, its statistics and, for an atlas, per
// input, per page and per chart figures. Only formatting: the caller reads the library.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raps.h"

namespace param_report {

// A JSON string literal of s (quotes and control characters escaped).
std::string json_string(const std::string& s);
// A JSON number; null for infinities and NaN, which JSON lacks.
std::string json_number(double value);

// {"domain": ..., ...}: every parameter a run of that domain uses.
std::string settings_json(const raps_settings* settings);
// {"flipped_triangles": ..., ...}; with atlas, also the pages, shrunk charts and density.
std::string stats_json(const raps_stats& stats, bool atlas);

// One input's share of the output (raps_result_mesh_range).
struct MeshShare {
    uint64_t first_vertex = 0, vertex_count = 0, first_index = 0, index_count = 0;
};
// `, "inputs": [...], "pages": [...], "charts": [...]` from the chart records.
std::string atlas_json(const std::vector<std::string>& paths, const std::vector<MeshShare>& shares,
                       const std::vector<raps_chart>& charts, const raps_stats& stats);

}  // namespace param_report
