#include "mesh/mesh_validation.h"

#include <string>

#include "core/error.h"

namespace raps {

void check_indices_in_range(const TriangleMesh& mesh, const ProgressSpan& progress) {
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            for (int k = 0; k < 3; ++k) {
                const int32_t v = mesh.triangles[t][k];
                if (v < 0 || v >= mesh.vertex_count()) {
                    throw Error(ErrorCode::kIndexOutOfRange,
                                "index " + std::to_string(3 * static_cast<int64_t>(t) + k) +
                                    " (triangle " + std::to_string(t) + ") is " +
                                    std::to_string(v) + " but the mesh has only " +
                                    std::to_string(mesh.vertex_count()) + " vertices");
                }
            }
        }
    });
}

void check_no_repeated_vertices(const TriangleMesh& mesh, const ProgressSpan& progress) {
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = mesh.triangles[t];
            if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
                throw Error(ErrorCode::kRepeatedVertex,
                            "triangle " + std::to_string(t) + " (" + std::to_string(v[0]) + ", " +
                                std::to_string(v[1]) + ", " + std::to_string(v[2]) +
                                ") names the same vertex twice");
            }
        }
    });
}

double triangle_area(const TriangleMesh& mesh, int32_t triangle) {
    const Triangle& v = mesh.triangles[triangle];
    const Eigen::Vector3d& a = mesh.positions[v[0]];
    return 0.5 * (mesh.positions[v[1]] - a).cross(mesh.positions[v[2]] - a).norm();
}

void check_no_zero_area_triangles(const TriangleMesh& mesh, const ProgressSpan& progress) {
    std::vector<double> areas(mesh.triangles.size());
    double total = 0.0;
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            areas[t] = triangle_area(mesh, t);
            total += areas[t];
        }
    });
    const double threshold = 1e-12 * total / static_cast<double>(areas.size());
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        // `!(a > threshold)` also catches a mesh whose every triangle has zero area.
        if (!(areas[t] > threshold)) {
            throw Error(ErrorCode::kZeroAreaTriangle,
                        "triangle " + std::to_string(t) + " has zero area (its vertices " +
                            std::to_string(mesh.triangles[t][0]) + ", " +
                            std::to_string(mesh.triangles[t][1]) + ", " +
                            std::to_string(mesh.triangles[t][2]) + " coincide or are collinear)");
        }
    }
}

void check_no_isolated_vertices(const TriangleMesh& mesh, const ProgressSpan& progress) {
    std::vector<char> used(mesh.positions.size(), 0);
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            for (int32_t v : mesh.triangles[t]) used[v] = 1;
        }
    });
    for (int32_t v = 0; v < mesh.vertex_count(); ++v) {
        if (!used[v]) {
            throw Error(ErrorCode::kIsolatedVertex,
                        "vertex " + std::to_string(v) + " is not used by any triangle");
        }
    }
}

}  // namespace raps
