// make_fuzz_seeds: writes inputs for the mesh fuzz target (layout: fuzz_mesh_input.h).
//
//   make_fuzz_seeds analytic OUT_DIR          the small seeds committed in tests/fuzz/seeds
//   make_fuzz_seeds meshes MESH_DIR OUT_DIR   seeds from every .obj/.off in MESH_DIR
//
// The committed seeds come from the tests' analytic meshes, one per domain and feature (flags,
// settings, cancellation). The shared meshes are never copied into the repository: CTest and
// quickstart turn them into seeds at test time. A mesh larger than the target's triangle cap
// gives a patch of it instead: the triangles reached from its first triangle across edges,
// breadth first, up to kPatchTriangles (a disk on most meshes).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <dirent.h>
#include <sys/stat.h>

#include "fuzz_mesh_input.h"
#include "mesh_io.h"
#include "raps.h"
#include "support/test_meshes.h"

namespace {

constexpr size_t kPatchTriangles = 600;

struct Mesh {
    std::vector<double> positions;
    std::vector<uint32_t> indices;
};

void write_seed(const std::string& path, fuzz_mesh_seed seed, const Mesh& mesh) {
    seed.positions = mesh.positions.data();
    seed.vertex_count = mesh.positions.size() / 3;
    seed.indices = mesh.indices.data();
    seed.index_count = mesh.indices.size();
    size_t size = 0;
    uint8_t* bytes = fuzz_mesh_seed_encode(&seed, &size);
    if (!bytes) throw std::runtime_error(path + ": the mesh does not fit the fuzz input layout");
    FILE* file = std::fopen(path.c_str(), "wb");
    const bool written = file && std::fwrite(bytes, 1, size, file) == size;
    if (file) std::fclose(file);
    std::free(bytes);
    if (!written) throw std::runtime_error("cannot write " + path);
}

fuzz_mesh_seed make_seed(int domain, uint8_t flags, std::vector<fuzz_setting> settings) {
    fuzz_mesh_seed seed;
    std::memset(&seed, 0, sizeof(seed));
    seed.domain = static_cast<uint8_t>(domain);
    seed.flags = flags;
    seed.setting_count = settings.size();
    for (size_t s = 0; s < settings.size(); ++s) seed.settings[s] = settings[s];
    return seed;
}

Mesh from_test_mesh(test_mesh mesh) {
    Mesh out;
    out.positions.assign(mesh.positions, mesh.positions + 3 * mesh.vertex_count);
    out.indices.assign(mesh.indices, mesh.indices + mesh.index_count);
    test_mesh_free(&mesh);
    return out;
}

double ripple(double x, double y) {
    return 0.3 * x * y + 0.1 * x * x;
}

void write_analytic_seeds(const std::string& dir) {
    const Mesh flat = from_test_mesh(make_flat_disk(6, 6, 0.2));
    write_seed(dir + "/disk-flat.bin", make_seed(RAPS_DOMAIN_DISK, 0, {}), flat);
    write_seed(
        dir + "/disk-lifted-cotangent-square.bin",
        [] {
            fuzz_mesh_seed seed =
                make_seed(RAPS_DOMAIN_DISK, FUZZ_FLAG_U16,
                          {fuzz_int_setting(RAPS_PARAM_WEIGHTS, RAPS_WEIGHTS_COTANGENT),
                           fuzz_int_setting(RAPS_PARAM_MONITOR, RAPS_MONITOR_ANGLE),
                           fuzz_int_setting(RAPS_PARAM_ITERATIONS, 2),
                           fuzz_int_setting(RAPS_PARAM_BOUNDARY, RAPS_BOUNDARY_SQUARE),
                           fuzz_float_setting(RAPS_PARAM_ALPHA, 2.0)});
            seed.point_padding = 4;
            return seed;
        }(),
        from_test_mesh(make_lifted_disk(8, 5, ripple)));
    write_seed(
        dir + "/disk-cancelled-twice.bin",
        [] {
            fuzz_mesh_seed seed =
                make_seed(RAPS_DOMAIN_DISK, FUZZ_FLAG_CANCEL | FUZZ_FLAG_RUN_TWICE, {});
            seed.cancel_at = 5;
            return seed;
        }(),
        flat);
    write_seed(dir + "/disk-huge-counts.bin",
               make_seed(RAPS_DOMAIN_DISK,
                         FUZZ_FLAG_F64 | FUZZ_FLAG_HUGE_VERTEX_COUNT | FUZZ_FLAG_HUGE_INDEX_COUNT |
                             FUZZ_FLAG_INDICES_FIRST,
                         {fuzz_int_setting(RAPS_PARAM_MONITOR, RAPS_MONITOR_EDGE_LENGTH)}),
               flat);
    write_seed(dir + "/sphere-robust-octahedral.bin",
               make_seed(RAPS_DOMAIN_SPHERE, FUZZ_FLAG_RUN_TWICE,
                         {fuzz_int_setting(RAPS_PARAM_SPHERE_UV, RAPS_SPHERE_UV_OCTAHEDRAL),
                          fuzz_int_setting(RAPS_PARAM_THREADS, 2)}),
               from_test_mesh(make_icosphere(2)));
    write_seed(dir + "/sphere-literal.bin",
               make_seed(RAPS_DOMAIN_SPHERE, FUZZ_FLAG_F64,
                         {fuzz_int_setting(RAPS_PARAM_SPHERE_METHOD, RAPS_SPHERE_LITERAL),
                          fuzz_int_setting(RAPS_PARAM_SPHERE_MAX_SWEEPS, 50),
                          fuzz_float_setting(RAPS_PARAM_SPHERE_DAMPING, 0.5)}),
               from_test_mesh(make_icosphere(1)));
    write_seed(dir + "/atlas-closed-torus.bin",
               make_seed(RAPS_DOMAIN_ATLAS, FUZZ_FLAG_F64,
                         {fuzz_int_setting(RAPS_PARAM_ATLAS_RESOLUTION, 256),
                          fuzz_int_setting(RAPS_PARAM_THREADS, 2)}),
               from_test_mesh(make_closed_torus(16, 8)));
    write_seed(dir + "/atlas-cone-hard-edges.bin",
               make_seed(RAPS_DOMAIN_ATLAS, 0,
                         {fuzz_float_setting(RAPS_PARAM_HARD_EDGE_ANGLE, 30.0),
                          fuzz_int_setting(RAPS_PARAM_ATLAS_PADDING, 2),
                          fuzz_float_setting(RAPS_PARAM_WELD_TOLERANCE, 1e-3)}),
               from_test_mesh(make_open_cone(5, 6, 1.5)));
    write_seed(dir + "/atlas-punctured-torus-twice.bin",
               make_seed(RAPS_DOMAIN_ATLAS, FUZZ_FLAG_RUN_TWICE | FUZZ_FLAG_U16,
                         {fuzz_int_setting(RAPS_PARAM_THREADS, 3),
                          fuzz_float_setting(RAPS_PARAM_ATLAS_MAX_L2_STRETCH, 1.5)}),
               from_test_mesh(make_punctured_torus(12, 6)));
    // Polygon ids (fuzz_mesh_api.c): the torus's quads (its triangles come in pairs) kept whole
    // through the cuts, and one id too many, which the atlas refuses.
    write_seed(
        dir + "/atlas-torus-quads-twice.bin",
        [] {
            fuzz_mesh_seed seed = make_seed(RAPS_DOMAIN_ATLAS, FUZZ_FLAG_RUN_TWICE,
                                            {fuzz_int_setting(RAPS_PARAM_ATLAS_RESOLUTION, 256)});
            seed.polygons = 1;  // runs of 2 triangles
            return seed;
        }(),
        from_test_mesh(make_closed_torus(16, 8)));
    write_seed(
        dir + "/atlas-polygon-count-wrong.bin",
        [] {
            fuzz_mesh_seed seed = make_seed(RAPS_DOMAIN_ATLAS, 0, {});
            seed.polygons = 4;  // mode 0: one id more than the triangles
            return seed;
        }(),
        flat);
}

// The triangles reached from triangle 0 across shared edges, breadth first, at most `limit`,
// with their vertices renumbered in first-use order.
Mesh patch_of(const raps_samples::PolygonMesh& polygons, size_t limit) {
    const std::vector<uint32_t> all = polygons.triangles();
    const size_t triangles = all.size() / 3;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> by_edge;
    for (uint32_t t = 0; t < triangles; ++t) {
        for (int k = 0; k < 3; ++k) {
            uint32_t a = all[3 * t + k], b = all[3 * t + (k + 1) % 3];
            if (a > b) std::swap(a, b);
            by_edge[{a, b}].push_back(t);
        }
    }
    std::vector<char> taken(triangles, 0);
    std::vector<uint32_t> order;
    if (triangles > 0) {
        order.push_back(0);
        taken[0] = 1;
    }
    for (size_t head = 0; head < order.size() && order.size() < limit; ++head) {
        const uint32_t t = order[head];
        for (int k = 0; k < 3 && order.size() < limit; ++k) {
            uint32_t a = all[3 * t + k], b = all[3 * t + (k + 1) % 3];
            if (a > b) std::swap(a, b);
            for (uint32_t n : by_edge[{a, b}]) {
                if (!taken[n] && order.size() < limit) {
                    taken[n] = 1;
                    order.push_back(n);
                }
            }
        }
    }
    Mesh out;
    std::map<uint32_t, uint32_t> renumber;
    for (uint32_t t : order) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = all[3 * t + k];
            auto found = renumber.find(v);
            if (found == renumber.end()) {
                found = renumber.emplace(v, static_cast<uint32_t>(renumber.size())).first;
                for (int c = 0; c < 3; ++c) out.positions.push_back(polygons.positions[3 * v + c]);
            }
            out.indices.push_back(found->second);
        }
    }
    return out;
}

int write_mesh_seeds(const std::string& mesh_dir, const std::string& out_dir) {
    DIR* dir = opendir(mesh_dir.c_str());
    if (!dir) throw std::runtime_error("cannot open " + mesh_dir);
    std::vector<std::string> names;
    for (dirent* entry = readdir(dir); entry; entry = readdir(dir)) {
        const std::string name = entry->d_name;
        const size_t dot = name.rfind('.');
        if (dot == std::string::npos) continue;
        const std::string ext = name.substr(dot);
        if (ext == ".obj" || ext == ".off" || ext == ".OBJ" || ext == ".OFF") names.push_back(name);
    }
    closedir(dir);
    int written = 0;
    for (const std::string& name : names) {
        const Mesh patch =
            patch_of(raps_samples::read_mesh(mesh_dir + "/" + name), kPatchTriangles);
        const std::string stem = out_dir + "/" + name.substr(0, name.rfind('.'));
        write_seed(stem + "-disk.bin", make_seed(RAPS_DOMAIN_DISK, 0, {}), patch);
        write_seed(stem + "-atlas.bin",
                   make_seed(RAPS_DOMAIN_ATLAS, FUZZ_FLAG_F64,
                             {fuzz_int_setting(RAPS_PARAM_ATLAS_RESOLUTION, 512)}),
                   patch);
        write_seed(stem + "-sphere.bin", make_seed(RAPS_DOMAIN_SPHERE, 0, {}), patch);
        written += 3;
    }
    std::printf("make_fuzz_seeds: %d seeds from %zu meshes in %s\n", written, names.size(),
                out_dir.c_str());
    return written > 0 ? 0 : 1;
}

// Creates `dir` unless it exists.
void make_folder(const std::string& dir) {
    struct stat info;
    if (stat(dir.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) return;
    if (mkdir(dir.c_str(), 0777) != 0) throw std::runtime_error("cannot create " + dir);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc >= 3) make_folder(argv[argc - 1]);
        if (argc == 3 && std::strcmp(argv[1], "analytic") == 0) {
            write_analytic_seeds(argv[2]);
            return 0;
        }
        if (argc == 4 && std::strcmp(argv[1], "meshes") == 0) {
            return write_mesh_seeds(argv[2], argv[3]);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_fuzz_seeds: %s\n", e.what());
        return 1;
    }
    std::fprintf(stderr,
                 "usage: make_fuzz_seeds analytic OUT_DIR\n"
                 "       make_fuzz_seeds meshes MESH_DIR OUT_DIR\n");
    return 2;
}
