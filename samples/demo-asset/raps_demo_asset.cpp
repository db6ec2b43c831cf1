// raps-demo-asset: writes the demo asset the README's quick start bakes texture coordinates
// into, so the project needs no downloaded data to show what it does.
//
//   raps-demo-asset OUT.obj [--resolution N]
//
// The asset is a "fountain": a dome of a disk-like patch whose centre rises into a tall spout.
// Conformal maps shrink such a spout to a dot in the middle of the texture (its triangles get a
// tiny share of the uv area); the area-adaptive step of r-APS gives them their share back, which
// the printed statistics and the area distortion figures show.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh_io.h"

namespace {

raps_samples::PolygonMesh make_fountain(int rings, int sectors) {
    raps_samples::PolygonMesh mesh;
    auto add = [&](double x, double y, double z) {
        mesh.positions.insert(mesh.positions.end(), {x, y, z});
    };
    // Polar grid: centre vertex, then `rings` rings of `sectors` vertices. Radius r in (0, 1];
    // height: a spout of radius 0.25 and height 1.2 on a dome of height 0.3, with ripples.
    add(0, 0, 1.5);
    for (int k = 1; k <= rings; ++k) {
        const double r = static_cast<double>(k) / rings;
        for (int s = 0; s < sectors; ++s) {
            const double a = 2 * M_PI * (s + 0.5 * (k % 2)) / sectors;
            const double spout = 1.2 * std::exp(-std::pow(r / 0.25, 4));
            const double dome = 0.3 * (1 - r * r);
            const double ripple = 0.03 * std::sin(14 * r) * std::cos(5 * a) * r;
            add(r * std::cos(a), r * std::sin(a), spout + dome + ripple);
        }
    }
    mesh.polygon_offsets.push_back(0);
    auto quad_or_triangle = [&](std::initializer_list<uint32_t> corners) {
        mesh.corners.insert(mesh.corners.end(), corners);
        mesh.polygon_offsets.push_back(static_cast<uint32_t>(mesh.corners.size()));
    };
    auto ring_vertex = [&](int k, int s) {
        return static_cast<uint32_t>(1 + (k - 1) * sectors + ((s % sectors) + sectors) % sectors);
    };
    for (int s = 0; s < sectors; ++s)
        quad_or_triangle({0, ring_vertex(1, s), ring_vertex(1, s + 1)});
    for (int k = 1; k < rings; ++k) {
        // Odd rings are rotated by half a sector: split each quad along its shorter diagonal.
        for (int s = 0; s < sectors; ++s) {
            const int shift = k % 2;
            const uint32_t a = ring_vertex(k, s), b = ring_vertex(k, s + 1);
            const uint32_t c = ring_vertex(k + 1, s + shift), d = ring_vertex(k + 1, s + shift + 1);
            if (shift) {
                quad_or_triangle({a, c, b});
                quad_or_triangle({b, c, d});
            } else {
                quad_or_triangle({a, d, b});
                quad_or_triangle({a, c, d});
            }
        }
    }
    return mesh;
}

}  // namespace

int main(int argc, char** argv) {
    std::string output;
    int resolution = 96;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--resolution" && i + 1 < argc) {
            resolution = std::atoi(argv[++i]);
        } else if (arg == "-h" || arg == "--help") {
            std::puts(
                "usage: raps-demo-asset OUT.obj [--resolution N]\n"
                "Writes the quick start's demo mesh: a fountain-shaped disk patch of\n"
                "about 2 N^2 triangles (N = 96 by default, 8..2000).");
            return 0;
        } else if (output.empty() && !arg.empty() && arg[0] != '-') {
            output = arg;
        } else {
            std::fprintf(stderr, "raps-demo-asset: unexpected argument '%s' (try --help)\n",
                         arg.c_str());
            return 2;
        }
    }
    if (output.empty() || resolution < 8 || resolution > 2000) {
        std::fprintf(stderr, "raps-demo-asset: need OUT.obj and 8 <= N <= 2000 (try --help)\n");
        return 2;
    }
    try {
        const raps_samples::PolygonMesh mesh = make_fountain(resolution, 2 * resolution);
        raps_samples::write_obj(output, mesh, {}, {}, "raps demo asset: fountain");
        std::printf("wrote %s: %zu vertices, %zu triangles\n", output.c_str(), mesh.vertex_count(),
                    mesh.polygon_count());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raps-demo-asset: %s\n", e.what());
        return 1;
    }
    return 0;
}
