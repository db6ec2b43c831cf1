// The robust initial spherical map, bijective by construction, instead of algorithm 7.1's Gauss
// map (after Choi, Lam and Lui, "Fast spherical quasiconformal parameterization of genus-0
// closed surfaces", 2015: puncture, flatten with one sparse solve, lift back):
//
//  1. Remove the star of one vertex, the pole. What remains is a topological disk whose
//     boundary is the pole's ring.
//  2. Put the ring on the unit circle (angles proportional to the 3D corner angles at the pole)
//     and solve the Laplace system of paper eq. (1) with positive weights (the base weights;
//     mean value in place of cotangent weights, which may be negative): by Tutte's and
//     Floater's theorems the disk is embedded without a fold.
//  3. Lift by inverse stereographic projection from the north pole, with the pole vertex at the
//     north pole itself: a conformal bijection of the plane onto the sphere minus the pole, so
//     the lifted map is quasi-conformal like the paper's initial map. The scale gives the pole's
//     star the share of the sphere that it has of the 3D area.
//  4. Moebius-centre it (mobius_centring.h), first in the plane, composing the boosts into one
//     complex Moebius matrix applied to the planar points before the lift
//     (mobius_centred_lift), then on the sphere for what rounding leaves. Measured on cow and
//     horse_quad subdivided to 88K and 77K triangles: centred on the sphere alone, their maps
//     folded 243 and 442 triangles and the centring stalled 0.99 from the origin; centred in the
//     plane first, neither folds and both end centred (docs/sphere-status.md).
//  5. If the planar map has a fold (rounding: the exact solution has none), the two-puncture
//     cylinder map (cylinder_initial_map.h) instead, where it folds fewer spherical triangles.
//     Measured: capsules of aspect 40 and 50 and a dumbbell with a neck of 0.02 had 679, 2,754
//     and 1,650 planar folds and were refused; their cylinder maps have none
//     (docs/sphere-status.md). Every mesh without a planar fold keeps the map of step 4.
//
// Measured, why: the Gauss map of a mesh that is not star-shaped about its centroid starts with
// folds (issue: hundreds to thousands), and relaxation cannot be trusted to undo them. Why a
// puncture at a vertex rather than a removed triangle (as Choi et al. do): the ring is a convex
// polygon around the origin, so the pole's star is positively oriented on the sphere at any
// scale, where a removed triangle's own orientation bounds the scale from the other side.
// Stereographic projection keeps circles, not straight edges, so a nearly flat planar triangle
// whose circumcircle it lifts past a great circle can still come out with det[a, b, c] <= 0:
// measured, 0 to 4 such triangles on the shared meshes, which the centring and the relaxation
// that follow turn back (they never fold a triangle, and may unfold one).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/settings.h"
#include "parallel/thread_pool.h"
#include "sphere/sphere_problem.h"

namespace raps {

// Angles on the unit circle for the ring of `pole` (vertex_ring order, the first at 0),
// counter-clockwise, proportional to the 3D corner angles at the pole; equal angles if that would
// give one gap of more than 0.9 pi (the star triangle would be nearly flat on the sphere).
std::vector<double> pole_ring_angles(const TriangleMesh& mesh, int32_t pole,
                                     const std::vector<int32_t>& ring);

// One unit vector per vertex. `progress` receives the fraction of the sparse factorization done
// (it may throw to cancel).
std::vector<Eigen::Vector3d> stereographic_initial_map(const SphereProblem& problem,
                                                       WeightScheme weights, ThreadPool& pool,
                                                       const ProgressSpan& progress);

}  // namespace raps
