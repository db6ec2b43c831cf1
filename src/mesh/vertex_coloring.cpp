#include "mesh/vertex_coloring.h"

namespace raps {

std::vector<std::vector<int32_t>> greedy_vertex_coloring(const VertexAdjacency& adjacency,
                                                         const ProgressSpan& progress) {
    const int32_t vertex_count = static_cast<int32_t>(adjacency.offsets.size()) - 1;
    std::vector<int32_t> color(vertex_count, -1);
    std::vector<int32_t> taken_by;  // taken_by[c] == v: colour c is used by a neighbour of v
    std::vector<std::vector<int32_t>> classes;
    progress.in_runs(vertex_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t v = static_cast<int32_t>(run_begin); v < run_end; ++v) {
            for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
                const int32_t c = color[adjacency.neighbors[s]];
                if (c >= 0) taken_by[c] = v;
            }
            int32_t c = 0;
            while (c < static_cast<int32_t>(taken_by.size()) && taken_by[c] == v) ++c;
            if (c == static_cast<int32_t>(taken_by.size())) {
                taken_by.push_back(-1);
                classes.emplace_back();
            }
            color[v] = c;
            classes[c].push_back(v);
        }
    });
    return classes;
}

}  // namespace raps
