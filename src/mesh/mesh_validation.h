// Checks on the input that need no adjacency. Each throws raps::Error naming the first
// offending element; the domain pipelines pick the checks they need.
#pragma once

#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

// Refuses an index outside [0, vertex count).
void check_indices_in_range(const TriangleMesh& mesh, const ProgressSpan& progress = {});

// Refuses a triangle that names one vertex twice.
void check_no_repeated_vertices(const TriangleMesh& mesh, const ProgressSpan& progress = {});

// Refuses a triangle whose area is below 1e-12 times the mean triangle area (the threshold the
// distortion metrics use to call a 3D triangle degenerate): its angles, and so its mean value and
// cotangent weights, are undefined.
void check_no_zero_area_triangles(const TriangleMesh& mesh, const ProgressSpan& progress = {});

// Refuses a vertex that no triangle uses: a map could give it any position.
void check_no_isolated_vertices(const TriangleMesh& mesh, const ProgressSpan& progress = {});

// Area of a 3D triangle.
double triangle_area(const TriangleMesh& mesh, int32_t triangle);

}  // namespace raps
