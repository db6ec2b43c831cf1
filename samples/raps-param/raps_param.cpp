// raps-param: parameterize a mesh file through the raps C API and write it back with UVs.
//
//   raps-param IN.(obj|off) -o OUT.obj [options]
//   raps-param --sphere IN.(obj|off) -o OUT.obj [options]
//
// Prints one JSON object on stdout (statistics, settings, per-phase times); see --help. This
// tool is a contract other tools and tests drive: keep its name, flags and OBJ-in/OBJ-out
// behaviour stable.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh_io.h"
#include "parameter_text.h"
#include "raps.h"

namespace {

const char* kUsage = R"(usage: raps-param [--atlas | --sphere] IN.(obj|off) -o OUT.obj [options]

Computes texture coordinates with r-adaptive parameterization (Zayer, Roessl, Seidel) and writes
OUT.obj with the input's vertices in their original order. Prints one JSON object on stdout:
input and output sizes, the settings used, the distortion statistics and the time of each phase
in milliseconds. On failure it prints {"error": {...}} on stdout, a message on stderr, writes
nothing, and exits with 1 (2 for a usage error).

Disk domain (default): the mesh must be a topological disk; one `vt` per vertex and the input's
faces in their order (`f v/vt ...`).
Atlas domain (--atlas): any mesh is cut into charts, each mapped and packed into one atlas;
seams get separate `vt` indices (`f v/vt`), faces are the input's in their order (a polygon is
written as triangles where a seam crosses it).
Sphere domain (--sphere): the mesh must be closed and of genus 0; it is mapped onto the unit
sphere (paper section 7) and OUT.obj gets the same faces with the points on the sphere as its `v` lines, in
input order, and no `vt`. With --sphere-uv octahedral the `v` lines are the same and the sphere
is also unfolded onto [0,1]^2 through the octahedron: `vt` lines, one per output vertex (the
vertices on the cut get one per side), faces `f v/vt`. The statistics are then those of the
uvs; without it, those of the sphere map (exact spherical triangle areas, angles between
great-circle arcs, flipped = det[a, b, c] < 0).

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
  --resolution N             texels on the atlas's longer side, 16..16384 (default 1024)
  --padding N                texels between charts, 0..64 (default 1)
  --weld-tolerance D         weld vertices closer than D (default 0: identical positions)
  --hard-edge-angle DEG      edges whose normals differ more become seams (default 180: none)
  --max-l2-stretch S         split charts until the atlas's L2 stretch is <= S (default 1.01)
  --max-linf-stretch S       split charts stretching any triangle more than S (default 2.9)
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

std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buffer[8];
                    std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
                    out += buffer;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

// JSON has no infinity or NaN: those become null, as in the project's reference metrics tool.
std::string json_number(double value) {
    if (!std::isfinite(value)) return "null";
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.10g", value);
    return buffer;
}

const char* choice_name(const char* flag, int64_t value) {
    return raps_samples::choice_name(*raps_samples::find_parameter_flag(flag), value);
}

double elapsed_ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
        .count();
}

struct Handles {
    raps_mesh* mesh = nullptr;
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    ~Handles() {
        raps_result_destroy(result);
        raps_settings_destroy(settings);
        raps_mesh_destroy(mesh);
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
// its fan triangles (in the order PolygonMesh::triangles() made them) agree on every corner's
// output vertex, that is when no seam runs through it; otherwise it is written as its triangles.
// Disk domain: output vertex = input vertex, so the input's faces come back unchanged.
void faces_with_output_vertices(const raps_samples::PolygonMesh& polygons,
                                const std::vector<uint32_t>& out_indices,
                                raps_samples::PolygonMesh& written,
                                std::vector<uint32_t>& uv_corners) {
    written.polygon_offsets.assign(1, 0);
    size_t triangle = 0;
    for (size_t f = 0; f < polygons.polygon_count(); ++f) {
        const uint32_t begin = polygons.polygon_offsets[f], end = polygons.polygon_offsets[f + 1];
        const size_t fan = end - begin - 2;
        std::vector<int64_t> corner_vertex(end - begin, -1);
        bool consistent = true;
        for (size_t i = 0; i < fan; ++i) {
            const size_t corners[3] = {0, i + 1, i + 2};
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
                const uint32_t corners[3] = {begin, static_cast<uint32_t>(begin + i + 1),
                                             static_cast<uint32_t>(begin + i + 2)};
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
                                     const raps_result* result) {
    const size_t vertices = raps_result_vertex_count(result);
    std::vector<double> points(3 * vertices);
    std::vector<uint32_t> remap(vertices);
    check(raps_result_copy_sphere_points_f64(result, points.data(), vertices, 0),
          [] { return "cannot copy sphere points"; });
    check(raps_result_copy_vertex_remap(result, remap.data(), vertices),
          [] { return "cannot copy the vertex remap"; });
    std::vector<double> positions(polygons.positions.size());
    for (size_t o = 0; o < vertices; ++o) {
        for (int c = 0; c < 3; ++c) positions[3 * remap[o] + c] = points[3 * o + c];
    }
    return positions;
}

int run(int argc, char** argv) {
    std::string input, output;
    Handles h;
    check(raps_settings_create(&h.settings), [] { return "cannot create settings"; });
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "-h" || arg == "--help") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (arg == "--version") {
            std::printf("raps-param (raps %s)\n", raps_version_string());
            return 0;
        } else if (arg == "-o" || arg == "--output") {
            output = value();
        } else if (arg == "--sphere") {
            check(raps_settings_set_int(h.settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_SPHERE),
                  [&] { return raps_settings_last_error(h.settings); });
        } else if (arg == "--atlas") {
            check(raps_settings_set_int(h.settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS),
                  [&] { return raps_settings_last_error(h.settings); });
        } else if (const raps_samples::ParameterFlag* flag =
                       raps_samples::find_parameter_flag(arg)) {
            const std::string error =
                raps_samples::set_parameter_from_text(h.settings, *flag, value());
            if (!error.empty()) throw UsageError(error);
        } else if (!arg.empty() && arg[0] == '-') {
            throw UsageError("unknown option " + arg);
        } else if (input.empty()) {
            input = arg;
        } else {
            throw UsageError("more than one input file (" + input + ", " + arg + ")");
        }
    }
    if (input.empty()) throw UsageError("no input file");
    if (output.empty()) throw UsageError("no output file (-o OUT.obj)");

    const auto read_start = std::chrono::steady_clock::now();
    const raps_samples::PolygonMesh polygons = raps_samples::read_mesh(input);
    const std::vector<uint32_t> triangles = polygons.triangles();
    const double read_ms = elapsed_ms(read_start);

    check(raps_mesh_create(&h.mesh), [] { return "cannot create a mesh"; });
    if (polygons.vertex_count() == 0) throw Failure(RAPS_ERROR_EMPTY_MESH, input + ": no vertices");
    if (triangles.empty()) throw Failure(RAPS_ERROR_EMPTY_MESH, input + ": no faces");
    check(
        raps_mesh_set_positions_f64(h.mesh, polygons.positions.data(), polygons.vertex_count(), 0),
        [&] { return raps_mesh_last_error(h.mesh); });
    check(raps_mesh_set_indices_u32(h.mesh, triangles.data(), triangles.size()),
          [&] { return raps_mesh_last_error(h.mesh); });
    check(raps_result_create(&h.result), [] { return "cannot create a result"; });
    check(raps_parameterize(h.mesh, h.settings, h.result),
          [&] { return raps_result_last_error(h.result); });

    int64_t domain, sphere_uv;
    raps_settings_get_int(h.settings, RAPS_PARAM_DOMAIN, &domain);
    raps_settings_get_int(h.settings, RAPS_PARAM_SPHERE_UV, &sphere_uv);
    const bool sphere = domain == RAPS_DOMAIN_SPHERE;
    const bool has_uvs = !sphere || sphere_uv != RAPS_SPHERE_UV_NONE;
    const size_t output_vertices = raps_result_vertex_count(h.result);
    std::vector<double> uvs;
    if (has_uvs) {
        uvs.resize(2 * output_vertices);
        check(raps_result_copy_uvs_f64(h.result, uvs.data(), output_vertices, 0),
              [&] { return "cannot copy uvs"; });
    }
    std::vector<uint32_t> out_indices(raps_result_index_count(h.result));
    check(raps_result_copy_indices_u32(h.result, out_indices.data(), out_indices.size()),
          [] { return "cannot copy indices"; });
    raps_samples::PolygonMesh written;
    std::vector<uint32_t> uv_corners;
    if (has_uvs) {
        faces_with_output_vertices(polygons, out_indices, written, uv_corners);
    } else {
        written.polygon_offsets = polygons.polygon_offsets;
        written.corners = polygons.corners;
    }
    written.positions = sphere ? sphere_positions(polygons, h.result) : polygons.positions;
    const auto write_start = std::chrono::steady_clock::now();
    raps_samples::write_obj(output, written, uvs, uv_corners,
                            std::string("raps-param ") + raps_version_string() + " from " + input);
    const double write_ms = elapsed_ms(write_start);

    raps_stats stats;
    stats.struct_size = sizeof(stats);
    check(raps_result_get_stats(h.result, &stats), [] { return "cannot read statistics"; });
    int64_t weights, monitor, iterations, mode, boundary, max_triangles, threads, resolution,
        padding, method, max_sweeps, alpha_steps;
    double alpha, weld, hard_edge, max_l2, max_linf, damping, tolerance;
    raps_settings_get_int(h.settings, RAPS_PARAM_ATLAS_RESOLUTION, &resolution);
    raps_settings_get_int(h.settings, RAPS_PARAM_ATLAS_PADDING, &padding);
    raps_settings_get_float(h.settings, RAPS_PARAM_WELD_TOLERANCE, &weld);
    raps_settings_get_float(h.settings, RAPS_PARAM_HARD_EDGE_ANGLE, &hard_edge);
    raps_settings_get_float(h.settings, RAPS_PARAM_ATLAS_MAX_L2_STRETCH, &max_l2);
    raps_settings_get_float(h.settings, RAPS_PARAM_ATLAS_MAX_LINF_STRETCH, &max_linf);
    raps_settings_get_int(h.settings, RAPS_PARAM_WEIGHTS, &weights);
    raps_settings_get_int(h.settings, RAPS_PARAM_MONITOR, &monitor);
    raps_settings_get_int(h.settings, RAPS_PARAM_ITERATIONS, &iterations);
    raps_settings_get_int(h.settings, RAPS_PARAM_ITERATION_MODE, &mode);
    raps_settings_get_int(h.settings, RAPS_PARAM_BOUNDARY, &boundary);
    raps_settings_get_int(h.settings, RAPS_PARAM_MAX_TRIANGLES, &max_triangles);
    raps_settings_get_float(h.settings, RAPS_PARAM_ALPHA, &alpha);
    raps_settings_get_int(h.settings, RAPS_PARAM_THREADS, &threads);
    raps_settings_get_int(h.settings, RAPS_PARAM_SPHERE_METHOD, &method);
    raps_settings_get_int(h.settings, RAPS_PARAM_SPHERE_MAX_SWEEPS, &max_sweeps);
    raps_settings_get_int(h.settings, RAPS_PARAM_SPHERE_ALPHA_STEPS, &alpha_steps);
    raps_settings_get_float(h.settings, RAPS_PARAM_SPHERE_DAMPING, &damping);
    raps_settings_get_float(h.settings, RAPS_PARAM_SPHERE_TOLERANCE, &tolerance);

    std::string json = "{";
    json += "\"input\": " + json_string(input) + ", \"output\": " + json_string(output);
    json += ", \"vertices\": " + std::to_string(stats.vertex_count);
    json += ", \"triangles\": " + std::to_string(stats.triangle_count);
    json += ", \"polygons\": " + std::to_string(polygons.polygon_count());
    const char* domain_name = domain == RAPS_DOMAIN_ATLAS ? "atlas" : sphere ? "sphere" : "disk";
    json += std::string(", \"settings\": {\"domain\": \"") + domain_name + "\", \"weights\": \"" +
            choice_name("--weights", weights) + "\", \"monitor\": \"" +
            choice_name("--monitor", monitor) + "\", \"alpha\": " + json_number(alpha) +
            ", \"iterations\": " + std::to_string(iterations) + ", \"iteration_mode\": \"" +
            choice_name("--iteration-mode", mode) + "\", \"threads\": " + std::to_string(threads) +
            ", \"max_triangles\": " + std::to_string(max_triangles);
    if (sphere) {
        json += std::string(", \"sphere_method\": \"") + choice_name("--sphere-method", method) +
                "\", \"sphere_uv\": \"" + choice_name("--sphere-uv", sphere_uv) +
                "\", \"damping\": " + json_number(damping) +
                ", \"tolerance\": " + json_number(tolerance) +
                ", \"max_sweeps\": " + std::to_string(max_sweeps) +
                ", \"alpha_steps\": " + std::to_string(alpha_steps);
    } else if (domain == RAPS_DOMAIN_ATLAS) {
        json += ", \"resolution\": " + std::to_string(resolution) +
                ", \"padding\": " + std::to_string(padding) +
                ", \"weld_tolerance\": " + json_number(weld) +
                ", \"hard_edge_angle\": " + json_number(hard_edge) +
                ", \"max_l2_stretch\": " + json_number(max_l2) +
                ", \"max_linf_stretch\": " + json_number(max_linf);
    } else {
        json += std::string(", \"boundary\": \"") + choice_name("--boundary", boundary) + "\"";
    }
    json += "}";
    json += ", \"stats\": {\"flipped_triangles\": " + std::to_string(stats.flipped_triangles) +
            ", \"zero_area_triangles\": " + std::to_string(stats.zero_area_triangles) +
            ", \"negative_weights\": " + std::to_string(stats.negative_weights) +
            ", \"adaptive_solves\": " + std::to_string(stats.adaptive_solves) +
            ", \"relaxation_sweeps\": " + std::to_string(stats.relaxation_sweeps) +
            ", \"area_log_mean\": " + json_number(stats.area_log_mean) +
            ", \"area_max\": " + json_number(stats.area_max) +
            ", \"angle_mean_deg\": " + json_number(stats.angle_mean_deg) +
            ", \"angle_max_deg\": " + json_number(stats.angle_max_deg) +
            ", \"stretch_l2\": " + json_number(stats.stretch_l2) +
            ", \"stretch_linf\": " + json_number(stats.stretch_linf) +
            ", \"charts\": " + std::to_string(stats.chart_count) +
            ", \"atlas_width\": " + std::to_string(stats.atlas_width) +
            ", \"atlas_height\": " + std::to_string(stats.atlas_height) +
            ", \"utilization\": " + json_number(stats.utilization) + "}";
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
