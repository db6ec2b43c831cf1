// Paper section 7, algorithm 7.1 step 4: relaxation on the sphere. Each vertex moves by the
// tangential part of the Laplacian, u_i += lambda L_par(u_i), and is projected back onto the
// sphere; sweeps repeat until the map stops moving. With the base weights this gives the
// initial quasi-conformal map, with the adaptive weights W = w e^alpha (section 6.4) the adapted
// one.
//
// Readings of the paper's text:
// - L(u_i) is taken as the move towards the weighted mean of the ring, sum_j W_ij (u_j - u_i)
//   / sum_j W_ij. Eq. (1)'s sign, u_i - u_j, would push each vertex away from its ring, and
//   without the division lambda in (0, 1] would not be a fraction of anything (mean value weights
//   scale like 1 / edge length).
// - "Until convergence": until the root mean square of the vertices' moves in one sweep, in
//   units of lambda omega times the mean edge length of the sphere, falls below a tolerance.
//   Moves are measured after removing the rotation that best aligns the map with the one before
//   the sweep (Kabsch): a rotation is no change of the map, and the robust relaxation's fixed
//   point keeps turning (measured on bunny: 2.5e-4 radians per sweep, for ever, while the map
//   modulo rotation settled to 1e-9), because a slight drift towards collapse composed with the
//   centring that undoes it has a rotation part.
//
// Literal (RAPS_SPHERE_LITERAL): exactly that, Gauss-Seidel in vertex order on one thread.
// Robust (RAPS_SPHERE_ROBUST) adds, each for a case that needed it (docs/method.md, "What the
// robust method adds"; the literal method's folds are counted in docs/bench-method.md):
// - Fold rejection with a plane floor (sphere_problem.h). A move that would turn one of the
//   vertex's triangles over, or leave one whose plane passes closer to the centre than
//   kPlaneFloor (unless it makes that triangle no worse), is halved, then quartered, and
//   otherwise not made. Starting from a bijection, every sweep
//   ends in a bijection. Needed: the fixed points themselves fold (issue: the converged mean
//   value map on 7/7 meshes; here, with the mean value weights, spot.obj pushes 35 vertices into
//   folds every sweep, for ever).
// - Moebius centring after every sweep (mobius_centring.h): otherwise the relaxation collapses
//   every mesh to a point.
// - Gauss-Seidel over a fixed vertex colouring: the vertices of one colour share no edge, so they
//   move in parallel, on any number of threads, with the same result bit for bit; and each
//   vertex's fold check stays valid while the others of its colour move.
// - Over-relaxation: the move is lambda omega L_par with omega = kOverRelaxation.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "parallel/thread_pool.h"
#include "sphere/sphere_problem.h"

namespace raps {

// Measured on bunny with uniform weights, every relaxation to convergence, when omega was chosen
// (no bench-report table repeats it): the initial relaxation took 312 sweeps at omega 1.0, 144 at
// 1.5, 80 at 1.8; all five relaxations 2,440, 984 and 12,080 - at 1.8 the adaptive ones oscillate
// until their sweep limit.
constexpr double kOverRelaxation = 1.5;

struct RelaxationOptions {
    bool literal = false;     // vertex order, one thread, no fold check, no centring, omega 1
    double damping = 1.0;     // lambda in (0, 1]
    double tolerance = 1e-4;  // RMS move per sweep / (lambda omega mean edge) at which to stop
    int64_t max_sweeps = 100;
};

struct RelaxationReport {
    int64_t sweeps = 0;
    bool converged = false;
    double residual = 0;  // RMS move of the last sweep, in the units of the tolerance
    int64_t refused = 0;  // moves not made (fold rejection), over all sweeps
};

// Relaxes `u` (unit vectors, one per vertex) with `weights` (one per adjacency slot, rows with a
// positive sum). `progress` gets the fraction done at least every 16 sweeps and every 1%, and
// the same fraction again after every colour, every kItemsPerReport vertices moved and inside
// the passes between sweeps (it may throw to cancel).
RelaxationReport relax_on_sphere(const SphereProblem& problem, const std::vector<double>& weights,
                                 std::vector<Eigen::Vector3d>& u, const RelaxationOptions& options,
                                 ThreadPool& pool, const ProgressSpan& progress);

}  // namespace raps
