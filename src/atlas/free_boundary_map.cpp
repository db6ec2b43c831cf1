#include "atlas/free_boundary_map.h"

#include <algorithm>

#include "solver/sparse_solver.h"
#include "weights/laplacian_weights.h"

namespace raps {

std::vector<Eigen::Vector2d> free_boundary_conformal_map(const TriangleMesh& mesh,
                                                         const VertexAdjacency& adjacency,
                                                         const std::vector<int32_t>& boundary_loop,
                                                         const std::vector<int32_t>& vertex_order) {
    const int32_t n = mesh.vertex_count();
    // Pins: two boundary vertices far apart (the farthest from the first, then the farthest
    // from that), placed at their 3D distance so the map comes out near the right scale.
    auto farthest = [&](int32_t from) {
        int32_t best = boundary_loop[0];
        for (int32_t v : boundary_loop) {
            if ((mesh.positions[v] - mesh.positions[from]).squaredNorm() >
                (mesh.positions[best] - mesh.positions[from]).squaredNorm()) {
                best = v;
            }
        }
        return best;
    };
    const int32_t pin_a = farthest(boundary_loop[0]);
    const int32_t pin_b = farthest(pin_a);
    std::vector<Eigen::Vector2d> uv(n, Eigen::Vector2d::Zero());
    uv[pin_b] = Eigen::Vector2d((mesh.positions[pin_b] - mesh.positions[pin_a]).norm(), 0.0);

    // E_D - A as a quadratic form in (u_0, v_0, u_1, v_1, ...): per vertex pair a 2x2 block.
    // The Dirichlet part is the cotangent Laplacian on u and on v; for each boundary edge
    // i -> j the area part -(u_i v_j - u_j v_i) / 2 couples u and v across the edge.
    const std::vector<double> cotangent =
        laplacian_weights(mesh, adjacency, WeightScheme::kCotangent);
    std::vector<int32_t> next_on_boundary(n, -1), previous_on_boundary(n, -1);
    for (size_t k = 0; k < boundary_loop.size(); ++k) {
        const int32_t i = boundary_loop[k], j = boundary_loop[(k + 1) % boundary_loop.size()];
        next_on_boundary[i] = j;
        previous_on_boundary[j] = i;
    }
    std::vector<int32_t> unknown(n, -1);
    int32_t count = 0;
    for (int32_t v = 0; v < n; ++v) {
        if (v != pin_a && v != pin_b) unknown[v] = count++;
    }
    SparsePattern pattern;
    pattern.size = 2 * count;
    std::vector<double> values, rhs(2 * static_cast<size_t>(count), 0.0);
    struct Block {
        int32_t column_vertex;
        double uu, uv, vu, vv;  // row u_i / v_i times column u_j / v_j
        bool coupled;           // u and v meet across a boundary edge: uv, vu in the pattern
    };
    std::vector<Block> blocks;  // one row block at a time, reused (allocating per row was 3%)
    std::vector<std::pair<int32_t, double>> entries;
    const size_t most_entries = 2 * (adjacency.neighbors.size() + n + 2 * boundary_loop.size());
    pattern.columns.reserve(most_entries);
    pattern.row_offsets.reserve(2 * static_cast<size_t>(count) + 1);
    values.reserve(most_entries);
    for (int32_t i = 0; i < n; ++i) {
        if (unknown[i] < 0) continue;
        // The row block of vertex i over its neighbours and itself, columns in unknown order.
        double diagonal = 0;
        for (int32_t s = adjacency.offsets[i]; s < adjacency.offsets[i + 1]; ++s)
            diagonal += cotangent[s];
        blocks.clear();
        blocks.push_back({i, diagonal, 0.0, 0.0, diagonal, false});
        for (int32_t s = adjacency.offsets[i]; s < adjacency.offsets[i + 1]; ++s) {
            const int32_t j = adjacency.neighbors[s];
            // -(u_i v_j - u_j v_i) / 2 for edge i -> j; +(u_j v_i - ... ) for edge j -> i.
            double uv_term = 0, vu_term = 0;
            if (next_on_boundary[i] == j) {
                uv_term -= 0.5;  // u_i v_j
                vu_term += 0.5;  // v_i u_j
            }
            if (previous_on_boundary[i] == j) {
                uv_term += 0.5;
                vu_term -= 0.5;
            }
            const bool coupled = next_on_boundary[i] == j || previous_on_boundary[i] == j;
            blocks.push_back({j, -cotangent[s], uv_term, vu_term, -cotangent[s], coupled});
        }
        for (int row = 0; row < 2; ++row) {
            entries.clear();
            for (const Block& b : blocks) {
                const double first = row == 0 ? b.uu : b.vu, second = row == 0 ? b.uv : b.vv;
                if (unknown[b.column_vertex] < 0) {
                    rhs[2 * unknown[i] + row] -=
                        first * uv[b.column_vertex].x() + second * uv[b.column_vertex].y();
                    continue;
                }
                // Only boundary edges couple u and v: elsewhere the two coordinates are two
                // Laplace systems, and leaving the zero cross terms out of the pattern keeps
                // them apart in the factorization, with less fill than full 2x2 blocks.
                if (row == 0 || b.coupled)
                    entries.emplace_back(2 * unknown[b.column_vertex], first);
                if (row == 1 || b.coupled)
                    entries.emplace_back(2 * unknown[b.column_vertex] + 1, second);
            }
            std::sort(entries.begin(), entries.end());
            for (const auto& [column, value] : entries) {
                pattern.columns.push_back(column);
                values.push_back(value);
            }
            pattern.row_offsets.push_back(static_cast<int32_t>(pattern.columns.size()));
        }
    }
    // Ordered on the graph of vertices, u_i and v_i together: ordering the 2n unknowns on
    // their own took 12% of a decimated-max atlas instead of 7%, for the same factorization.
    std::vector<int32_t> order;
    order.reserve(2 * static_cast<size_t>(count));
    for (int32_t v : vertex_order) {
        if (unknown[v] < 0) continue;
        order.push_back(2 * unknown[v]);
        order.push_back(2 * unknown[v] + 1);
    }
    // The conformal energy is a symmetric positive definite form once two vertices are pinned:
    // Cholesky, half the work of the LU.
    SparseSolver solver(std::move(pattern), std::move(order), Factorization::kCholesky);
    solver.solve(values, rhs.data(), 1, nullptr);
    for (int32_t v = 0; v < n; ++v) {
        if (unknown[v] >= 0) uv[v] = Eigen::Vector2d(rhs[2 * unknown[v]], rhs[2 * unknown[v] + 1]);
    }
    return uv;
}

}  // namespace raps
