#include "atlas/free_boundary_map.h"

#include <algorithm>
#include <map>

#include "solver/sparse_solver.h"

namespace raps {

std::vector<Eigen::Vector2d> free_boundary_conformal_map(
    const TriangleMesh& mesh, const std::vector<int32_t>& boundary_loop) {
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

    // Unknowns 2i (u) and 2i+1 (v) for every vertex but the pins.
    std::vector<int32_t> unknown(n, -1);
    int32_t count = 0;
    for (int32_t v = 0; v < n; ++v) {
        if (v != pin_a && v != pin_b) unknown[v] = count++;
    }
    // Quadratic form of E_D - A as (row, column) -> value over the 2n coordinates, assembled
    // per triangle: the cotangent Laplacian on u and on v, and for each boundary edge i -> j
    // the area term -(u_i v_j - u_j v_i) / 2.
    std::map<std::pair<int32_t, int32_t>, double> entries;
    auto add = [&](int32_t a, int32_t b, double value) { entries[{a, b}] += value; };
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        const Triangle& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k) {
            const int32_t o = tri[k], i = tri[(k + 1) % 3], j = tri[(k + 2) % 3];
            const Eigen::Vector3d a = mesh.positions[i] - mesh.positions[o];
            const Eigen::Vector3d b = mesh.positions[j] - mesh.positions[o];
            const double w = 0.5 * a.dot(b) / a.cross(b).norm();  // half the cotangent at o
            for (int c = 0; c < 2; ++c) {
                add(2 * i + c, 2 * i + c, w);
                add(2 * j + c, 2 * j + c, w);
                add(2 * i + c, 2 * j + c, -w);
                add(2 * j + c, 2 * i + c, -w);
            }
        }
    }
    for (size_t k = 0; k < boundary_loop.size(); ++k) {
        const int32_t i = boundary_loop[k], j = boundary_loop[(k + 1) % boundary_loop.size()];
        add(2 * i, 2 * j + 1, -0.5);
        add(2 * j + 1, 2 * i, -0.5);
        add(2 * j, 2 * i + 1, 0.5);
        add(2 * i + 1, 2 * j, 0.5);
    }
    // The reduced system over the free coordinates; pinned coordinates move to the right.
    SparsePattern pattern;
    pattern.size = 2 * count;
    std::vector<double> values, rhs(2 * static_cast<size_t>(count), 0.0);
    std::vector<std::vector<std::pair<int32_t, double>>> rows(2 * static_cast<size_t>(count));
    for (const auto& [key, value] : entries) {
        const int32_t row_vertex = key.first / 2, column_vertex = key.second / 2;
        if (unknown[row_vertex] < 0) continue;
        const int32_t row = 2 * unknown[row_vertex] + key.first % 2;
        if (unknown[column_vertex] < 0) {
            rhs[row] -= value * uv[column_vertex][key.second % 2];
        } else {
            rows[row].emplace_back(2 * unknown[column_vertex] + key.second % 2, value);
        }
    }
    for (auto& row : rows) {
        std::sort(row.begin(), row.end());
        for (const auto& [column, value] : row) {
            pattern.columns.push_back(column);
            values.push_back(value);
        }
        pattern.row_offsets.push_back(static_cast<int32_t>(pattern.columns.size()));
    }
    std::vector<Eigen::Vector3d> coordinates(2 * static_cast<size_t>(count));
    for (int32_t v = 0; v < n; ++v) {
        if (unknown[v] >= 0)
            coordinates[2 * unknown[v]] = coordinates[2 * unknown[v] + 1] = mesh.positions[v];
    }
    SparseSolver solver(std::move(pattern), coordinates);
    solver.solve(values, rhs.data(), 1, nullptr);
    for (int32_t v = 0; v < n; ++v) {
        if (unknown[v] >= 0) uv[v] = Eigen::Vector2d(rhs[2 * unknown[v]], rhs[2 * unknown[v] + 1]);
    }
    return uv;
}

}  // namespace raps
