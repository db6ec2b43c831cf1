// Paper section 6.4: the adaptive weights W_ij = w_ij * e_ij^alpha, where w_ij are the weights of
// the previous solve (or the base weights) and e_ij an error monitor measured on its map. Keeping
// w_ij in the product is the paper's conformality term: the adapted map inherits the smoothness
// of the quasi-conformal one instead of following the raw monitor.
#pragma once

#include <vector>

#include "core/progress.h"
#include "mesh/mesh_topology.h"

namespace raps {

// Returns W_ij = w_ij * e_ij^alpha for every slot, each row rescaled to sum 1 (which leaves the
// solution of eq. (1) unchanged) so that weights accumulated over many iterations stay within
// floating-point range. e^alpha is evaluated as exp(alpha log e) with the exponent clamped to
// +-600, so no alpha under- or overflows to a zero or infinite weight.
std::vector<double> adaptive_weights(const VertexAdjacency& adjacency,
                                     const std::vector<double>& weights,
                                     const std::vector<double>& monitor, double alpha,
                                     const ProgressSpan& progress = {});

}  // namespace raps
