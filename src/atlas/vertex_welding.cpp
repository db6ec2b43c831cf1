#include "atlas/vertex_welding.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>

#include "core/hash_mix.h"
#include "core/union_find.h"

namespace raps {
namespace {

// Union by smallest index, so the representative is the smallest vertex of each group.
void unite(std::vector<int32_t>& parent, int32_t a, int32_t b) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a < b) parent[b] = a;
    if (b < a) parent[a] = b;
}

}  // namespace

std::vector<int32_t> weld_vertices(const std::vector<Eigen::Vector3d>& positions, double tolerance,
                                   const ProgressSpan& progress) {
    const int32_t n = static_cast<int32_t>(positions.size());
    if (tolerance <= 0.0) {
        // Exact equality: a hash table of positions, vertices visited in index order, so each
        // position's first vertex is its representative. Linear, where sorting the positions
        // was a fifth of fandisk's topology phase.
        const size_t capacity = hash_table_size(static_cast<size_t>(n));
        std::vector<int32_t> slot(capacity, -1), representative(n);
        progress.in_runs(n, [&](int64_t run_begin, int64_t run_end) {
            for (int32_t v = static_cast<int32_t>(run_begin); v < run_end; ++v) {
                const Eigen::Vector3d& p = positions[v];
                uint64_t hash = 0;
                for (int k = 0; k < 3; ++k) {
                    const double coordinate = p[k] + 0.0;  // -0 and +0 are one position
                    uint64_t bits;
                    std::memcpy(&bits, &coordinate, sizeof(bits));
                    hash = mix_bits(hash ^ bits);
                }
                size_t i = hash & (capacity - 1);
                while (slot[i] >= 0 && positions[slot[i]] != p) i = (i + 1) & (capacity - 1);
                if (slot[i] < 0) slot[i] = v;
                representative[v] = slot[i];
            }
        });
        return representative;
    }
    std::vector<int32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
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
    progress.report(0.2);
    const double squared = tolerance * tolerance;
    progress.part(0.2, 1.0).in_runs(n, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t v = static_cast<int32_t>(run_begin); v < run_end; ++v) {
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
    });
    std::vector<int32_t> representative(n);
    for (int32_t v = 0; v < n; ++v) representative[v] = find_root(parent, v);
    return representative;
}

}  // namespace raps
