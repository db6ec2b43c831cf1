#include "gltf_library_map.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>

#include "gltf_accessors.h"
#include "gltf_error.h"

namespace raps_gltf {

namespace {

struct MeshHandle {
    raps_mesh* mesh = nullptr;
    MeshHandle() = default;
    MeshHandle(const MeshHandle&) = delete;
    MeshHandle& operator=(const MeshHandle&) = delete;
    ~MeshHandle() { raps_mesh_destroy(mesh); }
};

struct RunHandles {
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    ~RunHandles() {
        raps_result_destroy(result);
        raps_settings_destroy(settings);
    }
};

struct ProgressContext {
    const BakeOptions* options;
    std::string label;
};

int32_t forward_progress(void* user, raps_phase phase, double fraction) {
    const ProgressContext* c = static_cast<const ProgressContext*>(user);
    return c->options->progress(c->label, phase, fraction) ? 1 : 0;
}

// The settings of a run: the user's, in the atlas domain. With a density every mesh keeps its
// charts on one page: a primitive's uvs address one texture. (A resolution makes one page, and
// there the setting would only keep --stack from sharing charts between meshes.)
// `unit` is the length of one of the mesh's units in the library's (see scaled_exponent).
void prepare_run(const BakeOptions& options, ProgressContext* progress, RunHandles* h,
                 double unit = 1) {
    double density = 0;
    raps_settings_get_float(options.settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, &density);
    if (raps_result_create(&h->result) != RAPS_OK ||
        raps_settings_clone(options.settings, &h->settings) != RAPS_OK ||
        (density > 0 && unit != 1 &&
         raps_settings_set_float(h->settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, density / unit) !=
             RAPS_OK) ||
        raps_settings_set_int(h->settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS) != RAPS_OK ||
        (density > 0 &&
         raps_settings_set_int(h->settings, RAPS_PARAM_ATLAS_MESH_PER_PAGE, 1) != RAPS_OK)) {
        throw GltfError("raps", "cannot create the library's handles");
    }
    if (options.progress) raps_settings_set_progress(h->settings, &forward_progress, progress);
}

void load_mesh(const GroupGeometry& g, const Linear3* linear, const std::string& label,
               MeshHandle* h) {
    if (raps_mesh_create(&h->mesh) != RAPS_OK) {
        throw GltfError("raps", "cannot create the library's handles");
    }
    if (raps_mesh_set_positions_f64(h->mesh, g.xyz.data(), g.xyz.size() / 3, 0) != RAPS_OK ||
        raps_mesh_set_indices_u32(h->mesh, g.indices.data(), g.indices.size()) != RAPS_OK) {
        throw GltfError("raps", label + ": " + raps_mesh_last_error(h->mesh));
    }
    if (linear) {
        const Linear3& m = *linear;
        const double rows[12] = {m[0], m[1], m[2], 0, m[3], m[4], m[5], 0, m[6], m[7], m[8], 0};
        if (raps_mesh_set_transform(h->mesh, rows) != RAPS_OK)
            throw GltfError("raps", label + ": " + raps_mesh_last_error(h->mesh));
    }
}

// The run's figures: stats and phase times.
void read_figures(const raps_result* result, raps_stats* stats, double* phase_ms) {
    for (int phase = 0; phase < RAPS_PHASE_COUNT; ++phase)
        phase_ms[phase] = raps_result_phase_ms(result, static_cast<raps_phase>(phase));
    stats->struct_size = sizeof(raps_stats);
    raps_result_get_stats(result, stats);
}

// Everything the result holds, all meshes at once.
struct WholeResult {
    std::vector<double> uv;
    std::vector<uint32_t> indices, remap, charts;
};

WholeResult copy_result(const raps_result* result, const std::string& label) {
    WholeResult w;
    const size_t vertices = raps_result_vertex_count(result);
    w.uv.resize(2 * vertices);
    w.indices.resize(raps_result_index_count(result));
    w.remap.resize(vertices);
    w.charts.resize(w.indices.size() / 3);
    if (raps_result_copy_uvs_f64(result, w.uv.data(), vertices, 0) != RAPS_OK ||
        raps_result_copy_indices_u32(result, w.indices.data(), w.indices.size()) != RAPS_OK ||
        raps_result_copy_vertex_remap(result, w.remap.data(), vertices) != RAPS_OK ||
        raps_result_copy_chart_ids(result, w.charts.data(), w.charts.size()) != RAPS_OK) {
        throw GltfError("raps", label + ": " + raps_result_last_error(result));
    }
    return w;
}

// Mesh `mesh`'s share of the result, checked against the contract the gathering relies on:
// corner k of output triangle t is a copy of corner k of input triangle t.
GroupMap slice(const raps_result* result, const WholeResult& w, size_t mesh,
               const GroupGeometry& g) {
    uint64_t first_vertex = 0, vertex_count = 0, first_index = 0, index_count = 0;
    raps_result_mesh_range(result, mesh, &first_vertex, &vertex_count, &first_index, &index_count);
    if (index_count != g.indices.size()) {
        throw GltfError("internal", "the library returned another triangle count");
    }
    GroupMap map;
    map.first_triangle = g.first_triangle;
    map.uv.assign(w.uv.begin() + 2 * first_vertex,
                  w.uv.begin() + 2 * (first_vertex + vertex_count));
    map.indices.assign(w.indices.begin() + first_index,
                       w.indices.begin() + first_index + index_count);
    map.charts.assign(w.charts.begin() + first_index / 3,
                      w.charts.begin() + (first_index + index_count) / 3);
    for (size_t i = 0; i < map.indices.size(); ++i) {
        if (map.indices[i] >= vertex_count ||
            w.remap[first_vertex + map.indices[i]] != g.indices[i]) {
            throw GltfError("internal", "the library's vertex map breaks corner order");
        }
    }
    return map;
}

// A mesh's charts are all on one page (the run keeps them together): the first one's.
uint32_t page_of(const raps_result* result, const GroupMap& map) {
    if (map.charts.empty()) return 0;
    raps_chart chart{};
    chart.struct_size = sizeof(raps_chart);
    raps_result_get_chart(result, map.charts[0], &chart);
    return chart.page;
}

double elapsed_ms(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

using WeldKey = std::array<double, 5>;  // position, then the TEXCOORD_0 value

// Per vertex of primitive p, its TEXCOORD_0 value (empty when it has none, no data, or a value
// that is not finite).
std::vector<double> texcoord0(const Asset& asset, const PrimitiveInput& p) {
    const Json* set = member((*p.json)["attributes"], "TEXCOORD_0");
    if (!set || !accessor_has_data(asset, set->get<int>())) return {};
    const AccessorLayout a = accessor_layout(asset.doc, set->get<int>());
    if (a.type != "VEC2" || a.count != p.vertex_count) return {};
    const std::vector<uint8_t> data = read_accessor(asset, set->get<int>());
    const uint64_t element = element_size(a.type, a.component_type);
    std::vector<double> uv(2 * a.count);
    for (uint64_t v = 0; v < a.count; ++v) {
        for (int c = 0; c < 2; ++c) {
            uv[2 * v + c] = component_value(&data[v * element], a.component_type, a.normalized, c);
            // A set with a NaN has no seams to keep (and NaN keys would break the weld's map).
            if (!std::isfinite(uv[2 * v + c])) return {};
        }
    }
    return uv;
}

// The geometry under a linear map (raps_parameterize ignores a mesh's transform). A mirroring
// map is mirrored back, so that triangles keep the winding, and uvs the side, they had.
GroupGeometry shaped(const GroupGeometry& g, const Linear3& m) {
    const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                       m[2] * (m[3] * m[7] - m[4] * m[6]);
    const double flip = det < 0 ? -1 : 1;
    GroupGeometry out = g;
    for (size_t v = 0; v + 2 < g.xyz.size(); v += 3) {
        const double* p = &g.xyz[v];
        out.xyz[v] = flip * (m[0] * p[0] + m[1] * p[1] + m[2] * p[2]);
        out.xyz[v + 1] = m[3] * p[0] + m[4] * p[1] + m[5] * p[2];
        out.xyz[v + 2] = m[6] * p[0] + m[7] * p[1] + m[8] * p[2];
    }
    return out;
}

// The library refuses coordinates past 1e30 (its products of coordinates must stay finite). A
// map does not depend on the mesh's scale (at a density, once the density follows), so a mesh
// that large is scaled by 2^-k: exact, every ratio, hence every uv, kept. Returns k (0: none).
// `reach` bounds how far the mesh's transform moves a coordinate (1 without one).
double largest_coordinate(const GroupGeometry& g, double reach = 1) {
    double largest = 0;
    for (double c : g.xyz) largest = std::max(largest, std::fabs(c));
    return largest * reach;
}

int scaled_exponent(double largest) {
    return largest > 1e24 ? std::ilogb(largest) - 60 : 0;
}

GroupGeometry scaled(const GroupGeometry& g, int k) {
    GroupGeometry out = g;
    for (double& c : out.xyz) c = std::ldexp(c, -k);
    return out;
}

// A primitive's vertex -> library vertex (-1 until given): an array over the accessor when the
// primitive uses much of it, a hash map when it uses little.
class LocalIds {
  public:
    LocalIds(uint64_t vertex_count, size_t corners)
        : dense_(corners >= vertex_count / 4 ? vertex_count : 0, -1) {}
    int64_t& of(uint32_t v) {
        return dense_.empty() ? sparse_.emplace(v, -1).first->second : dense_[v];
    }

  private:
    std::vector<int64_t> dense_;
    std::unordered_map<uint32_t, int64_t> sparse_;
};

}  // namespace

GroupGeometry group_geometry(const Asset& asset, const std::vector<PrimitiveInput>& group,
                             bool weld_by_uv) {
    GroupGeometry g;
    for (const PrimitiveInput& p : group) {
        const int position = (*p.json)["attributes"]["POSITION"].get<int>();
        const AccessorLayout pa = accessor_layout(asset.doc, position);
        // Read at the corners only: primitives may each use a few vertices of one large
        // accessor (1000 such primitives of a 251001-vertex accessor: 10 s of copies before).
        const std::vector<uint8_t> data = read_accessor_at(asset, position, p.triangles);
        const uint64_t element = element_size("VEC3", pa.component_type);
        const std::vector<double> uv = weld_by_uv ? texcoord0(asset, p) : std::vector<double>();
        LocalIds local(p.vertex_count, p.triangles.size());
        std::map<WeldKey, uint32_t> welded;
        g.first_triangle.push_back(g.indices.size() / 3);
        for (size_t k = 0; k < p.triangles.size(); ++k) {
            const uint32_t v = p.triangles[k];
            int64_t& id = local.of(v);
            if (id < 0) {
                WeldKey key{};
                for (int c = 0; c < 3; ++c) {
                    key[c] =
                        component_value(&data[k * element], pa.component_type, pa.normalized, c);
                }
                if (!uv.empty()) key = {key[0], key[1], key[2], uv[2 * v], uv[2 * v + 1]};
                const uint32_t next = static_cast<uint32_t>(g.xyz.size() / 3);
                const auto found = weld_by_uv ? welded.emplace(key, next).first : welded.end();
                id = found != welded.end() ? found->second : next;
                if (id == next) g.xyz.insert(g.xyz.end(), key.begin(), key.begin() + 3);
            }
            g.indices.push_back(static_cast<uint32_t>(id));
        }
        g.input_vertices += p.vertex_count;
    }
    g.first_triangle.push_back(g.indices.size() / 3);
    return g;
}

double surface_area(const GroupGeometry& g, const Linear3& m) {
    auto at = [&](uint32_t v) {
        const double* p = &g.xyz[3 * size_t(v)];
        return std::array<double, 3>{m[0] * p[0] + m[1] * p[1] + m[2] * p[2],
                                     m[3] * p[0] + m[4] * p[1] + m[5] * p[2],
                                     m[6] * p[0] + m[7] * p[1] + m[8] * p[2]};
    };
    double area = 0;
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3) {
        const auto a = at(g.indices[t]), b = at(g.indices[t + 1]), c = at(g.indices[t + 2]);
        const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double f[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
                             e[0] * f[1] - e[1] * f[0]};
        area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    return area;
}

GroupMap map_group(const GroupGeometry& geometry, const Linear3* shape, const BakeOptions& options,
                   const std::string& label, GroupReport* report) {
    std::optional<GroupGeometry> moved;
    if (shape) moved = shaped(geometry, *shape);
    const int k = scaled_exponent(largest_coordinate(moved ? *moved : geometry));
    if (k != 0) moved = scaled(moved ? *moved : geometry, k);
    RunHandles h;
    ProgressContext progress{&options, label};
    prepare_run(options, &progress, &h, std::ldexp(1.0, -k));
    MeshHandle mesh;
    load_mesh(moved ? *moved : geometry, nullptr, label, &mesh);
    report->input_vertices = geometry.input_vertices;
    report->triangles = geometry.indices.size() / 3;
    const auto start = std::chrono::steady_clock::now();
    if (raps_parameterize(mesh.mesh, h.settings, h.result) != RAPS_OK) {
        throw GltfError("raps", label + ": " + raps_result_last_error(h.result));
    }
    report->total_ms = elapsed_ms(start);
    read_figures(h.result, &report->stats, report->phase_ms);
    report->stats.texels_per_unit = std::ldexp(report->stats.texels_per_unit, -k);
    GroupMap map = slice(h.result, copy_result(h.result, label), 0, geometry);
    map.page = page_of(h.result, map);
    map.page_width = report->stats.atlas_width;
    map.page_height = report->stats.atlas_height;
    return map;
}

std::vector<GroupMap> map_scene(const std::vector<const GroupGeometry*>& geometries,
                                const std::vector<Linear3>& transforms, const BakeOptions& options,
                                SceneReport* report) {
    // One scale for the whole scene (scaled_exponent), from the farthest world coordinate.
    double largest = 0;
    for (size_t i = 0; i < geometries.size(); ++i) {
        const Linear3& m = transforms[i];
        double reach = 0;
        for (int r = 0; r < 3; ++r)
            reach = std::max(
                reach, std::fabs(m[3 * r]) + std::fabs(m[3 * r + 1]) + std::fabs(m[3 * r + 2]));
        largest = std::max(largest, largest_coordinate(*geometries[i], reach));
    }
    const int k = scaled_exponent(largest);
    RunHandles h;
    ProgressContext progress{&options, "scene"};
    prepare_run(options, &progress, &h, std::ldexp(1.0, -k));
    std::vector<std::unique_ptr<MeshHandle>> meshes;
    std::vector<const raps_mesh*> pointers;
    for (size_t i = 0; i < geometries.size(); ++i) {
        meshes.push_back(std::make_unique<MeshHandle>());
        load_mesh(k ? scaled(*geometries[i], k) : *geometries[i], &transforms[i],
                  "scene mesh " + std::to_string(i), meshes.back().get());
        pointers.push_back(meshes.back()->mesh);
    }
    const auto start = std::chrono::steady_clock::now();
    if (raps_parameterize_scene(pointers.data(), pointers.size(), h.settings, h.result) !=
        RAPS_OK) {
        throw GltfError("raps", std::string("scene: ") + raps_result_last_error(h.result));
    }
    report->total_ms = elapsed_ms(start);
    read_figures(h.result, &report->stats, report->phase_ms);
    report->stats.texels_per_unit = std::ldexp(report->stats.texels_per_unit, -k);
    report->charts.resize(report->stats.chart_count);
    for (size_t c = 0; c < report->charts.size(); ++c) {
        report->charts[c].struct_size = sizeof(raps_chart);
        raps_result_get_chart(h.result, c, &report->charts[c]);
        report->charts[c].area_3d = std::ldexp(report->charts[c].area_3d, 2 * k);
    }
    const WholeResult whole = copy_result(h.result, "scene");
    std::vector<GroupMap> maps;
    for (size_t i = 0; i < geometries.size(); ++i) {
        maps.push_back(slice(h.result, whole, i, *geometries[i]));
        maps.back().page = page_of(h.result, maps.back());
        maps.back().page_width = report->stats.atlas_width;
        maps.back().page_height = report->stats.atlas_height;
    }
    return maps;
}

}  // namespace raps_gltf
