#include "sphere/sphere_initial_map.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/fill_in_runs.h"
#include "core/portable_math.h"
#include "core/release_in_runs.h"
#include "planar/laplace_system.h"
#include "sphere/cylinder_initial_map.h"
#include "sphere/exact_orientation.h"
#include "sphere/mobius_centring.h"
#include "sphere/sphere_map_check.h"
#include "weights/laplacian_weights.h"

namespace raps {
namespace {

// The pole: a vertex of largest degree (its ring is the roundest polygon), the lowest index
// among equals.
int32_t choose_pole(const SphereProblem& problem) {
    const VertexAdjacency& adjacency = problem.adjacency;
    int32_t best = 0;
    for (int32_t v = 1; v < problem.mesh.vertex_count(); ++v) {
        const int32_t degree = adjacency.offsets[v + 1] - adjacency.offsets[v];
        if (degree > adjacency.offsets[best + 1] - adjacency.offsets[best]) best = v;
    }
    return best;
}

}  // namespace

std::vector<double> pole_ring_angles(const TriangleMesh& mesh, int32_t pole,
                                     const std::vector<int32_t>& ring) {
    const size_t k = ring.size();
    std::vector<double> corner(k);
    double total = 0.0;
    for (size_t m = 0; m < k; ++m) {
        const Eigen::Vector3d a = mesh.positions[ring[m]] - mesh.positions[pole];
        const Eigen::Vector3d b = mesh.positions[ring[(m + 1) % k]] - mesh.positions[pole];
        corner[m] = portable::atan2(a.cross(b).norm(), a.dot(b));
        total += corner[m];
    }
    const double largest = *std::max_element(corner.begin(), corner.end());
    const bool even = !(total > 0.0) || largest * 2.0 * M_PI / total > 0.9 * M_PI;
    std::vector<double> angle(k);
    double sum = 0.0;
    for (size_t m = 0; m < k; ++m) {
        angle[m] = sum;
        sum += even ? 2.0 * M_PI / static_cast<double>(k) : corner[m] * 2.0 * M_PI / total;
    }
    return angle;
}

namespace {

// Planar triangles (the pole's star left out) that are not clockwise, by the exact sign (the
// disk comes out clockwise, below).
int64_t count_planar_folds(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& plane,
                           int32_t pole, const ProgressSpan& beat) {
    int64_t folded = 0;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        beat.at(static_cast<int64_t>(i), mesh.triangle_count());
        const Triangle& t = mesh.triangles[i];
        if (t[0] == pole || t[1] == pole || t[2] == pole) continue;
        const auto at = [&](int32_t v) { return Eigen::Vector3d(plane[v].x(), plane[v].y(), 1.0); };
        folded += exact_orientation_sign(at(t[0]), at(t[1]), at(t[2])) >= 0;
    }
    return folded;
}

}  // namespace

std::vector<Eigen::Vector3d> stereographic_initial_map(const SphereProblem& problem,
                                                       WeightScheme weights, ThreadPool& pool,
                                                       const ProgressSpan& progress) {
    const TriangleMesh& mesh = problem.mesh;
    const int32_t pole = choose_pole(problem);
    const std::vector<int32_t> ring = vertex_ring(mesh, problem.halfedges, pole);

    // The punctured mesh as a disk: the pole and its ring are fixed, every other vertex is an
    // unknown of the Laplace system (none of them is adjacent to the pole). The ring runs
    // counter-clockwise, so the disk (on the other side of the ring from the pole's star) comes
    // out clockwise: the orientation that stereographic projection from the north pole, seen
    // from outside the sphere, turns counter-clockwise again.
    // The large arrays are filled, and given back, in runs (fill_in_runs.h, release_in_runs.h):
    // at 5.65M triangles each was 40 to 200 ms of fresh or freed pages without a progress call.
    const ProgressSpan beat = progress.part(0.0, 0.0);
    std::vector<char> fixed = filled_in_runs(mesh.positions.size(), char{0}, beat);
    fixed[pole] = 1;
    std::vector<Eigen::Vector2d> plane =
        filled_in_runs(mesh.positions.size(), Eigen::Vector2d::Zero().eval(), beat);
    const std::vector<double> angle = pole_ring_angles(mesh, pole, ring);
    for (size_t m = 0; m < ring.size(); ++m) {
        fixed[ring[m]] = 1;
        plane[ring[m]] = Eigen::Vector2d(portable::cos(angle[m]), portable::sin(angle[m]));
    }
    const WeightScheme positive =
        weights == WeightScheme::kCotangent ? WeightScheme::kMeanValue : weights;
    {
        // Progress: ordering and analysis, weights, solve; the centring after it.
        LaplaceSystem system(mesh, problem.adjacency, fixed, {}, progress.part(0.0, 0.4));
        std::vector<double> w =
            laplacian_weights(mesh, problem.adjacency, positive, progress.part(0.4, 0.45));
        system.solve(w, plane, progress.part(0.45, 0.9));
        release_in_runs(w, progress.part(0.9, 0.9));
        system.release(progress.part(0.9, 0.9));
    }
    release_in_runs(fixed, progress.part(0.9, 0.9));

    // Inverse stereographic projection of s * plane. The ring (radius 1) lands on the circle of
    // height (s^2 - 1) / (s^2 + 1), which leaves the cap above it 4 pi / (1 + s^2): the pole's
    // star gets the share of the sphere that it has of the 3D area. The scale is the first
    // Moebius map of the centring, which is done on the planar points.
    const double star_share = std::clamp(3.0 * problem.mass[pole], 1e-12, 0.5);
    const double s = std::sqrt(1.0 / star_share - 1.0);
    std::vector<Eigen::Vector3d> points =
        mobius_centred_lift(problem, plane, pole, s, pool, 1e-4, 100, progress.part(0.9, 0.93));
    mobius_centre(problem, points, pool, 1e-4, 100, progress.part(0.93, 0.96));
    // A planar fold is rounding (the exact solution is an embedding): a long part squeezed below
    // the solve's absolute error. Then the two-puncture map, where it folds fewer triangles.
    if (count_planar_folds(mesh, plane, pole, progress.part(0.96, 0.96)) > 0) {
        std::optional<CylinderCoordinates> coordinates;
        try {
            coordinates = cylinder_coordinates(problem, weights, progress.part(0.96, 0.98));
        } catch (const Error& e) {
            // A singular system leaves the one-puncture map (refused later if still folded).
            if (e.code() != ErrorCode::kSolverFailed) throw;
        }
        if (coordinates) {
            std::vector<Eigen::Vector3d> cylinder =
                conformal_cylinder_map(problem, *coordinates, progress.part(0.98, 0.98));
            mobius_centre(problem, cylinder, pool, 1e-4, 100, progress.part(0.98, 1.0));
            if (count_folds(mesh, cylinder, progress.part(1.0, 1.0)).folded <
                count_folds(mesh, points, progress.part(1.0, 1.0)).folded) {
                points.swap(cylinder);
            }
        }
    }
    release_in_runs(plane, progress.part(1.0, 1.0));
    progress.report(1.0);
    return points;
}

}  // namespace raps
