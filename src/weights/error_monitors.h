// Paper section 6: error monitors e_ij measured on a map, one per directed edge i -> j (a slot of
// VertexAdjacency), strictly positive and increasing in the distortion they measure. The map is
// seen through MapGeometry, so the same monitors serve the disk (uv areas, lengths, angles) and
// the sphere (section 7: exact spherical triangle areas, great-circle arc lengths, the angles
// between great-circle arcs).
//
// Decisions the paper leaves open, and why:
// - Normalisation. Area and length ratios are divided by their global value (total uv area over
//   total 3D area; total uv edge length over total 3D edge length), so that e = 1 where the map
//   is exactly as large as it is on average. The Laplace system is homogeneous of degree one in
//   the weights, so a global factor changes nothing in exact arithmetic; it keeps e^alpha near
//   1 instead of under- or overflowing at large alpha. Angle ratios are scale-free and left as
//   they are.
// - Boundary edges. An edge with one triangle takes that triangle's value instead of the
//   average of two. Such an edge joins two boundary vertices, whose positions are fixed, so its
//   weight never enters a system with a fixed boundary.
// - Positivity. A triangle that is flipped or collapsed in the map has no meaningful ratio; its
//   contribution is floored at kMonitorFloor, the smallest monitor value, which gives it the
//   weakest springs so that the next solve expands it.
#pragma once

#include <vector>

#include "core/progress.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"
#include "metrics/map_geometry.h"

namespace raps {

constexpr double kMonitorFloor = 1e-12;

// e_ij for every slot of `adjacency`, measured on the map `map` (whose vertices are the mesh's).
// area (6.1):   e_ijk = map area / 3D area of triangle ijk; e_ij = mean over the triangles at ij.
// length (6.2): e_ij = |u_i - u_j| / |x_i - x_j| (in the map's own metric).
// angle (6.3):  e_ijk = map angle / 3D angle at corner i of triangle ijk; e_ij = mean over the
//               triangles at ij, both measured at i (so e_ij != e_ji).
std::vector<double> error_monitor(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                                  const MapGeometry& map, Monitor monitor,
                                  const ProgressSpan& progress = {});

}  // namespace raps
