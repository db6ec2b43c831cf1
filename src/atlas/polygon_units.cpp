#include "atlas/polygon_units.h"

#include <algorithm>
#include <unordered_map>

namespace raps {
namespace {

// Per position in `triangles`, its polygon: 0, 1, ... in order of their first triangle, through
// the polygons' own edges between triangles of the chart.
std::vector<int32_t> polygon_numbers(const AtlasSurface& surface,
                                     const std::vector<int32_t>& triangles,
                                     const std::vector<int32_t>& neighbour, int32_t& count) {
    std::vector<int32_t> number(triangles.size(), -1), stack;
    count = 0;
    for (size_t i = 0; i < triangles.size(); ++i) {
        if (number[i] >= 0) continue;
        number[i] = count;
        stack.assign(1, static_cast<int32_t>(i));
        while (!stack.empty()) {
            const int32_t j = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const int32_t o = neighbour[3 * j + k];
                if (o < 0 || number[o] >= 0 || !joins_polygon(surface, 3 * triangles[j] + k))
                    continue;
                number[o] = count;
                stack.push_back(o);
            }
        }
        ++count;
    }
    return number;
}

}  // namespace

bool is_one_polygon(const AtlasSurface& surface, const std::vector<int32_t>& triangles) {
    if (surface.polygon_inner.empty() || triangles.size() <= 1) return triangles.size() <= 1;
    // A polygon's triangulation is a tree of its triangles: n triangles joined by n - 1 of its
    // own edges. The chart's polygons are whole, so these edges all lie inside it.
    size_t inner = 0;
    for (int32_t t : triangles) {
        for (int k = 0; k < 3; ++k) inner += surface.polygon_inner[3 * t + k] != 0;
    }
    return inner / 2 + 1 >= triangles.size();
}

void keep_polygons_together(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                            const std::vector<int32_t>& neighbour, std::vector<int32_t>& side) {
    if (surface.polygon_inner.empty()) return;
    int32_t count = 0;
    const std::vector<int32_t> number = polygon_numbers(surface, triangles, neighbour, count);
    std::vector<int32_t> polygon_side(count, -1);
    for (size_t i = 0; i < triangles.size(); ++i) {
        if (polygon_side[number[i]] < 0) polygon_side[number[i]] = side[i];
        side[i] = polygon_side[number[i]];
    }
}

void halve_by_polygons(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                       const std::vector<int32_t>& neighbour, std::vector<int32_t>& side) {
    int32_t count = static_cast<int32_t>(triangles.size());
    std::vector<int32_t> number(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) number[i] = static_cast<int32_t>(i);
    if (!surface.polygon_inner.empty()) {
        int32_t polygons = 0;
        std::vector<int32_t> by_polygon = polygon_numbers(surface, triangles, neighbour, polygons);
        if (polygons > 1) {
            number = std::move(by_polygon);
            count = polygons;
        }
    }
    for (size_t i = 0; i < triangles.size(); ++i) side[i] = number[i] < count / 2 ? 0 : 1;
}

std::vector<char> polygon_triangles(const AtlasSurface& surface,
                                    const std::vector<int32_t>& triangles) {
    if (surface.polygon_inner.empty()) return {};
    std::vector<char> inside(triangles.size(), 0);
    for (size_t i = 0; i < triangles.size(); ++i) {
        for (int k = 0; k < 3; ++k) inside[i] |= joins_polygon(surface, 3 * triangles[i] + k);
    }
    return inside;
}

std::vector<int32_t> aside_polygon_charts(const TriangleMesh& mesh,
                                          const std::vector<int32_t>& welded,
                                          const AtlasSurface& surface,
                                          const std::vector<int32_t>& chart_of_input) {
    std::vector<int32_t> chart(surface.aside_triangles.size(), -1);
    if (mesh.triangle_polygon.empty()) return chart;
    auto edge = [&](int32_t t, int k) {
        const uint32_t a = static_cast<uint32_t>(welded[mesh.triangles[t][k]]);
        const uint32_t b = static_cast<uint32_t>(welded[mesh.triangles[t][(k + 1) % 3]]);
        return static_cast<uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
    };
    std::unordered_map<uint64_t, std::vector<int32_t>> aside_at;  // edge -> aside positions
    for (size_t i = 0; i < surface.aside_triangles.size(); ++i) {
        if (surface.aside_primary[i] >= 0) continue;  // a duplicate copies its primary
        for (int k = 0; k < 3; ++k)
            aside_at[edge(surface.aside_triangles[i], k)].push_back(static_cast<int32_t>(i));
    }
    if (aside_at.empty()) return chart;
    for (int32_t s : surface.input_triangle) {  // in order: the first such triangle wins
        for (int k = 0; k < 3; ++k) {
            const auto found = aside_at.find(edge(s, k));
            if (found == aside_at.end()) continue;
            for (int32_t i : found->second) {
                const int32_t t = surface.aside_triangles[i];
                if (chart[i] < 0 && mesh.triangle_polygon[t] == mesh.triangle_polygon[s])
                    chart[i] = chart_of_input[s];
            }
        }
    }
    return chart;
}

}  // namespace raps
