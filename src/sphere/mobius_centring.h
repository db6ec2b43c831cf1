// Moebius centring of a spherical map (Gu and Yau 2002; the normalisation of Gu, Wang, Chan,
// Thompson and Yau's spherical conformal maps). Conformal maps of the sphere are only defined up
// to the Moebius group; the three "boost" directions of that group cost a conformal energy
// nothing, and the tangential-Laplacian relaxation of paper section 7 drifts along them until
// every vertex sits in one point. Measured (issue, 7 genus-0 meshes): taken literally, the
// relaxation collapsed every mesh before it "converged". Centring fixes the boosts: it applies
// the Moebius map T_a, a inside the unit ball, which moves the 3D-area-weighted centre of mass
// of the points towards the origin.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "parallel/thread_pool.h"
#include "sphere/sphere_problem.h"

namespace raps {

// T_a(u) = ((1 - |a|^2)(u - a) - |u - a|^2 a) / |u - a|^2 for a unit vector u: a conformal
// bijection of the sphere that fixes +-a/|a| and spreads out the points near a/|a|.
Eigen::Vector3d mobius_boost(const Eigen::Vector3d& u, const Eigen::Vector3d& a);

// The centre of mass sum_i mass_i u_i (bit-identical for any thread count). This and the step
// below report to `beat` (its start fraction) as they go.
Eigen::Vector3d centre_of_mass(const SphereProblem& problem, const std::vector<Eigen::Vector3d>& u,
                               ThreadPool& pool, const ProgressSpan& beat = {});

// One centring step: T_a with a = 3/4 of the centre of mass (to first order T_a moves a uniform
// distribution's centre by -4/3 a), at most 0.9 long. A Moebius map keeps circles, not the sign
// of det[a, b, c]: a nearly flat triangle whose circumcircle it blows up past a great circle
// turns over. So the step is tried at 1, 1/4, 1/16 and 1/64 of its length and taken only if it
// turns no triangle over, else skipped. (Not a floor of its own: the relaxation's plane floor,
// sphere_problem.h, keeps every circumcircle it moves well inside a hemisphere, which is what
// lets the smaller steps through.) Returns the length of the centre of mass before the step, and
// whether the step was taken in `*moved` (if not NULL). `scratch` is a buffer.
double centring_step(const SphereProblem& problem, std::vector<Eigen::Vector3d>& u,
                     std::vector<Eigen::Vector3d>& scratch, ThreadPool& pool, bool* moved,
                     const ProgressSpan& beat = {});

// Centring steps until the centre of mass is shorter than `tolerance`, a step is refused or
// `max_steps` were taken; returns the steps taken.
// `progress` gets the share of max_steps taken after each step.
int mobius_centre(const SphereProblem& problem, std::vector<Eigen::Vector3d>& u, ThreadPool& pool,
                  double tolerance, int max_steps, const ProgressSpan& progress = {});

// The same centring done in the plane before the lift, for a map given as planar points (the
// stereographic coordinates of its sphere points, projected from the north pole) and one vertex
// at infinity (`pole`, or -1 for none). Each step is the boost of centring_step written as a
// complex Moebius matrix (a rotation taking the centre of mass's direction to the north pole, a
// scaling, the rotation back); the steps are composed, and the points are lifted from the
// original planar points through the composed matrix, never through the previous lift. Why:
// floating point resolves a point near the plane's origin relative to its distance from it, and
// the lift keeps that near the sphere's poles, where a boost applied on the sphere resolves only
// 1e-16 absolute. A capsule punctured at one end puts the other end at the origin and the body
// on a circle of radius e^-aspect around it; centring it is a scaling, exact in the plane,
// which on the sphere blew up the rounding of the squeezed end into folds (docs/sphere-status.md).
// Takes steps until the centre of mass is shorter than `tolerance` or `max_steps` were taken;
// returns the lifted points. `progress` gets the share of max_steps taken after each step.
std::vector<Eigen::Vector3d> mobius_centred_lift(const SphereProblem& problem,
                                                 const std::vector<Eigen::Vector2d>& plane,
                                                 int32_t pole, double scale, ThreadPool& pool,
                                                 double tolerance, int max_steps,
                                                 const ProgressSpan& progress = {});

}  // namespace raps
