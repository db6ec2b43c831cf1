#include "atlas/chart_parameterization.h"

#include <cmath>

#include "atlas/free_boundary_map.h"
#include "atlas/map_validity.h"
#include "core/error.h"
#include "mesh/mesh_topology.h"
#include "metrics/distortion.h"
#include "planar/adaptive_map.h"
#include "planar/convex_boundary.h"
#include "weights/laplacian_weights.h"

namespace raps {
namespace {

// Scales uv about its centroid so that its area equals the chart's 3D area, and fills in the
// stretch figures.
// Both report to `beat` as they go: each is a pass or two over the chart's triangles.
void normalise(const ChartDisk& disk, ChartMap& map, const ProgressSpan& beat) {
    double uv_area = 0, area = 0;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < disk.mesh.triangles.size(); ++i) {
        beat.at(static_cast<int64_t>(i), disk.mesh.triangle_count());
        const Triangle& t = disk.mesh.triangles[i];
        const Eigen::Vector2d a = map.uv[t[1]] - map.uv[t[0]], b = map.uv[t[2]] - map.uv[t[0]];
        uv_area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
        area += 0.5 * (disk.mesh.positions[t[1]] - disk.mesh.positions[t[0]])
                          .cross(disk.mesh.positions[t[2]] - disk.mesh.positions[t[0]])
                          .norm();
    }
    for (const Eigen::Vector2d& p : map.uv) centroid += p;
    centroid /= static_cast<double>(map.uv.size());
    const double scale = uv_area > 0 ? std::sqrt(area / uv_area) : 1.0;
    for (Eigen::Vector2d& p : map.uv) p = (p - centroid) * scale;
    beat.report(0.0);
    const Stretch stretch = measure_stretch(disk.mesh.positions, map.uv, disk.mesh.triangles, beat);
    map.stretch_l2 = stretch.l2;
    map.stretch_linf = stretch.linf;
}

bool injective(const ChartDisk& disk, const std::vector<Eigen::Vector2d>& uv,
               const ProgressSpan& beat) {
    for (const Eigen::Vector2d& p : uv) {
        if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return false;
    }
    beat.report(0.0);
    return count_flipped_or_degenerate(disk.mesh, uv, beat) == 0 &&
           !boundary_self_intersects(uv, disk.boundary_loop);
}

// The adaptive step on `start` with its boundary held; returns whether it gave a map.
bool adapted(const ChartDisk& disk, const Settings& settings,
             const std::vector<Eigen::Vector2d>& start, ChartMap& out, LaplaceSystem& system,
             const ProgressSpan& progress) {
    const VertexAdjacency& adjacency = disk.adjacency;
    if (system.unknown_count() == 0) return false;
    const std::vector<double> base =
        laplacian_weights(disk.mesh, adjacency, settings.weights, progress);
    out.uv = start;
    try {
        adapt_map(disk.mesh, adjacency, system, base, settings, out.uv, progress);
    } catch (const Error& error) {
        if (error.code() != ErrorCode::kSolverFailed) throw;
        return false;
    }
    progress.report(0.0);
    out.injective = injective(disk, out.uv, progress.part(0.0, 0.0));
    return out.injective;
}

}  // namespace

LaplaceSystem chart_laplace_system(const ChartDisk& disk, const ProgressSpan& progress) {
    std::vector<char> on_boundary(disk.mesh.positions.size(), 0);
    for (int32_t v : disk.boundary_loop) on_boundary[v] = 1;
    return LaplaceSystem(disk.mesh, disk.adjacency, on_boundary, disk.vertex_order, progress);
}

ChartMap circle_chart_map(const ChartDisk& disk, const Settings& settings, LaplaceSystem& system,
                          const ProgressSpan& progress) {
    ChartMap circle;
    circle.method = ChartMethod::kCircle;
    circle.uv.assign(disk.mesh.positions.size(), Eigen::Vector2d(0.5, 0.5));
    const std::vector<Eigen::Vector2d> boundary =
        convex_boundary(disk.mesh, disk.boundary_loop, BoundaryShape::kCircle);
    for (size_t i = 0; i < disk.boundary_loop.size(); ++i)
        circle.uv[disk.boundary_loop[i]] = boundary[i];
    const std::vector<double> base =
        laplacian_weights(disk.mesh, disk.adjacency, WeightScheme::kMeanValue);
    system.solve(base, circle.uv, progress);
    const ProgressSpan beat = progress.part(0.0, 0.0);
    circle.injective = injective(disk, circle.uv, beat);
    normalise(disk, circle, beat);
    adapt_chart_map(disk, settings, 1e300, circle, system, progress);
    return circle;
}

ChartMap free_boundary_chart_map(const ChartDisk& disk, LaplaceSystem& system, double max_linf,
                                 double give_up_l2, const ProgressSpan& progress) {
    ChartMap map;
    map.method = ChartMethod::kFreeBoundary;
    try {
        // The Linf prediction is given 5% of room, four times the largest shortfall measured.
        const double give_up_linf = 1.05 * max_linf;
        ConformalPrediction predicted;
        map.uv = free_boundary_conformal_map(disk.mesh, disk.adjacency, disk.angle_sum,
                                             disk.boundary_loop, system,
                                             {give_up_linf, give_up_l2}, predicted, progress);
        map.predicted_l2 = predicted.l2;
        map.over_l2 = predicted.l2 > give_up_l2 && !(predicted.linf > give_up_linf);
        progress.report(0.0);
        map.injective = !map.uv.empty() && injective(disk, map.uv, progress.part(0.0, 0.0));
    } catch (const Error& error) {
        if (error.code() != ErrorCode::kSolverFailed) throw;
        map.injective = false;
    }
    progress.report(0.0);
    if (map.injective) normalise(disk, map, progress.part(0.0, 0.0));
    return map;
}

void adapt_chart_map(const ChartDisk& disk, const Settings& settings, double max_linf,
                     ChartMap& map, LaplaceSystem& system, const ProgressSpan& progress) {
    // A chart the free boundary already maps (nearly) isometrically gains nothing.
    if (settings.monitor == Monitor::kNone || !map.injective || map.stretch_l2 < 1.0005) return;
    ChartMap candidate;
    candidate.method = map.method == ChartMethod::kCircle ? ChartMethod::kCircleAdapted
                                                          : ChartMethod::kFreeBoundaryAdapted;
    Settings chosen = settings;
    if (map.method == ChartMethod::kCircle) chosen.weights = WeightScheme::kMeanValue;
    if (!adapted(disk, chosen, map.uv, candidate, system, progress)) return;
    progress.report(0.0);
    normalise(disk, candidate, progress.part(0.0, 0.0));
    // Equalising area can stretch a few triangles more: keep the Linf limit.
    if (candidate.stretch_l2 < map.stretch_l2 &&
        candidate.stretch_linf <= std::max(max_linf, map.stretch_linf)) {
        candidate.adaptive_solves = settings.iterations;
        map = std::move(candidate);
    }
}

}  // namespace raps
