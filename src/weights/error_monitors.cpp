#include "weights/error_monitors.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/fill_in_runs.h"
#include "core/portable_math.h"

namespace raps {
namespace {

// Accumulates per-triangle values onto directed edges and averages them.
class EdgeAverage {
  public:
    EdgeAverage(size_t slots, const ProgressSpan& progress)
        : sum_(filled_in_runs(slots, 0.0, progress.part(0.0, 0.5))),
          count_(filled_in_runs(slots, 0, progress.part(0.5, 1.0))) {}
    void add(int32_t slot, double value) {
        sum_[slot] += value;
        ++count_[slot];
    }
    std::vector<double> mean(const ProgressSpan& progress) && {
        progress.in_runs(static_cast<int64_t>(sum_.size()), [&](int64_t begin, int64_t end) {
            for (int64_t s = begin; s < end; ++s) sum_[s] = count_[s] ? sum_[s] / count_[s] : 1.0;
        });
        return std::move(sum_);
    }

  private:
    std::vector<double> sum_;
    std::vector<int> count_;
};

std::vector<double> area_monitor(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                                 const MapGeometry& map, const ProgressSpan& progress) {
    const int32_t triangle_count = mesh.triangle_count();
    // Progress: the ratios (a pass over the triangles), then their average onto the edges.
    std::vector<double> ratio = filled_in_runs(triangle_count, 0.0, progress.part(0.0, 0.05));
    double total_map = 0.0, total_3d = 0.0;
    progress.part(0.05, 0.45).in_runs(triangle_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = mesh.triangles[t];
            const double map_area = map.area(v[0], v[1], v[2]);
            const double area = 0.5 * (mesh.positions[v[1]] - mesh.positions[v[0]])
                                          .cross(mesh.positions[v[2]] - mesh.positions[v[0]])
                                          .norm();
            ratio[t] = map_area / area;
            total_map += std::abs(map_area);
            total_3d += area;
        }
    });
    const double scale = total_3d / total_map;
    EdgeAverage average(adjacency.neighbors.size(), progress.part(0.45, 0.5));
    for (int32_t t = 0; t < triangle_count; ++t) {
        progress.at(t, triangle_count, 0.5, 0.95);
        const double e = std::max(ratio[t] * scale, kMonitorFloor);
        for (int k = 0; k < 3; ++k) {
            average.add(adjacency.forward_slot[3 * t + k], e);
            average.add(adjacency.backward_slot[3 * t + k], e);
        }
    }
    return std::move(average).mean(progress.part(0.95, 1.0));
}

std::vector<double> length_monitor(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                                   const MapGeometry& map, const ProgressSpan& progress) {
    std::vector<double> e =
        filled_in_runs(adjacency.neighbors.size(), 0.0, progress.part(0.0, 0.1));
    double total_map = 0.0, total_3d = 0.0;
    progress.part(0.1, 0.9).in_runs(mesh.vertex_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t i = static_cast<int32_t>(run_begin); i < run_end; ++i) {
            for (int32_t s = adjacency.offsets[i]; s < adjacency.offsets[i + 1]; ++s) {
                const int32_t j = adjacency.neighbors[s];
                const double map_length = map.length(i, j);
                const double length = (mesh.positions[i] - mesh.positions[j]).norm();
                e[s] = map_length / length;
                total_map += map_length;
                total_3d += length;
            }
        }
    });
    const double scale = total_3d / total_map;
    progress.part(0.9, 1.0).in_runs(static_cast<int64_t>(e.size()),
                                    [&](int64_t begin, int64_t end) {
                                        for (int64_t s = begin; s < end; ++s)
                                            e[s] = std::max(e[s] * scale, kMonitorFloor);
                                    });
    return e;
}

std::vector<double> angle_monitor(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                                  const MapGeometry& map, const ProgressSpan& progress) {
    EdgeAverage average(adjacency.neighbors.size(), progress.part(0.0, 0.1));
    progress.part(0.1, 0.9).in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = mesh.triangles[t];
            for (int k = 0; k < 3; ++k) {
                const int32_t i = v[k], j = v[(k + 1) % 3], l = v[(k + 2) % 3];
                const Eigen::Vector3d a = mesh.positions[j] - mesh.positions[i];
                const Eigen::Vector3d b = mesh.positions[l] - mesh.positions[i];
                const double angle = portable::atan2(a.cross(b).norm(), a.dot(b));
                double sine, cosine;
                map.angle(i, j, l, &sine, &cosine);
                // Signed: a flipped triangle has a negative angle in the map and gets the floor.
                const double map_angle = portable::atan2(sine, cosine);
                const double e = std::max(map_angle / angle, kMonitorFloor);
                average.add(adjacency.forward_slot[3 * t + k], e);             // i -> j
                average.add(adjacency.backward_slot[3 * t + (k + 2) % 3], e);  // i -> l
            }
        }
    });
    return std::move(average).mean(progress.part(0.9, 1.0));
}

}  // namespace

std::vector<double> error_monitor(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                                  const MapGeometry& map, Monitor monitor,
                                  const ProgressSpan& progress) {
    switch (monitor) {
        case Monitor::kArea:
            return area_monitor(mesh, adjacency, map, progress);
        case Monitor::kEdgeLength:
            return length_monitor(mesh, adjacency, map, progress);
        case Monitor::kAngle:
            return angle_monitor(mesh, adjacency, map, progress);
        case Monitor::kNone:
            break;
    }
    throw Error(ErrorCode::kInternal, "error_monitor called without a monitor");
}

}  // namespace raps
