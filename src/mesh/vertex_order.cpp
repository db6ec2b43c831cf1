#include "mesh/vertex_order.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "core/fill_in_runs.h"

namespace raps {
namespace {

// Spreads the low 21 bits of x so that two zero bits follow each.
uint64_t spread_bits(uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}

}  // namespace

std::vector<int32_t> morton_vertex_order(const std::vector<Eigen::Vector3d>& positions,
                                         const ProgressSpan& progress) {
    const int32_t n = static_cast<int32_t>(positions.size());
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d high = -low;
    for (const Eigen::Vector3d& p : positions) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    const double extent = std::max((high - low).maxCoeff(), 1e-300);
    std::vector<uint64_t> code(n);
    progress.part(0.0, 0.2).in_runs(n, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t i = static_cast<int32_t>(run_begin); i < run_end; ++i) {
            uint64_t key = 0;
            for (int c = 0; c < 3; ++c) {
                const double t = std::clamp((positions[i][c] - low[c]) / extent, 0.0, 1.0);
                key |= spread_bits(static_cast<uint64_t>(t * 2097151.0)) << c;
            }
            code[i] = key;
        }
    });
    // Stable radix sort by code, 16 bits a pass (codes have 63): the order a stable comparison
    // sort gives, in linear passes that report their progress.
    std::vector<int32_t> order(n), sorted(n);
    std::iota(order.begin(), order.end(), 0);
    std::vector<int32_t> start(65537);
    for (int shift = 0; shift < 64; shift += 16) {
        const ProgressSpan pass = progress.part(0.2 + 0.2 * shift / 16, 0.4 + 0.2 * shift / 16);
        std::fill(start.begin(), start.end(), 0);
        for (int32_t i = 0; i < n; ++i) ++start[((code[i] >> shift) & 0xffff) + 1];
        std::partial_sum(start.begin(), start.end(), start.begin());
        pass.in_runs(n, [&](int64_t run_begin, int64_t run_end) {
            for (int32_t k = static_cast<int32_t>(run_begin); k < run_end; ++k) {
                const int32_t i = order[k];
                sorted[start[(code[i] >> shift) & 0xffff]++] = i;
            }
        });
        order.swap(sorted);
    }
    return order;
}

TriangleMesh reorder_vertices(const TriangleMesh& mesh, const std::vector<int32_t>& order,
                              const ProgressSpan& progress) {
    // Every pass and copy reports (at 5.65M triangles the copy of the triangles and the
    // vertex pass were 73-95 ms without a progress call).
    TriangleMesh out;
    out.positions.reserve(order.size());
    std::vector<int32_t> position_of = filled_in_runs(order.size(), 0, progress.part(0.0, 0.1));
    progress.part(0.1, 0.3).in_runs(static_cast<int64_t>(order.size()),
                                    [&](int64_t run_begin, int64_t run_end) {
                                        for (int64_t k = run_begin; k < run_end; ++k) {
                                            out.positions.push_back(mesh.positions[order[k]]);
                                            position_of[order[k]] = static_cast<int32_t>(k);
                                        }
                                    });
    copy_in_runs(out.triangles, mesh.triangles, progress.part(0.3, 0.5));
    progress.part(0.5, 1.0).in_runs(out.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            for (int32_t& v : out.triangles[t]) v = position_of[v];
        }
    });
    return out;
}

}  // namespace raps
