#include "sphere/best_sphere_map.h"

#include <cmath>

#include "core/fill_in_runs.h"
#include "core/portable_math.h"
#include "core/release_in_runs.h"
#include "mesh/mesh_validation.h"
#include "sphere/mobius_centring.h"
#include "sphere/spherical_geometry.h"

namespace raps {
namespace {

struct Totals {
    int64_t folded = 0;
    double area_3d = 0, area_map = 0;
    Totals& operator+=(const Totals& o) {
        folded += o.folded;
        area_3d += o.area_3d;
        area_map += o.area_map;
        return *this;
    }
};

}  // namespace

SphereMapScore score_sphere_map(const SphereProblem& problem, const std::vector<Eigen::Vector3d>& u,
                                ThreadPool& pool, const ProgressSpan& beat) {
    const TriangleMesh& mesh = problem.mesh;
    const int64_t count = mesh.triangle_count();
    // Fresh pages touched, and given back, in runs: 90 MB at 5.65M triangles, 77 ms in one go.
    std::vector<double> area_3d = filled_in_runs(static_cast<size_t>(count), 0.0, beat);
    std::vector<double> area_map = filled_in_runs(static_cast<size_t>(count), 0.0, beat);
    const Totals totals = parallel_sum<Totals>(pool, count, [&](int64_t begin, int64_t end) {
        Totals sum;
        for (int64_t t = begin; t < end; ++t) {
            beat.at(t, count);
            const Triangle& v = mesh.triangles[t];
            area_3d[t] = triangle_area(mesh, static_cast<int32_t>(t));
            area_map[t] = spherical_triangle_area(u[v[0]], u[v[1]], u[v[2]]);
            sum.folded += !(orientation(u[v[0]], u[v[1]], u[v[2]]) > 0.0);
            sum.area_3d += area_3d[t];
            sum.area_map += std::abs(area_map[t]);
        }
        return sum;
    });
    SphereMapScore score;
    score.folded = totals.folded;
    score.centre = centre_of_mass(problem, u, pool, beat).norm();
    score.area_log = parallel_sum<double>(pool, count, [&](int64_t begin, int64_t end) {
        double sum = 0.0;
        for (int64_t t = begin; t < end; ++t) {
            beat.at(t, count);
            const double weight = area_3d[t] / totals.area_3d;
            const double r = std::abs(area_map[t]) / totals.area_map / weight;
            sum += weight * std::abs(portable::log(r));
        }
        return sum;
    });
    release_in_runs(area_3d, beat);
    release_in_runs(area_map, beat);
    return score;
}

bool better_sphere_map(const SphereMapScore& candidate, const SphereMapScore& best, bool by_area) {
    if (candidate.folded != best.folded) return candidate.folded < best.folded;
    const bool centred = candidate.centre <= kCentredEnough;
    if (centred != (best.centre <= kCentredEnough)) return centred;
    if (!centred) return candidate.centre < best.centre;
    return !by_area || candidate.area_log < best.area_log;
}

}  // namespace raps
