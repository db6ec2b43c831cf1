#include "sphere/sphere_parameterization.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.h"
#include "core/fill_in_runs.h"
#include "core/release_in_runs.h"
#include "mesh/mesh_topology.h"
#include "mesh/mesh_validation.h"
#include "mesh/vertex_order.h"
#include "parallel/thread_pool.h"
#include "sphere/best_sphere_map.h"
#include "sphere/cylinder_initial_map.h"
#include "sphere/gauss_map.h"
#include "sphere/mobius_centring.h"
#include "sphere/sphere_initial_map.h"
#include "sphere/sphere_map_check.h"
#include "sphere/sphere_problem.h"
#include "sphere/sphere_relaxation.h"
#include "sphere/spherical_geometry.h"
#include "weights/adaptive_weights.h"
#include "weights/error_monitors.h"
#include "weights/laplacian_weights.h"

namespace raps {

namespace {

// An initial map whose area distortion (raps_stats.area_log_mean) is above this has parts
// squeezed by orders of magnitude (capsules of aspect 10 to 100: 6.3 to 87.7; the shared genus-0
// meshes: 0.6 to 5.0, docs/sphere-status.md): there the area monitor's relaxation starts from
// the equal-area cylinder map where that is fold-free.
constexpr double kSqueezedArea = 5.0;

// The equal-area start must have at most this share of the initial map's area distortion: then
// the result, never worse than its start, keeps the promise of 40 % lower whatever the
// relaxation does from there.
constexpr double kStartBelow = 0.6;

// Replaces `points` (and `score`) by the equal-area cylinder map (cylinder_initial_map.h),
// blended with the conformal one only as far as needed for no fold by the exact sign, if that is
// centred and at most kStartBelow of the area distortion; returns whether it did. Why: 500 to 800
// sweeps of the adaptive relaxation, each moving a vertex a fraction of an edge, cannot undo a
// squeeze of e^-40 (capsule of aspect 50: 41.8 -> 34.1, 18 %); the equal-area latitudes undo it
// along the axis between the punctures at once (41.8 -> 0.45), and the relaxation goes on from
// there. Where the mesh is not close to symmetric about that axis the latitudes fold triangles
// (cow, horse_quad, decimated-knight: 9 to 52 even blended half way), and nothing changes.
// `progress` gets the factorization's progress (it may throw to cancel).
bool equal_area_start(const SphereProblem& problem, WeightScheme weights, ThreadPool& pool,
                      std::vector<Eigen::Vector3d>& points, SphereMapScore& score,
                      const ProgressSpan& progress) {
    std::optional<CylinderCoordinates> coordinates;
    try {
        coordinates = cylinder_coordinates(problem, weights, progress);
    } catch (const Error& e) {
        // A singular system is no start, not a failure of a map already found; a cancel is.
        if (e.code() != ErrorCode::kSolverFailed) throw;
    }
    if (!coordinates) return false;
    const ProgressSpan beat = progress.part(1.0, 1.0);
    for (double share : {1.0, 0.75, 0.5, 0.25}) {
        std::vector<Eigen::Vector3d> start =
            equal_area_cylinder_map(problem, *coordinates, share, beat);
        if (count_folds(problem.mesh, start, beat).folded > 0) continue;
        mobius_centre(problem, start, pool, 1e-4, 100, beat);
        const SphereMapScore candidate = score_sphere_map(problem, start, pool, beat);
        // The centring may have turned a triangle over by the exact sign, which the rounded
        // fold test of the score does not see.
        if (count_folds(problem.mesh, start, beat).folded > 0 || candidate.folded > 0 ||
            candidate.centre > kCentredEnough ||
            !(candidate.area_log <= kStartBelow * score.area_log)) {
            return false;
        }
        points.swap(start);
        score = candidate;
        return true;
    }
    return false;
}

}  // namespace

SphereMap parameterize_sphere(const TriangleMesh& input, const Settings& settings,
                              const Progress& progress, PhaseTimes& times) {
    {
        PhaseTimer timer(Phase::kValidate, progress, times);
        check_indices_in_range(input, timer.span(0.0, 0.2));
        check_no_repeated_vertices(input, timer.span(0.2, 0.4));
        check_no_isolated_vertices(input, timer.span(0.4, 0.6));
        check_no_zero_area_triangles(input, timer.span(0.6, 1.0));
        timer.finish();
    }

    // Checked on the input, so that messages name its vertices; then everything runs on the
    // vertices in Morton order (vertex_order.h) and the points go back to input order at the end.
    PhaseTimer topology_timer(Phase::kTopology, progress, times);
    check_closed_genus_zero(input, build_halfedges(input, topology_timer.span(0.0, 0.2)),
                            topology_timer.span(0.2, 0.3));
    const std::vector<int32_t> order =
        morton_vertex_order(input.positions, topology_timer.span(0.3, 0.45));
    const TriangleMesh mesh = reorder_vertices(input, order, topology_timer.span(0.45, 0.5));
    const SphereProblem problem = make_sphere_problem(
        mesh, build_halfedges(mesh, topology_timer.span(0.5, 0.7)), topology_timer.span(0.7, 1.0));
    topology_timer.finish();

    const bool literal = settings.sphere_method == SphereMethod::kLiteral;
    // The thread count changes nothing in the output (thread_pool.h); a few thousand vertices
    // per thread keep the synchronisation between colours cheap.
    ThreadPool pool(literal ? 1 : choose_thread_count(settings.threads, mesh.vertex_count(), 4096));
    RelaxationOptions options;
    options.literal = literal;
    options.damping = settings.sphere_damping;
    options.tolerance = settings.sphere_tolerance;
    options.max_sweeps = settings.sphere_max_sweeps > 0 ? settings.sphere_max_sweeps
                         : literal                      ? kLiteralMaxSweeps
                                                        : kRobustMaxSweeps;

    SphereMap map;
    std::vector<Eigen::Vector3d> points;
    std::vector<double> base_weights;
    {
        // Progress: the base weights and the initial map are the first half of the phase, its
        // relaxation the second.
        PhaseTimer timer(Phase::kInitialMap, progress, times);
        base_weights =
            laplacian_weights(mesh, problem.adjacency, settings.weights, timer.span(0.0, 0.05));
        timer.span(0.05, 0.05)
            .in_runs(static_cast<int64_t>(base_weights.size()), [&](int64_t begin, int64_t end) {
                for (int64_t s = begin; s < end; ++s) map.negative_weights += base_weights[s] < 0.0;
            });
        if (literal) {
            points = gauss_map(mesh);
        } else {
            points =
                stereographic_initial_map(problem, settings.weights, pool, timer.span(0.05, 0.5));
        }
        map.relaxation_sweeps +=
            relax_on_sphere(problem, base_weights, points, options, pool, timer.span(0.5, 1.0))
                .sweeps;
        timer.finish();
    }

    PhaseTimer adapt_timer(Phase::kAdapt, progress, times);
    // Progress: the adaptive relaxations, then the unfold when there is one.
    const bool unfold = settings.sphere_uv == SphereUv::kOctahedral;
    const ProgressSpan relaxations = adapt_timer.span(0.0, unfold ? 0.8 : 1.0);
    if (!literal && settings.sphere_max_sweeps == 0) options.max_sweeps = kRobustAdaptiveMaxSweeps;
    if (settings.monitor != Monitor::kNone) {
        // Iterations as in the plane (RAPS_PARAM_ITERATIONS, RAPS_PARAM_ITERATION_MODE). The
        // robust method reaches each iteration's exponent alpha by continuation: alpha_steps
        // relaxations, each multiplying the weights by e^(alpha / steps) measured on the map
        // the previous one left. A step that takes a fold-free, centred map to a folded or
        // off-centre one is taken back and tried again at half its exponent, at most
        // kStepRetries times per iteration, and with half the sweeps (so that all steps taken
        // together still get the sweeps of one iteration). Measured on a capsule of aspect 30:
        // both steps of alpha / 2 drifted off-centre (0.11 and 0.63), which left only the
        // initial map to return (docs/sphere-status.md).
        const int steps = literal ? 1 : settings.sphere_alpha_steps;
        const bool by_area = settings.monitor == Monitor::kArea;
        std::vector<double> weights;  // 270 MB at 5.65M triangles: copied in runs
        copy_in_runs(weights, base_weights, relaxations.part(0.0, 0.0));
        std::vector<Eigen::Vector3d> best, before;  // robust: the best map so far, the last one
        SphereMapScore best_score;
        bool acceptable = false;  // robust: whether the current map is fold-free and centred
        SphereMapScore initial_score;
        bool start_tried = false;
        if (!literal) {
            copy_in_runs(best, points, relaxations.part(0.0, 0.0));
            best_score = score_sphere_map(problem, points, pool, relaxations.part(0.0, 0.0));
            initial_score = best_score;
            acceptable = best_score.folded == 0 && best_score.centre <= kCentredEnough;
            if (by_area && acceptable && best_score.area_log > kSqueezedArea) {
                start_tried = true;
                if (equal_area_start(problem, settings.weights, pool, points, best_score,
                                     relaxations.part(0.0, 0.0))) {
                    best = points;
                }
            }
        }
        double reported = 0.0;
        for (int iteration = 0; iteration < settings.iterations; ++iteration) {
            if (settings.iteration_mode == IterationMode::kReapply) weights = base_weights;
            double reached = 0.0, step = 1.0 / steps;  // fractions of alpha
            int retries = literal ? 0 : kStepRetries;
            while (reached < 1.0 - 1e-9) {
                step = std::min(step, 1.0 - reached);
                // The per-edge arrays (270 MB each at 5.65M triangles) are given back in runs
                // (release_in_runs.h): freed in one go, each was up to 85 ms without a call.
                const ProgressSpan beat = relaxations.part(reported, reported);
                std::vector<double> monitor = error_monitor(
                    mesh, problem.adjacency, SphericalMapGeometry(points), settings.monitor, beat);
                std::vector<double> trial = adaptive_weights(problem.adjacency, weights, monitor,
                                                             settings.alpha * step, beat);
                release_in_runs(monitor, beat);
                if (!literal) copy_in_runs(before, points, relaxations.part(reported, reported));
                RelaxationOptions step_options = options;
                step_options.max_sweeps = std::max<int64_t>(
                    1, std::llround(static_cast<double>(options.max_sweeps) * step * steps));
                // A retried step does not go back: the phase's progress never falls.
                const double from = (iteration + reached) / settings.iterations;
                const double to = (iteration + reached + step) / settings.iterations;
                map.relaxation_sweeps += relax_on_sphere(problem, trial, points, step_options, pool,
                                                         relaxations.part(from, to))
                                             .sweeps;
                reported = std::max(reported, to);
                ++map.adaptive_solves;
                if (!literal) {
                    const SphereMapScore score = score_sphere_map(
                        problem, points, pool, relaxations.part(reported, reported));
                    const bool fine = score.folded == 0 && score.centre <= kCentredEnough;
                    if (acceptable && !fine && retries > 0) {
                        points.swap(before);
                        step *= 0.5;
                        --retries;
                        release_in_runs(trial, beat);
                        continue;
                    }
                    acceptable = fine;
                    if (better_sphere_map(score, best_score, by_area)) {
                        copy_in_runs(best, points, relaxations.part(reported, reported));
                        best_score = score;
                    }
                }
                weights.swap(trial);
                release_in_runs(trial, beat);
                reached += step;
            }
        }
        // Where the continuation ends less than 40 % below the initial map, the equal-area map
        // competes as a result. Measured: bunny subdivided to 446K triangles, whose relaxations
        // stop far from their fixed point (200 sweeps each), 1.645 -> 1.204 (27 %) adapted and
        // 0.505 equal-area (docs/sphere-status.md); the continuation from that start only rose
        // from it.
        if (!literal && by_area && !start_tried && initial_score.folded == 0 &&
            initial_score.centre <= kCentredEnough &&
            !(best_score.area_log <= kStartBelow * initial_score.area_log)) {
            std::vector<Eigen::Vector3d> candidate;
            SphereMapScore candidate_score = initial_score;
            if (equal_area_start(problem, settings.weights, pool, candidate, candidate_score,
                                 relaxations.part(1.0, 1.0)) &&
                better_sphere_map(candidate_score, best_score, by_area)) {
                best.swap(candidate);
                best_score = candidate_score;
            }
            release_in_runs(candidate, relaxations.part(1.0, 1.0));
        }
        if (!literal) points.swap(best);
        const ProgressSpan beat = relaxations.part(1.0, 1.0);
        release_in_runs(weights, beat);
        release_in_runs(best, beat);
        release_in_runs(before, beat);
    }
    const ProgressSpan beat = relaxations.part(1.0, 1.0);
    release_in_runs(base_weights, beat);
    assign_in_runs(map.points, points.size(), Eigen::Vector3d::Zero().eval(), beat);
    for (size_t k = 0; k < order.size(); ++k) {
        beat.at(static_cast<int64_t>(k), static_cast<int64_t>(order.size()));
        map.points[order[k]] = points[k];
    }
    release_in_runs(points, beat);
    relaxations.report(1.0);
    // The literal method returns what algorithm 7.1 gives, folds and all (docs/bench-method.md,
    // "algorithm 7.1 as written", counts them); the robust one returns a bijection or nothing.
    if (!literal) require_bijective_sphere_map(input, map.points, relaxations.part(1.0, 1.0));
    if (unfold) map.unfold = octahedral_unfold(input, map.points, adapt_timer.span(0.8, 1.0));
    adapt_timer.finish();
    map.threads_used = pool.threads_used();
    return map;
}

}  // namespace raps
