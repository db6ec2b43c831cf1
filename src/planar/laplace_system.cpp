#include "planar/laplace_system.h"

#include <cmath>

#include "core/error.h"
#include "core/fill_in_runs.h"
#include "core/release_in_runs.h"

namespace raps {

std::vector<int32_t> vertex_elimination_order(const TriangleMesh& mesh,
                                              const VertexAdjacency& adjacency,
                                              const ProgressSpan& progress) {
    SparsePattern pattern;  // the vertex graph with its diagonal, rows sorted
    pattern.size = mesh.vertex_count();
    pattern.columns.reserve(adjacency.neighbors.size() + mesh.positions.size());
    for (int32_t v = 0; v < pattern.size; ++v) {
        progress.at(v, pattern.size, 0.0, 0.1);
        bool diagonal_placed = false;
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            if (!diagonal_placed && adjacency.neighbors[s] > v) {
                pattern.columns.push_back(v);
                diagonal_placed = true;
            }
            pattern.columns.push_back(adjacency.neighbors[s]);
        }
        if (!diagonal_placed) pattern.columns.push_back(v);
        pattern.row_offsets.push_back(static_cast<int32_t>(pattern.columns.size()));
    }
    return fill_reducing_order(pattern, mesh.positions, progress.part(0.1, 1.0));
}

namespace {

// The pattern of a Laplace system over the vertices not on the boundary, one unknown each
// (numbered in vertex order), rows sorted with the diagonal included, and where each adjacency
// slot of an unknown's row lands. vertex_order (a vertex_elimination_order(), or empty) is
// restricted to the unknowns.
struct InteriorPattern {
    SparsePattern pattern;
    std::vector<int32_t> vertex_of_unknown;
    std::vector<int32_t> value_of_slot;        // per slot of an unknown's row: its entry, or -1
    std::vector<int32_t> diagonal_of_unknown;  // its diagonal entry
    std::vector<int32_t> order;                // order[k]: the unknown eliminated k-th
};
InteriorPattern interior_pattern(const VertexAdjacency& adjacency,
                                 const std::vector<char>& on_boundary,
                                 const std::vector<int32_t>& vertex_order,
                                 const ProgressSpan& progress) {
    InteriorPattern interior;
    const int32_t vertex_count = static_cast<int32_t>(on_boundary.size());
    const ProgressSpan start = progress.part(0.0, 0.0);
    std::vector<int32_t> unknown_of_vertex = filled_in_runs(vertex_count, -1, start);
    interior.vertex_of_unknown.reserve(vertex_count);
    for (int32_t v = 0; v < vertex_count; ++v) {
        start.at(v, vertex_count);
        if (!on_boundary[v]) {
            unknown_of_vertex[v] = static_cast<int32_t>(interior.vertex_of_unknown.size());
            interior.vertex_of_unknown.push_back(v);
        }
    }
    const int32_t n = static_cast<int32_t>(interior.vertex_of_unknown.size());
    SparsePattern& pattern = interior.pattern;
    pattern.size = n;
    // Reserved: grown by push_back, the columns were copied whole at each doubling (80 MB at
    // 3M triangles, tens of milliseconds without a progress call).
    pattern.row_offsets.reserve(static_cast<size_t>(n) + 1);
    pattern.columns.reserve(adjacency.neighbors.size() + static_cast<size_t>(n));
    assign_in_runs(interior.value_of_slot, adjacency.neighbors.size(), -1, progress.part(0.0, 0.2));
    interior.diagonal_of_unknown.resize(n);
    progress.part(0.2, 1.0).in_runs(n, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t row = static_cast<int32_t>(run_begin); row < run_end; ++row) {
            const int32_t v = interior.vertex_of_unknown[row];
            bool diagonal_placed = false;
            // Neighbours are sorted by vertex and unknowns are numbered in vertex order, so the
            // columns come out sorted once the diagonal is slotted in.
            for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
                const int32_t column = unknown_of_vertex[adjacency.neighbors[s]];
                if (column < 0) continue;
                if (!diagonal_placed && column > row) {
                    interior.diagonal_of_unknown[row] =
                        static_cast<int32_t>(pattern.columns.size());
                    pattern.columns.push_back(row);
                    diagonal_placed = true;
                }
                interior.value_of_slot[s] = static_cast<int32_t>(pattern.columns.size());
                pattern.columns.push_back(column);
            }
            if (!diagonal_placed) {
                interior.diagonal_of_unknown[row] = static_cast<int32_t>(pattern.columns.size());
                pattern.columns.push_back(row);
            }
            pattern.row_offsets.push_back(static_cast<int32_t>(pattern.columns.size()));
        }
    });
    interior.order.reserve(vertex_order.size());
    for (int32_t v : vertex_order) {
        if (unknown_of_vertex[v] >= 0) interior.order.push_back(unknown_of_vertex[v]);
    }
    return interior;
}

}  // namespace

LaplaceSystem::LaplaceSystem(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                             const std::vector<char>& on_boundary,
                             const std::vector<int32_t>& vertex_order, const ProgressSpan& progress)
    : adjacency_(adjacency) {
    InteriorPattern interior =
        interior_pattern(adjacency, on_boundary, vertex_order, progress.part(0.0, 0.1));
    vertex_of_unknown_ = std::move(interior.vertex_of_unknown);
    value_of_slot_ = std::move(interior.value_of_slot);
    diagonal_of_unknown_ = std::move(interior.diagonal_of_unknown);
    if (!vertex_order.empty()) {
        solver_ = std::make_unique<SparseSolver>(
            std::move(interior.pattern), std::move(interior.order), progress.part(0.1, 1.0));
        return;
    }
    const int32_t n = unknown_count();
    std::vector<Eigen::Vector3d> coordinates;
    coordinates.reserve(n);
    progress.part(0.1, 0.11).in_runs(n, [&](int64_t run_begin, int64_t run_end) {
        for (int64_t row = run_begin; row < run_end; ++row)
            coordinates.push_back(mesh.positions[vertex_of_unknown_[row]]);
    });
    solver_ = std::make_unique<SparseSolver>(std::move(interior.pattern), coordinates,
                                             progress.part(0.11, 1.0));
}

void LaplaceSystem::solve(const std::vector<double>& weights, std::vector<Eigen::Vector2d>& uv,
                          const ProgressSpan& progress) {
    const int32_t n = unknown_count();
    if (n == 0) return;  // every vertex is on the boundary
    // Reused by the next solve: the pages are touched once per system, not once per solve.
    std::vector<double>& values = values_;
    std::vector<double>& rhs = rhs_;
    assign_in_runs(values, solver_->pattern().columns.size(), 0.0, progress.part(0.0, 0.03));
    assign_in_runs(rhs, 2 * static_cast<size_t>(n), 0.0, progress.part(0.03, 0.04));
    const ProgressSpan assembly = progress.part(0.04, 0.1);
    assembly.in_runs(n, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t row = static_cast<int32_t>(run_begin); row < run_end; ++row) {
            const int32_t v = vertex_of_unknown_[row];
            double diagonal = 0.0;
            for (int32_t s = adjacency_.offsets[v]; s < adjacency_.offsets[v + 1]; ++s) {
                diagonal += weights[s];
            }
            if (!(std::abs(diagonal) > 0.0) || !std::isfinite(diagonal)) {
                throw Error(ErrorCode::kSolverFailed,
                            "the weights around vertex " + std::to_string(v) +
                                " sum to zero or are not finite (a triangle around it is "
                                "a needle or a cap, with an angle of nearly 0 or 180 degrees), "
                                "so its row of the Laplace system is singular");
            }
            // Rows scaled to a unit diagonal: the solution is unchanged, and pivots become
            // comparable across rows whose weights differ by orders of magnitude.
            const double inverse = 1.0 / diagonal;
            values[diagonal_of_unknown_[row]] = 1.0;
            for (int32_t s = adjacency_.offsets[v]; s < adjacency_.offsets[v + 1]; ++s) {
                const double w = weights[s] * inverse;
                if (value_of_slot_[s] >= 0) {
                    values[value_of_slot_[s]] = -w;
                } else {
                    const Eigen::Vector2d& fixed = uv[adjacency_.neighbors[s]];
                    rhs[row] += w * fixed.x();
                    rhs[n + row] += w * fixed.y();
                }
            }
        }
    });
    solver_->solve(values, rhs.data(), 2, progress.part(0.1, 0.98));
    progress.part(0.98, 1.0).in_runs(n, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t row = static_cast<int32_t>(run_begin); row < run_end; ++row) {
            if (!std::isfinite(rhs[row]) || !std::isfinite(rhs[n + row])) {
                throw Error(ErrorCode::kSolverFailed,
                            "the Laplace system is numerically singular (non-finite solution at "
                            "vertex " +
                                std::to_string(vertex_of_unknown_[row]) + ")");
            }
            uv[vertex_of_unknown_[row]] = Eigen::Vector2d(rhs[row], rhs[n + row]);
        }
    });
}

void LaplaceSystem::release(const ProgressSpan& progress) {
    if (solver_) solver_->release(progress);
    solver_.reset();
    release_in_runs(values_, progress);
    release_in_runs(rhs_, progress);
    release_in_runs(value_of_slot_, progress);
    release_in_runs(vertex_of_unknown_, progress);
    release_in_runs(diagonal_of_unknown_, progress);
}

}  // namespace raps
