#include "bench_support.h"

#include <algorithm>

#include "mesh_io.h"

namespace raps_bench {

TriangleMesh load_triangles(const std::string& file, int subdivisions) {
    const raps_samples::PolygonMesh mesh = raps_samples::read_mesh(file);
    TriangleMesh out{mesh.positions, mesh.triangles()};
    for (int s = 0; s < subdivisions; ++s)
        raps_samples::subdivide_midpoint(out.positions, out.triangles);
    return out;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace raps_bench
