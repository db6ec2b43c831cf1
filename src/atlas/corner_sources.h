// Where each input triangle's corners come from in an atlas: the record the output is written
// from (atlas_pipeline.cpp), shared with the steps that make charts without mapping them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace raps {

// A chart per input triangle (its index; the point charts of degenerate triangles with no chart
// beside them follow the real ones, one per part that has such triangles) and, per corner, the
// chart vertex.
struct CornerSources {
    std::vector<int32_t> chart;                  // per input triangle
    std::vector<std::array<int32_t, 3>> vertex;  // per input triangle, per corner
    std::vector<int32_t> point_chart_part;       // per point chart: its part
    // Per input triangle: 1 for an exact copy of another (the same welded corners, so the same
    // uvs); its texels are its original's and count once. Empty: no copies.
    std::vector<char> copy;
};

}  // namespace raps
