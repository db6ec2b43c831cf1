#include "core/memory_estimate.h"

#include <algorithm>
#include <cmath>

#include "core/portable_math.h"
#include "mesh/mesh_validation.h"

namespace raps {

// The model: peak = kFixed + triangles * (a + b * log2(triangles)) per domain, plus, for the
// atlas, bytes per texel of its resolution squared. The log term follows the sparse factor's
// fill, which grows as n log n for meshes (nested dissection). The numbers were set above the
// highest peaks measured by bench/memory_bench.cpp (raps-bench-memory --subdivide 3, default
// settings, Debian 12, glibc malloc): the peak resident set one raps_parameterize call added,
// over the shared meshes subdivided 1-to-4 zero to three times. Bytes per triangle measured then:
//   disk   (alligator, camelhead, face; 6K to 3.3M triangles): 483 to 860
//   sphere (spot, bunny; 5.9K to 446K): 681 to 869
//   atlas  (fandisk, bunny; 7K to 829K): 531 to 2342 (fandisk's many charts)
// and the atlas's texel grids 1.2 to 1.5 bytes per texel (at 4096 and 16384 texels). Measured
// again 2026-12-07 (`/usr/bin/time raps-param --atlas MESH --resolution 8192`, peak resident
// set): the packer rasterises its 32 largest charts in 24 orientations at the final density,
// and a resolution's texels cost cow 10.7 bytes each, lion 8.3, fandisk 7.1 (10.5 for cow at
// 4096); at a density (`--texels-per-unit 1e4` and `3e4 --max-size 16384`) cow's peak was 2.2
// and 1.9 bytes per texel of its charts' area, plus the open pages' cells.
// docs/bench-memory.md (bench-report: --subdivide 2, atlas resolution 1024) sets the current
// peaks beside the estimate (its sphere rows reach 892 bytes per triangle, above the range
// measured then); that table is the one to check after changing anything here.
namespace {

constexpr double kFixed = 4.0 * 1048576.0;  // thread stacks, allocator arenas, small tables

struct PerTriangle {
    double a, b;
};

constexpr PerTriangle kDisk{510.0, 25.0};
constexpr PerTriangle kSphere{590.0, 25.0};
constexpr PerTriangle kAtlas{2000.0, 40.0};
constexpr double kAtlasBytesPerTexel = 12.0;        // of the square at a resolution
constexpr double kDensityBytesPerChartTexel = 2.5;  // of the charts' area at a density
constexpr double kOpenPages = 8.0;                  // page_packing.cpp, a bit per cell each

double surface_area(const TriangleMesh& mesh) {
    double area = 0;
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) area += triangle_area(mesh, t);
    return area;
}

}  // namespace

double estimated_peak_bytes(const TriangleMesh& mesh, const Settings& settings) {
    const double triangles = static_cast<double>(mesh.triangles.size());
    const double log_triangles = portable::log2(std::max(triangles, 2.0));
    const PerTriangle per = settings.domain == Domain::kSphere  ? kSphere
                            : settings.domain == Domain::kAtlas ? kAtlas
                                                                : kDisk;
    double bytes = kFixed + triangles * (per.a + per.b * log_triangles);
    if (settings.domain == Domain::kAtlas && settings.atlas_texels_per_unit > 0) {
        const double density = settings.atlas_texels_per_unit;
        const double page =
            static_cast<double>(settings.atlas_max_width) * settings.atlas_max_height;
        bytes += kDensityBytesPerChartTexel * surface_area(mesh) * density * density +
                 kOpenPages * page / 8.0;
    } else if (settings.domain == Domain::kAtlas) {
        const double side = static_cast<double>(settings.atlas_resolution);
        bytes += kAtlasBytesPerTexel * side * side;
    }
    return bytes;
}

}  // namespace raps
