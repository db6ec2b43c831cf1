// Paper section 3: the boundary loop is fixed to a convex polygon, which (with positive weights)
// makes the solution of the Laplace system a bijection (Tutte; Floater 2003).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/settings.h"
#include "core/triangle_mesh.h"

namespace raps {

// UV positions for the loop's vertices (in loop order), spaced by the chord length of the 3D
// boundary polygon, counter-clockwise: the circle of radius 0.5 centred at (0.5, 0.5), or the
// unit square with its corners at the loop vertices nearest to each quarter of the length.
std::vector<Eigen::Vector2d> convex_boundary(const TriangleMesh& mesh,
                                             const std::vector<int32_t>& loop, BoundaryShape shape);

}  // namespace raps
