#include "mesh/vertex_order.h"

#include <algorithm>
#include <limits>
#include <numeric>

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

std::vector<int32_t> morton_vertex_order(const std::vector<Eigen::Vector3d>& positions) {
    const int32_t n = static_cast<int32_t>(positions.size());
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d high = -low;
    for (const Eigen::Vector3d& p : positions) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    const double extent = std::max((high - low).maxCoeff(), 1e-300);
    std::vector<uint64_t> code(n);
    for (int32_t i = 0; i < n; ++i) {
        uint64_t key = 0;
        for (int c = 0; c < 3; ++c) {
            const double t = std::clamp((positions[i][c] - low[c]) / extent, 0.0, 1.0);
            key |= spread_bits(static_cast<uint64_t>(t * 2097151.0)) << c;
        }
        code[i] = key;
    }
    std::vector<int32_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int32_t a, int32_t b) { return code[a] < code[b]; });
    return order;
}

TriangleMesh reorder_vertices(const TriangleMesh& mesh, const std::vector<int32_t>& order) {
    TriangleMesh out;
    out.positions.resize(order.size());
    std::vector<int32_t> position_of(order.size());
    for (size_t k = 0; k < order.size(); ++k) {
        out.positions[k] = mesh.positions[order[k]];
        position_of[order[k]] = static_cast<int32_t>(k);
    }
    out.triangles = mesh.triangles;
    for (Triangle& t : out.triangles) {
        for (int32_t& v : t) v = position_of[v];
    }
    return out;
}

}  // namespace raps
