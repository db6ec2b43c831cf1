#include "planar/adaptive_map.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "weights/adaptive_weights.h"
#include "weights/error_monitors.h"

namespace raps {
namespace {

// The first vertex one of whose edges, weighted in the base weights, lost its weight (0 or not
// a number) in the adapted ones; -1 when none did.
int32_t vertex_with_vanished_weight(const VertexAdjacency& adjacency,
                                    const std::vector<double>& base,
                                    const std::vector<double>& adapted) {
    const int32_t vertex_count = static_cast<int32_t>(adjacency.offsets.size()) - 1;
    for (int32_t v = 0; v < vertex_count; ++v) {
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            if (base[s] > 0 && !(adapted[s] > 0 && std::isfinite(adapted[s]))) return v;
        }
    }
    return -1;
}

}  // namespace

int64_t adapt_map(const TriangleMesh& mesh, const VertexAdjacency& adjacency, LaplaceSystem& system,
                  const std::vector<double>& base_weights, const Settings& settings,
                  std::vector<Eigen::Vector2d>& uv, const ProgressSpan& progress) {
    if (settings.monitor == Monitor::kNone) return 0;
    // No copy of base_weights to start from (tens of megabytes at millions of triangles, a
    // progress gap of its own): the first step reads them, later ones what the last one made.
    std::vector<double> weights;
    for (int step = 0; step < settings.iterations; ++step) {
        // Per step: the monitor and the weights (passes over the mesh), then the solve.
        const ProgressSpan span =
            progress.part(static_cast<double>(step) / settings.iterations,
                          static_cast<double>(step + 1) / settings.iterations);
        const std::vector<double> monitor = error_monitor(mesh, adjacency, PlanarMapGeometry(uv),
                                                          settings.monitor, span.part(0.0, 0.1));
        const std::vector<double>& previous =
            settings.iteration_mode == IterationMode::kAccumulate && step > 0 ? weights
                                                                              : base_weights;
        weights =
            adaptive_weights(adjacency, previous, monitor, settings.alpha, span.part(0.1, 0.2));
        try {
            system.solve(weights, uv, span.part(0.2, 1.0));
        } catch (const Error& error) {
            if (error.code() != ErrorCode::kSolverFailed) throw;
            const int32_t vertex = vertex_with_vanished_weight(adjacency, base_weights, weights);
            if (vertex < 0) throw;
            char alpha[32];
            std::snprintf(alpha, sizeof(alpha), "%g", settings.alpha);
            throw Error(ErrorCode::kSolverFailed,
                        "adaptive step " + std::to_string(step + 1) + " of " +
                            std::to_string(settings.iterations) +
                            ": the error monitor raised to alpha " + alpha +
                            " spans more than doubles hold, so weights around vertex " +
                            std::to_string(vertex) +
                            " underflow to 0 and the system is singular: "
                            "lower alpha or the iterations");
        }
    }
    return settings.iterations;
}

}  // namespace raps
