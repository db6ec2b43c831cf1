// raps-demo-asset: writes the demo asset the README's quick start bakes texture coordinates
// into, so the project needs no downloaded data to show what it does.
//
//   raps-demo-asset OUT.obj [--resolution N]
//   raps-demo-asset OUT.glb [--resolution N]
//
// OUT.obj is the fountain alone (a disk, for raps-param). OUT.glb is a small glTF scene for
// raps-gltf: the fountain and, around its foot, a basin rim shaped as a torus (closed, genus 1:
// only an atlas can unwrap it), with normals and a material each, in glTF's y-up frame.
// The asset is a "fountain": a dome of a disk-like patch whose centre rises into a tall spout.
// Conformal maps shrink such a spout to a dot in the middle of the texture (its triangles get a
// tiny share of the uv area); the area-adaptive step of r-APS gives them their share back, which
// the printed statistics and the area distortion figures show.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

// A closed torus of `rings` x `sides` quads split into triangles, around the z axis.
raps_samples::PolygonMesh make_torus(int rings, int sides, double radius, double tube, double z) {
    raps_samples::PolygonMesh mesh;
    for (int i = 0; i < rings; ++i) {
        const double a = 2 * M_PI * i / rings;
        for (int j = 0; j < sides; ++j) {
            const double b = 2 * M_PI * j / sides;
            const double r = radius + tube * std::cos(b);
            mesh.positions.insert(mesh.positions.end(),
                                  {r * std::cos(a), r * std::sin(a), z + tube * std::sin(b)});
        }
    }
    mesh.polygon_offsets.push_back(0);
    auto id = [&](int i, int j) { return static_cast<uint32_t>((i % rings) * sides + j % sides); };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < sides; ++j) {
            for (const auto& t :
                 {std::array<uint32_t, 3>{id(i, j), id(i + 1, j), id(i + 1, j + 1)},
                  std::array<uint32_t, 3>{id(i, j), id(i + 1, j + 1), id(i, j + 1)}}) {
                mesh.corners.insert(mesh.corners.end(), t.begin(), t.end());
                mesh.polygon_offsets.push_back(static_cast<uint32_t>(mesh.corners.size()));
            }
        }
    }
    return mesh;
}

// Writes the meshes as one GLB: per mesh float positions (z-up turned into glTF's y-up), vertex
// normals (area-weighted) and 32-bit indices, one node and one material each.
void write_glb(const std::string& path, const std::vector<raps_samples::PolygonMesh>& meshes,
               const std::vector<std::string>& names, const std::vector<std::string>& colours) {
    std::string bin, views, accessors, mesh_json, nodes, materials, scene_nodes;
    auto append = [&](const void* data, size_t size) {
        const size_t offset = bin.size();
        bin.append(static_cast<const char*>(data), size);
        while (bin.size() % 4) bin.push_back('\0');
        return offset;
    };
    int view = 0;
    for (size_t m = 0; m < meshes.size(); ++m) {
        const raps_samples::PolygonMesh& mesh = meshes[m];
        const size_t n = mesh.vertex_count();
        const std::vector<uint32_t> triangles = mesh.triangles();
        std::vector<float> position(3 * n), normal(3 * n, 0.0f);
        float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
        for (size_t v = 0; v < n; ++v) {
            const double* p = &mesh.positions[3 * v];
            const float q[3] = {float(p[0]), float(p[2]), float(-p[1])};
            for (int k = 0; k < 3; ++k) {
                position[3 * v + k] = q[k];
                lo[k] = std::min(lo[k], q[k]);
                hi[k] = std::max(hi[k], q[k]);
            }
        }
        for (size_t t = 0; t < triangles.size(); t += 3) {
            const float* a = &position[3 * triangles[t]];
            const float* b = &position[3 * triangles[t + 1]];
            const float* c = &position[3 * triangles[t + 2]];
            const float e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            const float f[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const float cross[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
                                    e[0] * f[1] - e[1] * f[0]};
            for (int k = 0; k < 3; ++k)
                for (int c3 = 0; c3 < 3; ++c3) normal[3 * triangles[t + k] + c3] += cross[c3];
        }
        for (size_t v = 0; v < n; ++v) {
            float* q = &normal[3 * v];
            const float length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            for (int k = 0; k < 3; ++k) q[k] = length > 0 ? q[k] / length : (k == 1 ? 1.0f : 0.0f);
        }
        const size_t p_at = append(position.data(), position.size() * 4);
        const size_t n_at = append(normal.data(), normal.size() * 4);
        const size_t i_at = append(triangles.data(), triangles.size() * 4);
        char text[1024];
        std::snprintf(text, sizeof(text),
                      "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
                      "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
                      "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963}",
                      m ? "," : "", p_at, position.size() * 4, n_at, normal.size() * 4, i_at,
                      triangles.size() * 4);
        views += text;
        std::snprintf(text, sizeof(text),
                      "%s{\"bufferView\":%d,\"componentType\":5126,\"count\":%zu,\"type\":"
                      "\"VEC3\",\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]},"
                      "{\"bufferView\":%d,\"componentType\":5126,\"count\":%zu,\"type\":"
                      "\"VEC3\"},"
                      "{\"bufferView\":%d,\"componentType\":5125,\"count\":%zu,\"type\":"
                      "\"SCALAR\"}",
                      m ? "," : "", view, n, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], view + 1, n,
                      view + 2, triangles.size());
        accessors += text;
        std::snprintf(text, sizeof(text),
                      "%s{\"name\":\"%s\",\"primitives\":[{\"attributes\":{\"POSITION\":%d,"
                      "\"NORMAL\":%d},\"indices\":%d,\"material\":%zu}]}",
                      m ? "," : "", names[m].c_str(), view, view + 1, view + 2, m);
        mesh_json += text;
        std::snprintf(text, sizeof(text), "%s{\"name\":\"%s\",\"mesh\":%zu}", m ? "," : "",
                      names[m].c_str(), m);
        nodes += text;
        std::snprintf(text, sizeof(text),
                      "%s{\"name\":\"%s\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%s,1],"
                      "\"metallicFactor\":0,\"roughnessFactor\":0.8}}",
                      m ? "," : "", names[m].c_str(), colours[m].c_str());
        materials += text;
        scene_nodes += (m ? "," : "") + std::to_string(m);
        view += 3;
    }
    std::string json =
        "{\"asset\":{\"version\":\"2.0\",\"generator\":\"raps-demo-asset\"},"
        "\"scene\":0,\"scenes\":[{\"nodes\":[" +
        scene_nodes + "]}],\"nodes\":[" + nodes + "],\"meshes\":[" + mesh_json +
        "],\"materials\":[" + materials + "],\"accessors\":[" + accessors + "],\"bufferViews\":[" +
        views + "],\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) + "}]}";
    while (json.size() % 4) json.push_back(' ');
    std::string glb;
    auto u32 = [&](uint32_t v) {
        for (int k = 0; k < 4; ++k) glb.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
    };
    glb += "glTF";
    u32(2);
    u32(static_cast<uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    u32(static_cast<uint32_t>(json.size()));
    u32(0x4E4F534A);
    glb += json;
    u32(static_cast<uint32_t>(bin.size()));
    u32(0x004E4942);
    glb += bin;
    raps_samples::write_file_atomically(path, glb);
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
                "usage: raps-demo-asset OUT.obj|OUT.glb [--resolution N]\n"
                "Writes the quick start's demo mesh: a fountain-shaped disk patch of\n"
                "about 2 N^2 triangles (N = 96 by default, 8..2000); OUT.glb adds a\n"
                "torus-shaped basin rim (3,072 triangles) as a second mesh.");
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
        std::fprintf(stderr,
                     "raps-demo-asset: need OUT.obj or OUT.glb and 8 <= N <= 2000 (try --help)\n");
        return 2;
    }
    try {
        const raps_samples::PolygonMesh mesh = make_fountain(resolution, 2 * resolution);
        const bool glb = output.size() > 4 && output.compare(output.size() - 4, 4, ".glb") == 0;
        if (glb) {
            const raps_samples::PolygonMesh rim = make_torus(96, 16, 1.12, 0.1, 0.02);
            write_glb(output, {mesh, rim}, {"fountain", "basin rim"},
                      {"0.72,0.78,0.86", "0.62,0.58,0.52"});
            std::printf("wrote %s: %zu + %zu vertices, %zu + %zu triangles\n", output.c_str(),
                        mesh.vertex_count(), rim.vertex_count(), mesh.polygon_count(),
                        rim.polygon_count());
        } else {
            raps_samples::write_obj(output, mesh, {}, {}, "raps demo asset: fountain");
            std::printf("wrote %s: %zu vertices, %zu triangles\n", output.c_str(),
                        mesh.vertex_count(), mesh.polygon_count());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raps-demo-asset: %s\n", e.what());
        return 1;
    }
    return 0;
}
