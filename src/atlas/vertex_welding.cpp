#include "atlas/vertex_welding.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace raps {
namespace {

int32_t find_root(std::vector<int32_t>& parent, int32_t v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];  // path halving
        v = parent[v];
    }
    return v;
}

// Union by smallest index, so the representative is the smallest vertex of each group.
void unite(std::vector<int32_t>& parent, int32_t a, int32_t b) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a < b) parent[b] = a;
    if (b < a) parent[a] = b;
}

}  // namespace

std::vector<int32_t> weld_vertices(const std::vector<Eigen::Vector3d>& positions,
                                   double tolerance) {
    const int32_t n = static_cast<int32_t>(positions.size());
    std::vector<int32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<int32_t> sorted(n);
    std::iota(sorted.begin(), sorted.end(), 0);
    if (tolerance <= 0.0) {
        // Exact equality: sort lexicographically, then neighbours in the order are equal runs.
        std::sort(sorted.begin(), sorted.end(), [&](int32_t a, int32_t b) {
            const Eigen::Vector3d &p = positions[a], &q = positions[b];
            if (p.x() != q.x()) return p.x() < q.x();
            if (p.y() != q.y()) return p.y() < q.y();
            if (p.z() != q.z()) return p.z() < q.z();
            return a < b;
        });
        for (int32_t i = 1; i < n; ++i) {
            if (positions[sorted[i]] == positions[sorted[i - 1]])
                unite(parent, sorted[i], sorted[i - 1]);
        }
    } else {
        // Grid of cells of the tolerance's size: a vertex can only weld with vertices in its
        // own or the 26 neighbouring cells. Cells are sorted so each lookup is a binary search;
        // the result does not depend on the visiting order (union by smallest index).
        using Cell = std::array<int64_t, 3>;
        auto cell_of = [&](const Eigen::Vector3d& p) {
            Cell c;
            for (int k = 0; k < 3; ++k) {
                c[k] = static_cast<int64_t>(std::clamp(std::floor(p[k] / tolerance), -4e18, 4e18));
            }
            return c;
        };
        std::vector<std::pair<Cell, int32_t>> cells(n);
        for (int32_t v = 0; v < n; ++v) cells[v] = {cell_of(positions[v]), v};
        std::sort(cells.begin(), cells.end());
        const double squared = tolerance * tolerance;
        for (int32_t v = 0; v < n; ++v) {
            const Cell c = cell_of(positions[v]);
            for (int64_t dx = -1; dx <= 1; ++dx) {
                for (int64_t dy = -1; dy <= 1; ++dy) {
                    for (int64_t dz = -1; dz <= 1; ++dz) {
                        const Cell key = {c[0] + dx, c[1] + dy, c[2] + dz};
                        auto it = std::lower_bound(cells.begin(), cells.end(),
                                                   std::make_pair(key, int32_t(0)));
                        for (; it != cells.end() && it->first == key; ++it) {
                            if (it->second != v &&
                                (positions[it->second] - positions[v]).squaredNorm() <= squared) {
                                unite(parent, v, it->second);
                            }
                        }
                    }
                }
            }
        }
    }
    std::vector<int32_t> representative(n);
    for (int32_t v = 0; v < n; ++v) representative[v] = find_root(parent, v);
    return representative;
}

}  // namespace raps
