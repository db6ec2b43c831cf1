#include "weights/adaptive_weights.h"

#include <algorithm>
#include <cmath>

#include "core/fill_in_runs.h"
#include "core/portable_math.h"

namespace raps {

std::vector<double> adaptive_weights(const VertexAdjacency& adjacency,
                                     const std::vector<double>& weights,
                                     const std::vector<double>& monitor, double alpha,
                                     const ProgressSpan& progress) {
    std::vector<double> adapted = filled_in_runs(weights.size(), 0.0, progress.part(0.0, 0.1));
    const int32_t vertex_count = static_cast<int32_t>(adjacency.offsets.size()) - 1;
    progress.part(0.1, 1.0).in_runs(vertex_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t v = static_cast<int32_t>(run_begin); v < run_end; ++v) {
            const int32_t begin = adjacency.offsets[v], end = adjacency.offsets[v + 1];
            double row_sum = 0.0;
            for (int32_t s = begin; s < end; ++s) {
                const double exponent =
                    std::clamp(alpha * portable::log(monitor[s]), -600.0, 600.0);
                adapted[s] = weights[s] * portable::exp(exponent);
                row_sum += adapted[s];
            }
            // A row sum that is not positive (possible with negative cotangent weights) is left
            // unscaled; the solver reports the row if it is singular.
            if (row_sum > 0.0 && std::isfinite(row_sum)) {
                for (int32_t s = begin; s < end; ++s) adapted[s] /= row_sum;
            }
        }
    });
    return adapted;
}

}  // namespace raps
