#include "planar/adaptive_map.h"

#include "weights/adaptive_weights.h"
#include "weights/error_monitors.h"

namespace raps {

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
        system.solve(weights, uv, span.part(0.2, 1.0));
    }
    return settings.iterations;
}

}  // namespace raps
