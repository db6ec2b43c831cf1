// The sign of det[a, b, c] of three points given as doubles, exactly (Shewchuk, "Adaptive
// precision floating-point arithmetic and fast robust geometric predicates", Discrete and
// Computational Geometry 18, 1997): a filter on the rounded determinant, and floating-point
// expansions where the filter cannot decide. The final check of a spherical map
// (sphere_map_check.h) uses it, so that "fold-free" means det > 0 for the points as stored,
// whatever a caller's own rounding of the determinant says about a triangle of 1e-17.
#pragma once

#include <Eigen/Core>

namespace raps {

// +1, 0 or -1: the sign of the exact determinant of the rows a, b, c.
int exact_orientation_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c);

}  // namespace raps
