#include "planar/adaptive_map.h"

#include "weights/adaptive_weights.h"
#include "weights/error_monitors.h"

namespace raps {

int64_t adapt_map(const TriangleMesh& mesh, const VertexAdjacency& adjacency, LaplaceSystem& system,
                  const std::vector<double>& base_weights, const Settings& settings,
                  std::vector<Eigen::Vector2d>& uv, const std::function<void(double)>& progress) {
    if (settings.monitor == Monitor::kNone) return 0;
    std::vector<double> weights = base_weights;
    for (int step = 0; step < settings.iterations; ++step) {
        const std::vector<double> monitor =
            error_monitor(mesh, adjacency, PlanarMapGeometry(uv), settings.monitor);
        const std::vector<double>& previous =
            settings.iteration_mode == IterationMode::kAccumulate ? weights : base_weights;
        weights = adaptive_weights(adjacency, previous, monitor, settings.alpha);
        system.solve(weights, uv, [&](double fraction) {
            if (progress) progress((step + fraction) / settings.iterations);
        });
    }
    return settings.iterations;
}

}  // namespace raps
