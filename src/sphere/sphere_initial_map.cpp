#include "sphere/sphere_initial_map.h"

#include <algorithm>
#include <cmath>

#include "core/portable_math.h"
#include "planar/laplace_system.h"
#include "sphere/mobius_centring.h"
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

// Angles on the unit circle for the ring of `pole`, counter-clockwise in ring order,
// proportional to the 3D corner angles at the pole; equal angles if that would give one gap of
// more than 0.9 pi (the star triangle would be nearly flat on the sphere).
std::vector<double> ring_angles(const TriangleMesh& mesh, int32_t pole,
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
    std::vector<char> fixed(mesh.positions.size(), 0);
    fixed[pole] = 1;
    std::vector<Eigen::Vector2d> plane(mesh.positions.size(), Eigen::Vector2d::Zero());
    const std::vector<double> angle = ring_angles(mesh, pole, ring);
    for (size_t m = 0; m < ring.size(); ++m) {
        fixed[ring[m]] = 1;
        plane[ring[m]] = Eigen::Vector2d(portable::cos(angle[m]), portable::sin(angle[m]));
    }
    const WeightScheme positive =
        weights == WeightScheme::kCotangent ? WeightScheme::kMeanValue : weights;
    {
        // Progress: ordering and analysis, weights, solve; the centring after it.
        LaplaceSystem system(mesh, problem.adjacency, fixed, {}, progress.part(0.0, 0.4));
        system.solve(laplacian_weights(mesh, problem.adjacency, positive, progress.part(0.4, 0.45)),
                     plane, progress.part(0.45, 0.9));
    }

    // Inverse stereographic projection of s * plane. The ring (radius 1) lands on the circle of
    // height (s^2 - 1) / (s^2 + 1), which leaves the cap above it 4 pi / (1 + s^2): the pole's
    // star gets the share of the sphere that it has of the 3D area. The scale is the first
    // Moebius map of the centring, which is done on the planar points.
    const double star_share = std::clamp(3.0 * problem.mass[pole], 1e-12, 0.5);
    const double s = std::sqrt(1.0 / star_share - 1.0);
    std::vector<Eigen::Vector3d> points =
        mobius_centred_lift(problem, plane, pole, s, pool, 1e-4, 100, progress.part(0.9, 0.95));
    mobius_centre(problem, points, pool, 1e-4, 100, progress.part(0.95, 1.0));
    progress.report(1.0);
    return points;
}

}  // namespace raps
