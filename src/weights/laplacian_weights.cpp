#include "weights/laplacian_weights.h"

#include "core/fill_in_runs.h"

namespace raps {

std::vector<double> laplacian_weights(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                                      WeightScheme scheme, const ProgressSpan& progress) {
    if (scheme == WeightScheme::kUniform)
        return filled_in_runs(adjacency.neighbors.size(), 1.0, progress);
    std::vector<double> weights =
        filled_in_runs(adjacency.neighbors.size(), 0.0, progress.part(0.0, 0.1));
    progress.part(0.1, 1.0).in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            for (int k = 0; k < 3; ++k) {
                // Corner k at vertex i, with j following and l preceding it in the triangle.
                const Triangle& v = mesh.triangles[t];
                const int32_t i = v[k], j = v[(k + 1) % 3], l = v[(k + 2) % 3];
                const Eigen::Vector3d a = mesh.positions[j] - mesh.positions[i];
                const Eigen::Vector3d b = mesh.positions[l] - mesh.positions[i];
                const double sine = a.cross(b).norm(), cosine = a.dot(b);  // both times |a||b|
                const int32_t h_ij = 3 * t + k;                            // half-edge i -> j
                const int32_t h_li = 3 * t + (k + 2) % 3;                  // half-edge l -> i
                if (scheme == WeightScheme::kMeanValue) {
                    // tan(theta / 2) = sin / (1 + cos), free of trigonometric calls and stable for
                    // small angles; theta < pi for a triangle of nonzero area.
                    const double la = a.norm(), lb = b.norm();
                    const double half_tan = sine / (la * lb + cosine);
                    weights[adjacency.forward_slot[h_ij]] += half_tan / la;
                    weights[adjacency.backward_slot[h_li]] += half_tan / lb;
                } else {
                    // The angle at i is opposite edge (j, l).
                    const double half_cot = 0.5 * cosine / sine;
                    const int32_t h_jl = 3 * t + (k + 1) % 3;
                    weights[adjacency.forward_slot[h_jl]] += half_cot;
                    weights[adjacency.backward_slot[h_jl]] += half_cot;
                }
            }
        }
    });
    return weights;
}

}  // namespace raps
