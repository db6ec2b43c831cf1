// raps-param: parameterize a mesh file through the raps C API and write it back with UVs.
//
//   raps-param IN.(obj|off|ply) -o OUT.obj [options]
//   raps-param --atlas IN1 [IN2 ...] -o OUT.obj [options]
//   raps-param --sphere IN.(obj|off|ply) -o OUT.obj [options]
//
// Prints one JSON object on stdout (statistics, settings, per-phase times); see --help. This
// tool is a contract other tools and tests drive: keep its name, flags and OBJ-in/OBJ-out
// behaviour stable.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh_io.h"
#include "parameter_text.h"
#include "raps.h"
#include "report_json.h"

namespace {

using param_report::json_number;
using param_report::json_string;

const char* kUsage = R"(usage: raps-param [--atlas | --sphere] IN.(obj|off|ply) -o OUT.obj [options]
       raps-param --atlas IN1 [IN2 ...] -o OUT.obj [options]

Computes texture coordinates with r-adaptive parameterization (Zayer, Roessl, Seidel) and writes
OUT.obj with the input's vertices in their original order. Prints one JSON object on stdout:
input and output sizes, the settings used, the distortion statistics and the time of each phase
in milliseconds. On failure it prints {"error": {...}} on stdout, a message on stderr, writes
nothing, and exits with 1 (2 for a usage error).

Disk domain (default): the mesh must be a topological disk; one `vt` per vertex a face uses,
in vertex order, and the input's faces in their order (`f v/vt ...`). Vertices no face uses
are left out of the map (the library refuses them) and keep their `v` line, with no `vt`.
Atlas domain (--atlas): any mesh is cut into charts, each mapped and packed into one atlas;
seams get separate `vt` indices (`f v/vt`), faces are the input's in their order (a polygon is
written as triangles where a seam crosses it). With several inputs, all are packed into one
atlas at one texel density and OUT.obj holds one `o` line per input, in the order given, each
followed by that input's `v`, `vt` and `f` lines; the JSON adds per input, per page and per
chart figures ("inputs", "pages", "charts"). `vt` are normalised to the page (--texels-per-unit).
Sphere domain (--sphere): the mesh must be closed and of genus 0; it is mapped onto the unit
sphere (paper section 7) and OUT.obj gets the same faces with the points on the sphere as its
`v` lines, in input order (a vertex no face uses keeps its position), and no `vt`. With
--sphere-uv octahedral the `v` lines are the same and the sphere is also unfolded onto [0,1]^2
through the octahedron: `vt` lines, one per output vertex (the vertices on the cut get one per
side), faces `f v/vt`. The statistics are then those of the uvs; without it, those of the
sphere map (exact spherical triangle areas, angles between great-circle arcs, flipped =
det[a, b, c] < 0).

options:
  -o, --output FILE          where to write the OBJ (required)
  --atlas                    the atlas domain (any mesh; charts, seams, packing)
  --sphere                   the sphere domain (closed genus-0 mesh onto the unit sphere)
  --weights mvc|cotan|uniform
                             base weights of the Laplace system (default mvc: mean value)
  --monitor none|area|length|angle
                             error monitor of the adaptive step (default area); none keeps the
                             initial quasi-conformal map
  --alpha A                  exponent of W = w * e^alpha, A > 0 (default 1)
  --iterations K             adaptive solves, 1..100 (default 1)
  --iteration-mode accumulate|reapply
                             how solves combine for K > 1 (default accumulate)
  --boundary circle|square   convex shape the boundary is fixed to (default circle)
  --max-triangles N          refuse meshes with more triangles (default 2^31 - 1)
  --max-memory-mb N          refuse runs estimated to need more memory (default 0: no cap)
  --threads N                threads, 0 = all cores (default 0); output is identical for any N
atlas options:
  --resolution N             texels on each side of the square atlas, 16..16384 (default 1024)
  --padding N                texels between charts, 0..64 (default 1)
  --weld-tolerance D         weld vertices closer than D (default 0: identical positions)
  --hard-edge-angle DEG      edges whose normals differ more become seams (default 180: none)
  --max-l2-stretch S         split charts until the atlas's L2 stretch is <= S (default 1.01)
  --max-linf-stretch S       split charts stretching any triangle more than S (default 2.9)
  --texels-per-unit T        pack at T texels per unit of the positions instead of filling
                             --resolution: charts on whole texels, on pages of at most
                             --max-size texels, as many pages as needed (default 0: off)
  --max-size N               with a density: pages of at most N x N texels, 16..16384
                             (default 4096); a chart larger than a page is shrunk to fit
  --rotate any|quarter|none  turns the packing may give a chart (default any)
  --margin N                 with a density or whole texels: texels free at each page's
                             border (default 0)
  --block-align              with a density or whole texels: charts on whole 4x4 blocks
  --mesh-per-page            with a density: each input's charts on one page
  --whole-texels             without a density: charts on whole texels (as with a density,
                             --margin and --block-align too) on one page of --resolution, at
                             the largest density that fits
  --keep-uv-seams            keep the input's uv seams as chart boundaries: an OBJ's corners
                             with different `vt` are different vertices to the atlas, which
                             does not weld across them (every face corner needs a vt)
  --repack                   keep each input's own uvs: the islands of its `vt` (faces that
                             share an edge whose two ends name equal uvs) are the charts,
                             each scaled to the one density and packed, never mapped again;
                             only moved, turned (--rotate) and scaled; flipped or overlapping
                             faces stay so (every face corner needs a vt)
  --stack                    congruent charts share one place (the same triangles, vertices
                             that agree up to a rigid motion): an input given twice, or one
                             repeating an earlier one, costs no extra texels; the JSON's
                             charts say "stacked_on"
  --stack-mirrored           --stack, mirrored copies too (their texture appears mirrored)
  --stack-tolerance F        how far a stacked chart's vertices may lie from its original's,
                             as a fraction of the chart's extent, [0, 0.1] (default 1e-4)
  --obj-groups               no chart crosses from one OBJ group to another: faces under
                             different `g` or `usemtl` lines never share a chart
  --split-polygons           let charts split quads and n-gons: by default each face of the
                             input is one unit (its triangles share a chart, no seam crosses
                             it, each corner gets one vt); with this flag its triangles are
                             separate, as in a triangle mesh (--repack ignores polygons: its
                             charts are the input's uv islands)
  --lightmap                 lightmap settings: --atlas --padding 2 --rotate quarter
                             --mesh-per-page --whole-texels (--padding and --rotate given
                             override theirs); refuses --stack, a lightmap needs every chart
                             its own texels
sphere options:
  --sphere-method literal|robust
                             literal: the paper's algorithm 7.1 as written (Gauss map,
                             Gauss-Seidel, damping; may fold and collapse); robust (default):
                             bijective start, fold-safe parallel relaxation, centring
  --sphere-uv none|octahedral
                             also unfold the sphere onto [0,1]^2 (default none)
  --damping L                sphere relaxation damping lambda in (0, 1] (default 1)
  --tolerance T              sphere relaxation stops below this residual (default 1e-4)
  --max-sweeps N             most sweeps per sphere relaxation (default 0: robust 100
                             initial and 200 adaptive, literal 50000)
  --alpha-steps K            robust sphere method: continuation steps to alpha (default 2)
  -h, --help                 this text
  --version                  the raps library version
)";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

double elapsed_ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
        .count();
}

struct Handles {
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    ~Handles() {
        raps_result_destroy(result);
        raps_settings_destroy(settings);
    }
};

struct Failure : std::runtime_error {
    Failure(raps_status s, const std::string& message) : std::runtime_error(message), status(s) {}
    raps_status status;
};

// Takes the message getter rather than the message: it must be read after the call fails.
template <typename Message>
void check(raps_status status, Message&& message) {
    if (status != RAPS_OK) throw Failure(status, message());
}

// The OBJ's faces and, per corner, its output vertex (its `vt`). A polygon stays a polygon when
// its triangles (PolygonMesh::polygon_triangles, in the order triangles() made them) agree on
// every corner's output vertex, that is when no seam runs through it; otherwise it is written as
// its triangles. Disk domain: output vertex = input vertex, so the input's faces come back
// unchanged.
void faces_with_output_vertices(const raps_samples::PolygonMesh& polygons,
                                const std::vector<uint32_t>& out_indices,
                                raps_samples::PolygonMesh& written,
                                std::vector<uint32_t>& uv_corners) {
    written.polygon_offsets.assign(1, 0);
    size_t triangle = 0;
    std::vector<std::array<uint32_t, 3>> parts;
    for (size_t f = 0; f < polygons.polygon_count(); ++f) {
        const uint32_t begin = polygons.polygon_offsets[f], end = polygons.polygon_offsets[f + 1];
        polygons.polygon_triangles(f, parts);
        const size_t fan = parts.size();
        std::vector<int64_t> corner_vertex(end - begin, -1);
        bool consistent = true;
        for (size_t i = 0; i < fan; ++i) {
            const std::array<uint32_t, 3>& corners = parts[i];
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = out_indices[3 * (triangle + i) + k];
                int64_t& slot = corner_vertex[corners[k]];
                if (slot >= 0 && slot != v) consistent = false;
                slot = v;
            }
        }
        if (consistent) {
            for (uint32_t c = begin; c < end; ++c) {
                written.corners.push_back(polygons.corners[c]);
                uv_corners.push_back(static_cast<uint32_t>(corner_vertex[c - begin]));
            }
            written.polygon_offsets.push_back(static_cast<uint32_t>(written.corners.size()));
        } else {
            for (size_t i = 0; i < fan; ++i) {
                const uint32_t corners[3] = {begin + parts[i][0], begin + parts[i][1],
                                             begin + parts[i][2]};
                for (int k = 0; k < 3; ++k) {
                    written.corners.push_back(polygons.corners[corners[k]]);
                    uv_corners.push_back(out_indices[3 * (triangle + i) + k]);
                }
                written.polygon_offsets.push_back(static_cast<uint32_t>(written.corners.size()));
            }
        }
        triangle += fan;
    }
}

// The sphere domain writes its points on the sphere as the OBJ's `v` lines, in input order.
std::vector<double> sphere_positions(const raps_samples::PolygonMesh& polygons,
                                     const std::vector<uint32_t>& vertex_of,
                                     const raps_result* result) {
    const size_t vertices = raps_result_vertex_count(result);
    std::vector<double> points(3 * vertices);
    std::vector<uint32_t> remap(vertices);
    check(raps_result_copy_sphere_points_f64(result, points.data(), vertices, 0),
          [] { return "cannot copy sphere points"; });
    check(raps_result_copy_vertex_remap(result, remap.data(), vertices),
          [] { return "cannot copy the vertex remap"; });
    // A vertex no face uses keeps its position: it is on no triangle, so on no sphere.
    std::vector<double> positions = polygons.positions;
    for (size_t o = 0; o < vertices; ++o) {
        const size_t v = vertex_of.empty() ? remap[o] : vertex_of[remap[o]];
        for (int c = 0; c < 3; ++c) positions[3 * v + c] = points[3 * o + c];
    }
    return positions;
}

struct Options {
    std::vector<std::string> inputs;
    std::string output;
    bool keep_uv_seams = false;   // the library sees a vertex per (v, vt) pair of the OBJ
    bool obj_groups = false;      // OBJ `g` / `usemtl` as triangle groups
    bool repack = false;          // the OBJ's own vt as the charts
    bool split_polygons = false;  // each fan triangle on its own, not its face's unit
};

// Reads the command line into the settings; returns the files. Exits early (returning false)
// for --help and --version.
bool parse_arguments(int argc, char** argv, raps_settings* settings, Options& options) {
    bool lightmap = false;
    for (int i = 1; i < argc; ++i) lightmap = lightmap || std::strcmp(argv[i], "--lightmap") == 0;
    // The domain flags: the last one would win in silence (`--sphere --lightmap` mapped a sphere
    // with the lightmap's settings unused).
    const char* sphere_flag = nullptr;
    const char* atlas_flag = nullptr;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--sphere") sphere_flag = argv[i];
        if (arg == "--atlas" || arg == "--lightmap" || arg == "--repack") atlas_flag = argv[i];
    }
    if (sphere_flag && atlas_flag) {
        throw UsageError(std::string(sphere_flag) + " and " + atlas_flag +
                         " choose different domains (the sphere, an atlas): give one");
    }
    if (lightmap) {
        const std::string error = raps_samples::apply_lightmap_preset(settings);
        if (!error.empty()) throw Failure(RAPS_ERROR_INTERNAL, error);
    }
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "-h" || arg == "--help") {
            std::fputs(kUsage, stdout);
            return false;
        } else if (arg == "--version") {
            std::printf("raps-param (raps %s)\n", raps_version_string());
            return false;
        } else if (arg == "-o" || arg == "--output") {
            options.output = value();
        } else if (arg == "--sphere") {
            check(raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_SPHERE),
                  [&] { return raps_settings_last_error(settings); });
        } else if (arg == "--atlas") {
            check(raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS),
                  [&] { return raps_settings_last_error(settings); });
        } else if (arg == "--lightmap") {
            continue;  // applied above
        } else if (arg == "--max-size") {
            const std::string error = raps_samples::set_max_size(settings, value());
            if (!error.empty()) throw UsageError(error);
        } else if (const raps_samples::SwitchFlag* on = raps_samples::find_switch_flag(arg)) {
            check(raps_settings_set_int(settings, on->param, 1),
                  [&] { return raps_settings_last_error(settings); });
            options.keep_uv_seams = options.keep_uv_seams || arg == "--keep-uv-seams";
        } else if (arg == "--repack") {
            check(raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS),
                  [&] { return raps_settings_last_error(settings); });
            check(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_REPACK, 1),
                  [&] { return raps_settings_last_error(settings); });
            options.repack = true;
        } else if (arg == "--stack" || arg == "--stack-mirrored") {
            const std::string error = raps_samples::set_stack(settings, arg, lightmap);
            if (!error.empty()) throw UsageError(error);
        } else if (arg == "--obj-groups") {
            options.obj_groups = true;
        } else if (arg == "--split-polygons") {
            options.split_polygons = true;
        } else if (const raps_samples::ParameterFlag* flag =
                       raps_samples::find_parameter_flag(arg)) {
            const std::string error =
                raps_samples::set_parameter_from_text(settings, *flag, value());
            if (!error.empty()) throw UsageError(error);
        } else if (!arg.empty() && arg[0] == '-') {
            throw UsageError("unknown option " + arg);
        } else {
            options.inputs.push_back(arg);
        }
    }
    if (options.inputs.empty()) throw UsageError("no input file");
    if (options.output.empty()) throw UsageError("no output file (-o OUT.obj)");
    int64_t domain = 0;
    raps_settings_get_int(settings, RAPS_PARAM_DOMAIN, &domain);
    if (options.inputs.size() > 1 && domain != RAPS_DOMAIN_ATLAS) {
        throw UsageError("more than one input file (" + options.inputs[0] + ", " +
                         options.inputs[1] + "): only --atlas packs several into one atlas");
    }
    return true;
}

// One input file, read and handed to the library.
struct Input {
    raps_samples::PolygonMesh polygons;
    raps_mesh* mesh = nullptr;
    // The disk and sphere domains map only the vertices faces use (the library refuses any
    // other): per vertex given to the library, its vertex of `polygons`; empty when all are.
    std::vector<uint32_t> vertex_of;
    Input() = default;
    Input(const Input&) = delete;
    Input& operator=(const Input&) = delete;
    ~Input() { raps_mesh_destroy(mesh); }
};

// --keep-uv-seams and --repack read the file's vt: every face corner must name one.
void require_texcoords(const std::string& path, const raps_samples::PolygonMesh& polygons,
                       const char* flag, raps_status status) {
    const auto missing =
        std::find(polygons.texcoord_corners.begin(), polygons.texcoord_corners.end(),
                  raps_samples::PolygonMesh::kNoTexcoord);
    if (polygons.texcoord_corners.empty() || missing != polygons.texcoord_corners.end()) {
        const size_t corner = static_cast<size_t>(missing - polygons.texcoord_corners.begin());
        throw Failure(status,
                      path + ": " + flag + " needs an OBJ whose every face corner names a vt" +
                          (polygons.texcoord_corners.empty()
                               ? std::string(" (this file has no faces with vt)")
                               : "; face corner " + std::to_string(corner) + " names none"));
    }
}

// With --keep-uv-seams the library gets one vertex per (v, vt) pair, so the file's uv seams are
// vertex splits it keeps; the OBJ is still written with the file's own `v` (the output's faces
// are matched to the input's corners in order, never through the remap).
raps_samples::PolygonMesh library_view(const std::string& path,
                                       const raps_samples::PolygonMesh& polygons,
                                       const Options& options) {
    if (!options.keep_uv_seams) return polygons;
    require_texcoords(path, polygons, "--keep-uv-seams", RAPS_ERROR_INVALID_ARGUMENT);
    return polygons.split_at_texcoord_seams();
}

// Per triangle of PolygonMesh::triangles(), the index of the face it was fanned from. Empty for
// a mesh of triangles only: every triangle its own polygon is the library's default, so such
// meshes take the same path (and give the same bits) as before polygons were passed.
std::vector<uint32_t> triangle_polygons(const raps_samples::PolygonMesh& mesh) {
    std::vector<uint32_t> out;
    if (mesh.corners.size() == 3 * mesh.polygon_count()) return out;
    out.reserve(mesh.corners.size() - 2 * mesh.polygon_count());
    for (size_t f = 0; f < mesh.polygon_count(); ++f)
        out.insert(out.end(), mesh.polygon_offsets[f + 1] - mesh.polygon_offsets[f] - 2,
                   static_cast<uint32_t>(f));
    return out;
}

// The atlas keeps each face whole unless --split-polygons; --repack takes the input's uv
// islands as they are and never reads polygons, and the disk and sphere domains cut nothing.
bool pass_polygons(const Options& options, const raps_settings* settings) {
    int64_t domain = 0;
    raps_settings_get_int(settings, RAPS_PARAM_DOMAIN, &domain);
    return domain == RAPS_DOMAIN_ATLAS && !options.split_polygons && !options.repack;
}

// The vertices `triangles` use, renumbered in their order, and the positions of those alone:
// `vertex_of` gets each one's old number (left empty when every vertex is used).
void drop_unused_vertices(raps_samples::PolygonMesh& mesh, std::vector<uint32_t>& triangles,
                          std::vector<uint32_t>& vertex_of) {
    std::vector<uint32_t> number(mesh.vertex_count(), UINT32_MAX);
    for (uint32_t v : triangles) {
        if (v >= number.size()) return;  // the library names the index out of range
        number[v] = 0;
    }
    if (std::count(number.begin(), number.end(), UINT32_MAX) == 0) return;
    std::vector<double> kept;
    for (uint32_t v = 0; v < number.size(); ++v) {
        if (number[v] == UINT32_MAX) continue;
        number[v] = static_cast<uint32_t>(vertex_of.size());
        vertex_of.push_back(v);
        kept.insert(kept.end(), mesh.positions.begin() + 3 * v, mesh.positions.begin() + 3 * v + 3);
    }
    for (uint32_t& v : triangles) v = number[v];
    mesh.positions = std::move(kept);
}

void load_input(const std::string& path, const Options& options, bool polygons,
                bool used_vertices_only, Input& input) {
    input.polygons = raps_samples::read_mesh(path);
    raps_samples::PolygonMesh library = library_view(path, input.polygons, options);
    std::vector<uint32_t> triangles = library.triangles();
    if (used_vertices_only) drop_unused_vertices(library, triangles, input.vertex_of);
    check(raps_mesh_create(&input.mesh), [] { return "cannot create a mesh"; });
    // No faces first: without them the disk and sphere domains keep no vertex either.
    if (triangles.empty()) throw Failure(RAPS_ERROR_EMPTY_MESH, path + ": no faces");
    if (library.vertex_count() == 0) throw Failure(RAPS_ERROR_EMPTY_MESH, path + ": no vertices");
    check(raps_mesh_set_positions_f64(input.mesh, library.positions.data(), library.vertex_count(),
                                      0),
          [&] { return path + ": " + raps_mesh_last_error(input.mesh); });
    check(raps_mesh_set_indices_u32(input.mesh, triangles.data(), triangles.size()),
          [&] { return path + ": " + raps_mesh_last_error(input.mesh); });
    if (options.repack) {
        require_texcoords(path, library, "--repack", RAPS_ERROR_UV_COUNT);
        const std::vector<double> uv = library.triangle_texcoords();
        check(raps_mesh_set_corner_uvs_f64(input.mesh, uv.data(), uv.size() / 2, 0),
              [&] { return path + ": " + raps_mesh_last_error(input.mesh); });
    }
    if (options.obj_groups) {
        const std::vector<uint32_t> groups = library.triangle_groups();
        check(raps_mesh_set_triangle_groups(input.mesh, groups.data(), groups.size()),
              [&] { return path + ": " + raps_mesh_last_error(input.mesh); });
    }
    const std::vector<uint32_t> ids =
        polygons ? triangle_polygons(library) : std::vector<uint32_t>();
    if (!ids.empty()) {
        check(raps_mesh_set_triangle_polygons(input.mesh, ids.data(), ids.size()),
              [&] { return path + ": " + raps_mesh_last_error(input.mesh); });
    }
}

// An `o` line's name: the file name without its folder and extension.
std::string object_name(const std::string& path) {
    const size_t slash = path.find_last_of("/\\");
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    const size_t dot = name.find_last_of('.');
    if (dot != std::string::npos && dot > 0) name.resize(dot);
    for (char& c : name) {
        if (static_cast<unsigned char>(c) <= ' ') c = '_';
    }
    return name.empty() ? "mesh" : name;
}

// The OBJ object of input `m` of the result, from the result's uvs and indices: its share of
// them, its faces.
raps_samples::ObjObject output_object(const std::string& path, const Input& input,
                                      const raps_result* result, size_t m, bool sphere,
                                      const std::vector<double>& uvs,
                                      const std::vector<uint32_t>& indices) {
    uint64_t first_vertex = 0, vertex_count = 0, first_index = 0, index_count = 0;
    check(
        raps_result_mesh_range(result, m, &first_vertex, &vertex_count, &first_index, &index_count),
        [&] { return raps_result_last_error(result); });
    raps_samples::ObjObject object;
    object.name = object_name(path);
    if (!uvs.empty()) {
        object.uvs.assign(uvs.begin() + 2 * first_vertex,
                          uvs.begin() + 2 * (first_vertex + vertex_count));
        const std::vector<uint32_t> own(indices.begin() + first_index,
                                        indices.begin() + first_index + index_count);
        faces_with_output_vertices(input.polygons, own, object.mesh, object.uv_corners);
    } else {
        object.mesh.polygon_offsets = input.polygons.polygon_offsets;
        object.mesh.corners = input.polygons.corners;
    }
    object.mesh.positions = sphere ? sphere_positions(input.polygons, input.vertex_of, result)
                                   : input.polygons.positions;
    return object;
}

int run(int argc, char** argv) {
    Options options;
    Handles h;
    check(raps_settings_create(&h.settings), [] { return "cannot create settings"; });
    if (!parse_arguments(argc, argv, h.settings, options)) return 0;

    const auto read_start = std::chrono::steady_clock::now();
    std::vector<std::unique_ptr<Input>> inputs;
    std::vector<const raps_mesh*> meshes;
    size_t polygons = 0;
    const bool whole_polygons = pass_polygons(options, h.settings);
    int64_t mapped_domain = 0;
    raps_settings_get_int(h.settings, RAPS_PARAM_DOMAIN, &mapped_domain);
    for (const std::string& path : options.inputs) {
        inputs.push_back(std::make_unique<Input>());
        load_input(path, options, whole_polygons, mapped_domain != RAPS_DOMAIN_ATLAS,
                   *inputs.back());
        meshes.push_back(inputs.back()->mesh);
        polygons += inputs.back()->polygons.polygon_count();
    }
    const double read_ms = elapsed_ms(read_start);

    int64_t domain, sphere_uv;
    raps_settings_get_int(h.settings, RAPS_PARAM_DOMAIN, &domain);
    raps_settings_get_int(h.settings, RAPS_PARAM_SPHERE_UV, &sphere_uv);
    const bool atlas = domain == RAPS_DOMAIN_ATLAS;
    const bool sphere = domain == RAPS_DOMAIN_SPHERE;
    const bool has_uvs = !sphere || sphere_uv != RAPS_SPHERE_UV_NONE;
    check(raps_result_create(&h.result), [] { return "cannot create a result"; });
    check(atlas ? raps_parameterize_scene(meshes.data(), meshes.size(), h.settings, h.result)
                : raps_parameterize(meshes[0], h.settings, h.result),
          [&] { return raps_result_last_error(h.result); });

    const size_t output_vertices = raps_result_vertex_count(h.result);
    std::vector<double> uvs;
    if (has_uvs) {
        uvs.resize(2 * output_vertices);
        check(raps_result_copy_uvs_f64(h.result, uvs.data(), output_vertices, 0),
              [&] { return "cannot copy uvs"; });
    }
    std::vector<uint32_t> indices(raps_result_index_count(h.result));
    check(raps_result_copy_indices_u32(h.result, indices.data(), indices.size()),
          [] { return "cannot copy indices"; });
    std::vector<raps_samples::ObjObject> objects;
    for (size_t m = 0; m < inputs.size(); ++m) {
        objects.push_back(
            output_object(options.inputs[m], *inputs[m], h.result, m, sphere, uvs, indices));
    }
    const auto write_start = std::chrono::steady_clock::now();
    const std::string comment =
        std::string("raps-param ") + raps_version_string() + " from " + options.inputs[0];
    if (objects.size() == 1) {
        raps_samples::write_obj(options.output, objects[0].mesh, objects[0].uvs,
                                objects[0].uv_corners, comment);
    } else {
        raps_samples::write_obj_objects(options.output, objects, comment);
    }
    const double write_ms = elapsed_ms(write_start);

    raps_stats stats;
    stats.struct_size = sizeof(stats);
    check(raps_result_get_stats(h.result, &stats), [] { return "cannot read statistics"; });
    std::string json = "{";
    json += "\"input\": " + json_string(options.inputs[0]) +
            ", \"output\": " + json_string(options.output);
    json += ", \"vertices\": " + std::to_string(stats.vertex_count);
    json += ", \"triangles\": " + std::to_string(stats.triangle_count);
    json += ", \"polygons\": " + std::to_string(polygons);
    json += std::string(", \"whole_polygons\": ") + (whole_polygons ? "true" : "false");
    json += ", \"settings\": " + param_report::settings_json(h.settings);
    json += ", \"stats\": " + param_report::stats_json(stats, atlas);
    if (atlas) {
        std::vector<param_report::MeshShare> shares(options.inputs.size());
        for (size_t m = 0; m < shares.size(); ++m) {
            check(raps_result_mesh_range(h.result, m, &shares[m].first_vertex,
                                         &shares[m].vertex_count, &shares[m].first_index,
                                         &shares[m].index_count),
                  [&] { return raps_result_last_error(h.result); });
        }
        std::vector<raps_chart> charts(stats.chart_count);
        for (size_t c = 0; c < charts.size(); ++c) {
            charts[c].struct_size = sizeof(raps_chart);
            check(raps_result_get_chart(h.result, c, &charts[c]),
                  [&] { return raps_result_last_error(h.result); });
        }
        json += param_report::atlas_json(options.inputs, shares, charts, stats);
    }
    json += ", \"time_ms\": {\"read\": " + json_number(read_ms);
    double library_ms = 0;
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p) {
        const double ms = raps_result_phase_ms(h.result, p);
        library_ms += ms;
        json += std::string(", \"") + raps_samples::phase_name(p) + "\": " + json_number(ms);
    }
    json += ", \"library_total\": " + json_number(library_ms) +
            ", \"write\": " + json_number(write_ms) + "}}";
    std::puts(json.c_str());
    return 0;
}

void report_error(const char* kind, raps_status status, const std::string& message) {
    std::printf(
        "{\"error\": {\"kind\": \"%s\", \"status\": %d, \"status_name\": %s, \"message\": %s}}\n",
        kind, status, json_string(raps_status_string(status)).c_str(),
        json_string(message).c_str());
    std::fprintf(stderr, "raps-param: %s\n", message.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const UsageError& e) {
        report_error("usage", RAPS_ERROR_INVALID_ARGUMENT, e.what());
        std::fputs("try raps-param --help\n", stderr);
        return 2;
    } catch (const Failure& e) {
        report_error("raps", e.status, e.what());
        return 1;
    } catch (const std::exception& e) {
        report_error("input", RAPS_ERROR_INVALID_ARGUMENT, e.what());
        return 1;
    }
}
