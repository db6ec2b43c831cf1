// A second initial spherical map for meshes whose long parts the one-puncture map cannot resolve:
// two punctures, a periodic Tutte embedding of the annulus between them into a straight
// cylinder, and the lift w = e^(H h + i theta): the exponential coordinates of the cylinder
// between the two poles, done last, in the lift (Choi, Lam and Lui 2015 correct the pole region of
// their one-puncture map with a second projection from the other pole; here the second pole is a
// puncture of its own):
//
//  1. Punctures A and B at the ends of an approximate longest geodesic (double-sweep Dijkstra
//     over 3D edge lengths). Their stars are removed; the rings bound an annulus.
//  2. A height h: the Laplace system of paper eq. (1) with the base weights, h = 0 on A's ring
//     and 1 on B's ring. An angle theta: the same system with a jump of 2 pi across a cut (a
//     fewest-edges path from A to B), the rings at angles proportional to their 3D corner
//     angles, and B's ring turned by the twist of least weighted energy; both rings are straight
//     lines of the cylinder's universal cover, which is convex, so with positive weights the
//     embedding has no fold (Tutte's theorem for the periodic graph; Gortler, Gotsman and
//     Thurston 2006 for the torus).
//  3. The height scaled to the conformal modulus, H = sqrt(E(theta) / E(h)) in the weights'
//     energy, shifted so that the 3D-area-weighted centre of mass has no height component, and
//     lifted: A at the south pole, B at the north pole, each ring at e^(-+H c) of the sphere.
//
// Why (docs/sphere-status.md, issue 18): a conformal map squeezes a limb of length L and radius r
// by about e^(-L / r). The one-puncture map computes that squeeze in the plane, where a solve
// has an absolute error of 1e-16 of the disk: on a capsule of aspect 40 the far end, which
// belongs 1e-34 from the plane's origin, comes out as a cluster of noise around a point about
// 1e-17 off it, and 679 planar triangles fold. Here both ends of the longest part are the
// punctures, the squeeze is in the exponential, and a point near either pole keeps the relative
// precision of its height and angle: x and y of a unit vector near (0, 0, +-1) are resolved
// relative to their size.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/settings.h"
#include "sphere/sphere_problem.h"

namespace raps {

// The cylinder between the punctures: height h in [0, 1] (0 on the south puncture's ring, 1 on the
// north one's) and angle theta per vertex (as its cosine and sine), and the modulus H.
struct CylinderCoordinates {
    int32_t south = -1, north = -1;  // the punctures
    std::vector<double> height, cosine, sine;
    double modulus = 0;
};

// None when the mesh has no two vertices 4 edges apart (their stars would touch).
std::optional<CylinderCoordinates> cylinder_coordinates(const SphereProblem& problem,
                                                        WeightScheme weights,
                                                        const ProgressSpan& progress = {});

// The conformal lift w = e^(H (h - c) + i theta), c balancing the centre of mass along the axis
// (not sideways: that would move the squeezed ends off the poles, where a unit vector resolves
// 1e-16 absolute). Reports to `beat` as it goes, as the next one does.
std::vector<Eigen::Vector3d> conformal_cylinder_map(const SphereProblem& problem,
                                                    const CylinderCoordinates& cylinder,
                                                    const ProgressSpan& beat = {});

// The equal-area lift: the same angles, and the latitude at which the sphere's share below a
// point equals the mesh's 3D share below its height (z = 2 F(h) - 1; by Archimedes' theorem a
// band's area on the sphere is proportional to its height: Lambert's cylindrical equal-area
// projection). Height is monotone along the cylinder, so this keeps every triangle's orientation
// where F is close to linear across it; a start for the area monitor (sphere_parameterization.cpp).
// With share < 1 the latitude's share is blended with the conformal lift's: (1 - share) of it
// and `share` of the equal-area one (still monotone in h).
std::vector<Eigen::Vector3d> equal_area_cylinder_map(const SphereProblem& problem,
                                                     const CylinderCoordinates& cylinder,
                                                     double share, const ProgressSpan& beat = {});

}  // namespace raps
