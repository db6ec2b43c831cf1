// Paper section 7, algorithm 7.1 steps 1-3: the literal initial spherical map. Translate the
// vertices so that their plain mean is the origin and project each onto the unit sphere. It is a
// bijection only for meshes that are star-shaped around their mean; measured (issue), a mesh that
// is not starts with hundreds to thousands of folded triangles. Used by RAPS_SPHERE_LITERAL.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/triangle_mesh.h"

namespace raps {

// One unit vector per vertex. A vertex at the mean itself (no direction) gets +z.
std::vector<Eigen::Vector3d> gauss_map(const TriangleMesh& mesh);

}  // namespace raps
