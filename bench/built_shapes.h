// Closed genus-0 shapes that raps-bench --sphere builds itself (issue 18's hard cases, as
// tests/test_sphere_hard.c builds them): surfaces of revolution about the z axis with rings
// spaced by the circumferential edge length, every other ring turned by half a sector.
#pragma once

#include <cstdint>
#include <vector>

namespace raps_bench {

// A capsule of radius 1 and length 2 * aspect.
void build_capsule(double aspect, int sectors, std::vector<double>& positions,
                   std::vector<uint32_t>& triangles);

// Two unit spheres 3 apart joined by a neck of radius `neck`.
void build_dumbbell(double neck, int sectors, std::vector<double>& positions,
                    std::vector<uint32_t>& triangles);

}  // namespace raps_bench
