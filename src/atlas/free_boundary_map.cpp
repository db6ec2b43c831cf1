#include "atlas/free_boundary_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/fill_in_runs.h"
#include "core/portable_math.h"
#include "planar/laplace_system.h"
#include "solver/sparse_solver.h"
#include "weights/laplacian_weights.h"

namespace raps {

std::vector<Eigen::Vector2d> free_boundary_conformal_map(const TriangleMesh& mesh,
                                                         const VertexAdjacency& adjacency,
                                                         const std::vector<double>& angle_sum,
                                                         const std::vector<int32_t>& boundary_loop,
                                                         LaplaceSystem& system,
                                                         const ConformalGiveUp& give_up,
                                                         ConformalPrediction& predicted,
                                                         const ProgressSpan& progress) {
    const int32_t n = mesh.vertex_count();
    // Each pass reports to `beat` as it goes (at a million triangles, the passes between the
    // solves were up to 80 ms without a progress call); the solves report to `progress`.
    const ProgressSpan beat = progress.part(0.0, 0.0);
    // Angle defects: 2 pi - angle sum inside, the turning angle pi - angle sum on the boundary.
    std::vector<char> on_boundary(n, 0);
    for (int32_t v : boundary_loop) on_boundary[v] = 1;
    // The cotangent Laplacian L (the Dirichlet energy's matrix, positive definite on the
    // interior vertices) with the boundary held: Cholesky, on the system's pattern.
    const std::vector<double> cotangent =
        laplacian_weights(mesh, adjacency, WeightScheme::kCotangent, beat);
    SparseSolver& solver = system.solver();
    const std::vector<int32_t>& vertex_of = system.vertex_of_unknown();
    const std::vector<int32_t>& value_of_slot = system.value_of_slot();
    const int32_t unknowns = system.unknown_count();
    std::vector<double> values = filled_in_runs(solver.pattern().columns.size(), 0.0, beat);
    beat.in_runs(unknowns, [&](int64_t begin, int64_t end) {
        for (int64_t row = begin; row < end; ++row) {
            const int32_t v = vertex_of[row];
            double diagonal = 0;
            for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
                diagonal += cotangent[s];
                if (value_of_slot[s] >= 0) values[value_of_slot[s]] = -cotangent[s];
            }
            values[system.diagonal_of_unknown()[row]] = diagonal;
        }
    });

    // The log scale factor u that flattens the interior while keeping the boundary's lengths
    // (u = 0 there: the conformal flattening of least area distortion). A conformal change of
    // metric moves the angle defects by L u, so zero defects inside mean L_II u_I = -K_I.
    std::vector<double> log_scale(n, 0.0);
    {
        std::vector<double> rhs(unknowns);
        for (int32_t row = 0; row < unknowns; ++row)
            rhs[row] = angle_sum[vertex_of[row]] - 2 * M_PI;
        solver.solve(values, rhs.data(), 1, progress, Factorization::kCholesky);
        for (int32_t row = 0; row < unknowns; ++row) log_scale[vertex_of[row]] = rhs[row];
    }
    // A chart the caller would reject for its Linf stretch needs no map (merging tries unions
    // that fail this way: fandisk's last two, of 5,544 and 7,402 triangles, Linf 7.6 and 5.8),
    // nor one whose L2 stretch the caller can already tell is too high (merging's budget).
    {
        double area = 0, scaled_area = 0, shrunk_area = 0;
        double smallest_scale = std::numeric_limits<double>::max();
        for (size_t i = 0; i < mesh.triangles.size(); ++i) {
            beat.at(static_cast<int64_t>(i), mesh.triangle_count());
            const Triangle& t = mesh.triangles[i];
            const double a = 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]])
                                       .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
                                       .norm();
            const double scale =
                portable::exp((log_scale[t[0]] + log_scale[t[1]] + log_scale[t[2]]) / 3.0);
            area += a;
            scaled_area += a * scale * scale;
            shrunk_area += a / (scale * scale);
            smallest_scale = std::min(smallest_scale, scale);
        }
        // Scaled to the chart's area, a triangle of scale s has both stretches (1 / s) times
        // sqrt(scaled_area / area): L2 squared is the area-weighted mean of that squared.
        predicted.l2 = std::sqrt(scaled_area * shrunk_area) / area;
        predicted.linf = std::sqrt(scaled_area / area) / smallest_scale;
        if (predicted.linf > give_up.linf || predicted.l2 > give_up.l2) return {};
    }

    // The boundary curve: each vertex turns by its own turning angle plus (L u) there, and
    // every edge keeps its length. Integrating the turns does not quite close the curve (the
    // relation above is a linearisation); the lengths are corrected by the least change,
    // weighted by 1 / length, that closes it.
    const size_t m = boundary_loop.size();
    std::vector<double> length(m);
    std::vector<Eigen::Vector2d> tangent(m);
    double direction = 0;
    for (size_t k = 0; k < m; ++k) {
        const int32_t v = boundary_loop[k];
        if (k > 0) {
            double turn = M_PI - angle_sum[v];
            for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s)
                turn -= cotangent[s] * log_scale[adjacency.neighbors[s]];
            direction += turn;
        }
        tangent[k] = Eigen::Vector2d(portable::cos(direction), portable::sin(direction));
        length[k] = (mesh.positions[boundary_loop[(k + 1) % m]] - mesh.positions[v]).norm();
    }
    Eigen::Vector2d gap = Eigen::Vector2d::Zero();
    Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
    for (size_t k = 0; k < m; ++k) {
        gap += length[k] * tangent[k];
        spread += length[k] * tangent[k] * tangent[k].transpose();
    }
    const Eigen::Vector2d correction = spread.inverse() * gap;
    std::vector<Eigen::Vector2d> uv(n, Eigen::Vector2d::Zero());
    Eigen::Vector2d at = Eigen::Vector2d::Zero();
    for (size_t k = 0; k < m; ++k) {
        uv[boundary_loop[k]] = at;
        at += length[k] * (1.0 - tangent[k].dot(correction)) * tangent[k];
    }

    // The interior: the harmonic extension of the boundary curve, with the same factorization.
    if (unknowns > 0) {
        std::vector<double> rhs(2 * static_cast<size_t>(unknowns), 0.0);
        for (int32_t row = 0; row < unknowns; ++row) {
            beat.at(row, unknowns);
            const int32_t v = vertex_of[row];
            for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
                const int32_t j = adjacency.neighbors[s];
                if (!on_boundary[j]) continue;
                rhs[row] += cotangent[s] * uv[j].x();
                rhs[unknowns + row] += cotangent[s] * uv[j].y();
            }
        }
        solver.solve_more(rhs.data(), 2, progress);
        for (int32_t row = 0; row < unknowns; ++row)
            uv[vertex_of[row]] = Eigen::Vector2d(rhs[row], rhs[unknowns + row]);
    }
    return uv;
}

}  // namespace raps
