// The weights w_ij of the discrete Laplacian L(u_i) = sum_j w_ij (u_i - u_j) (paper eq. 1), one
// per directed edge i -> j (a slot of VertexAdjacency). These are the "base" or quasi-conformal
// weights: the initial map solves with them, and the adaptive step multiplies them by the error
// monitor (section 6.4).
#pragma once

#include <vector>

#include "core/progress.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"

namespace raps {

// Mean value (Floater 2003): w_ij = (tan(d_ij / 2) + tan(g_ij / 2)) / |x_i - x_j|, d and g the
// angles at i of the two triangles at edge ij. Positive; not symmetric.
// Cotangent (Pinkall & Polthier 1993): w_ij = (cot a_ij + cot b_ij) / 2, the angles opposite the
// edge. Symmetric; negative where the opposite angles sum to more than pi.
// Uniform (Tutte 1963): w_ij = 1.
// Each triangle contributes its part at each corner, so boundary edges get one triangle's part.
std::vector<double> laplacian_weights(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                                      WeightScheme scheme, const ProgressSpan& progress = {});

}  // namespace raps
