#include "gltf_bake.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>

#include "gltf_accessors.h"
#include "gltf_error.h"

namespace raps_gltf {

namespace {

const char* kModeNames[] = {"points",    "lines",          "line loop",   "line strip",
                            "triangles", "triangle strip", "triangle fan"};

std::string texcoord_name(int set) {
    return "TEXCOORD_" + std::to_string(set);
}

struct RapsHandles {
    raps_mesh* mesh = nullptr;
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    ~RapsHandles() {
        raps_result_destroy(result);
        raps_settings_destroy(settings);
        raps_mesh_destroy(mesh);
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

// glTF 2.0 section 3.7.2.1: triangle i of a strip is (i, i+1+i%2, i+2-i%2), of a fan
// (i+1, i+2, 0), so that every triangle keeps the strip's or fan's winding.
std::vector<uint32_t> triangle_list(int mode, const std::vector<uint32_t>& v) {
    std::vector<uint32_t> out;
    if (v.size() < 3) return out;
    if (mode == 4) {
        out.assign(v.begin(), v.begin() + (v.size() / 3) * 3);
    } else if (mode == 5) {
        for (size_t i = 0; i + 2 < v.size(); ++i) {
            out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
        }
    } else if (mode == 6) {
        for (size_t i = 0; i + 2 < v.size(); ++i) out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
    return out;
}

// The primitive's material's normal texture set: tangents belong to that uv set, so they stay
// valid when another set is written.
int normal_texcoord(const Json& doc, const Json& primitive) {
    const auto m = primitive.find("material");
    if (m == primitive.end() || !m->is_number_unsigned()) return 0;
    const auto materials = doc.find("materials");
    if (materials == doc.end() || m->get<uint64_t>() >= materials->size()) return 0;
    const Json& material = (*materials)[m->get<size_t>()];
    const auto normal = material.find("normalTexture");
    if (!material.is_object() || normal == material.end() || !normal->is_object()) return 0;
    const auto set = normal->find("texCoord");
    return set != normal->end() && set->is_number_unsigned() ? set->get<int>() : 0;
}

struct PrimitiveInput {
    int index = 0;
    const Json* json = nullptr;
    int mode = 4;
    uint64_t vertex_count = 0;
    std::vector<uint32_t> triangles;  // primitive-local vertex ids
    bool drop_tangents = false;
};

// Appends a new accessor (and its own bufferView) holding `data` laid out tightly, padded to a
// 4-byte stride for vertex attributes as glTF requires. `like` is the accessor whose members
// (name, normalized, extensions, extras) the new one keeps.
class AccessorWriter {
  public:
    explicit AccessorWriter(BakeResult& result) : result_(result) {}

    int add(const Json& like, const std::string& type, int component_type, uint64_t count,
            const std::vector<uint8_t>& data, bool vertex_attribute, bool with_min_max) {
        const uint64_t element = element_size(type, component_type);
        const uint64_t stride = vertex_attribute ? (element + 3) / 4 * 4 : element;
        std::vector<uint8_t> bytes(stride * count, 0);
        for (uint64_t i = 0; i < count; ++i)
            std::memcpy(&bytes[i * stride], &data[i * element], element);
        Json view = Json::object();
        view["buffer"] = 0;  // the writer lays out every bufferView in its one output buffer
        view["byteLength"] = bytes.size();
        if (stride != element) view["byteStride"] = stride;
        view["target"] = vertex_attribute ? 34962 : 34963;
        Json& views = result_.doc["bufferViews"];
        if (!views.is_array()) views = Json::array();
        views.push_back(view);
        result_.new_views.push_back(std::move(bytes));

        Json accessor = Json::object();
        accessor["bufferView"] = views.size() - 1;
        accessor["componentType"] = component_type;
        accessor["count"] = count;
        accessor["type"] = type;
        for (auto it = like.begin(); like.is_object() && it != like.end(); ++it) {
            static const char* kReplaced[] = {"bufferView", "byteOffset", "componentType",
                                              "count",      "type",       "min",
                                              "max",        "sparse"};
            bool replaced = false;
            for (const char* key : kReplaced) replaced = replaced || it.key() == key;
            if (!replaced) accessor[it.key()] = it.value();
        }
        if (with_min_max) {
            Json lo, hi;
            min_max(data, type, component_type, &lo, &hi);
            accessor["min"] = lo;
            accessor["max"] = hi;
        }
        Json& accessors = result_.doc["accessors"];
        if (!accessors.is_array()) accessors = Json::array();
        accessors.push_back(accessor);
        return static_cast<int>(accessors.size() - 1);
    }

  private:
    BakeResult& result_;
};

// Gathers the elements of `source` (dense) at `vertices`.
std::vector<uint8_t> gather(const std::vector<uint8_t>& source, uint64_t element,
                            const std::vector<uint32_t>& vertices) {
    std::vector<uint8_t> out(vertices.size() * element);
    for (size_t i = 0; i < vertices.size(); ++i)
        std::memcpy(&out[i * element], &source[uint64_t(vertices[i]) * element], element);
    return out;
}

}  // namespace

BakeResult bake(const Asset& asset, const BakeOptions& options) {
    BakeResult result;
    result.doc = asset.doc;
    // The AccessorWriter appends to these two arrays. Creating them now means no later insertion
    // into the top-level object can reallocate its members, which an ordered_json copies (its keys
    // are const) and frees, under the references into result.doc taken below (found by fuzzing:
    // an asset without "bufferViews", every accessor zero-filled).
    for (const char* key : {"bufferViews", "accessors"}) {
        if (!result.doc.contains(key)) result.doc[key] = Json::array();
    }
    const Json& doc = asset.doc;
    const tinygltf::Model& model = asset.model;
    result.first_new_view = doc.contains("bufferViews") ? doc["bufferViews"].size() : 0;
    const std::string set_name = texcoord_name(options.texcoord);
    const Json no_meshes = Json::array();
    const Json& meshes = doc.contains("meshes") ? doc["meshes"] : no_meshes;

    // Pass 1: which primitives are baked; refuse before any work when a set would be replaced
    // without --overwrite.
    std::vector<std::vector<PrimitiveInput>> groups;
    std::vector<int> group_mesh;
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Json& primitives = meshes[m]["primitives"];
        std::vector<PrimitiveInput> mesh_group;
        for (size_t p = 0; p < primitives.size(); ++p) {
            const Json& prim = primitives[p];
            const int mode = prim.contains("mode") ? prim["mode"].get<int>() : 4;
            const std::string where =
                "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            if (mode < 4) {
                result.skipped.push_back(
                    {int(m), int(p), std::string(kModeNames[mode]) + " primitive left as it is"});
                continue;
            }
            const Json& attributes = prim["attributes"];
            if (!attributes.contains("POSITION")) {
                result.skipped.push_back(
                    {int(m), int(p), "no POSITION attribute: nothing to bake"});
                continue;
            }
            if (attributes.contains(set_name) && !options.overwrite) {
                throw GltfError("texcoord_exists",
                                where + " already has " + set_name +
                                    "; pass --overwrite to replace it, or --texcoord N to write "
                                    "another set");
            }
            PrimitiveInput input;
            input.index = static_cast<int>(p);
            input.json = &prim;
            input.mode = mode;
            const int position = attributes["POSITION"].get<int>();
            const tinygltf::Accessor& pa = model.accessors[position];
            input.vertex_count = pa.count;
            if (type_name(pa.type) != "VEC3" ||
                (pa.componentType != kFloat && component_size(pa.componentType) > 2)) {
                throw GltfError("accessor", where +
                                                ": POSITION must be VEC3 (float, or "
                                                "KHR_mesh_quantization integers)");
            }
            std::vector<uint32_t> vertices;
            if (prim.contains("indices")) {
                const int ia = prim["indices"].get<int>();
                const tinygltf::Accessor& a = model.accessors[ia];
                if (type_name(a.type) != "SCALAR" ||
                    (a.componentType != kUnsignedByte && a.componentType != kUnsignedShort &&
                     a.componentType != kUnsignedInt) ||
                    a.bufferView < 0) {
                    throw GltfError("accessor", where +
                                                    ": indices must be an unsigned SCALAR "
                                                    "accessor with a bufferView");
                }
                vertices = read_indices(model, ia);
                for (size_t i = 0; i < vertices.size(); ++i) {
                    if (vertices[i] >= input.vertex_count) {
                        throw GltfError("accessor", where + ": index " + std::to_string(i) +
                                                        " is " + std::to_string(vertices[i]) +
                                                        ", past the vertex count " +
                                                        std::to_string(input.vertex_count));
                    }
                }
            } else {
                vertices.resize(input.vertex_count);
                for (uint32_t i = 0; i < vertices.size(); ++i) vertices[i] = i;
            }
            input.triangles = triangle_list(mode, vertices);
            if (input.triangles.empty()) {
                result.skipped.push_back({int(m), int(p), "no complete triangle"});
                continue;
            }
            // Every position must be finite (NaN would poison the map and every min/max).
            const std::vector<uint8_t> data = read_accessor(model, position);
            const uint64_t element = element_size("VEC3", pa.componentType);
            for (uint64_t v = 0; v < pa.count; ++v) {
                for (int c = 0; c < 3; ++c) {
                    if (!std::isfinite(component_value(&data[v * element], pa.componentType,
                                                       pa.normalized, c))) {
                        throw GltfError("accessor", where + ": POSITION accessor " +
                                                        std::to_string(position) + " vertex " +
                                                        std::to_string(v) + " is not finite");
                    }
                }
            }
            input.drop_tangents =
                attributes.contains("TANGENT") && normal_texcoord(doc, prim) == options.texcoord;
            if (options.group_by_mesh) {
                mesh_group.push_back(std::move(input));
            } else {
                groups.push_back({std::move(input)});
                group_mesh.push_back(int(m));
            }
        }
        if (options.group_by_mesh && !mesh_group.empty()) {
            groups.push_back(std::move(mesh_group));
            group_mesh.push_back(int(m));
        }
    }

    AccessorWriter writer(result);
    // Groups whose primitives read the same accessors the same way get the same new accessors.
    struct Done {
        size_t group;
        std::vector<Json> edits;
        std::vector<size_t> primitive_reports;
    };
    std::map<std::string, Done> done;
    for (size_t g = 0; g < groups.size(); ++g) {
        const std::vector<PrimitiveInput>& group = groups[g];
        const int m = group_mesh[g];
        GroupReport report;
        report.mesh = m;
        report.mesh_name = meshes[m].value("name", std::string());
        Json key = Json::array();
        for (const PrimitiveInput& p : group) {
            report.primitives.push_back(p.index);
            key.push_back({p.mode, p.json->value("indices", Json()), (*p.json)["attributes"],
                           p.json->value("targets", Json()), p.drop_tangents});
        }
        Json& out_primitives = result.doc["meshes"][m]["primitives"];
        const auto cached = done.find(key.dump());
        if (cached != done.end()) {
            const Done& first = cached->second;
            const GroupReport& first_report = result.groups[first.group];
            report.input_vertices = first_report.input_vertices;
            report.output_vertices = first_report.output_vertices;
            report.triangles = first_report.triangles;
            report.stats = first_report.stats;
            report.reused_from_mesh = first_report.mesh;
            for (size_t i = 0; i < group.size(); ++i) {
                const Json& edited = first.edits[i];
                Json& prim = out_primitives[group[i].index];
                for (auto it = edited.begin(); it != edited.end(); ++it)
                    prim[it.key()] = it.value();
                PrimitiveReport pr = result.primitives[first.primitive_reports[i]];
                pr.mesh = m;
                pr.primitive = group[i].index;
                result.primitives.push_back(pr);
            }
            result.baked_triangles += report.triangles;
            result.preview_of_group.push_back(result.preview_of_group[first.group]);
            result.groups.push_back(report);
            continue;
        }

        // The library's input: the group's primitives side by side, only vertices that
        // triangles use (an unused vertex would be an isolated vertex to the library).
        std::vector<double> xyz;
        std::vector<uint32_t> indices;
        std::vector<std::pair<int, uint32_t>> source;  // per library vertex: (primitive, vertex)
        std::vector<size_t> first_triangle;
        for (size_t i = 0; i < group.size(); ++i) {
            const PrimitiveInput& p = group[i];
            const int position = (*p.json)["attributes"]["POSITION"].get<int>();
            const tinygltf::Accessor& pa = model.accessors[position];
            const std::vector<uint8_t> data = read_accessor(model, position);
            const uint64_t element = element_size("VEC3", pa.componentType);
            std::vector<int64_t> local(p.vertex_count, -1);
            first_triangle.push_back(indices.size() / 3);
            for (uint32_t v : p.triangles) {
                if (local[v] < 0) {
                    local[v] = static_cast<int64_t>(source.size());
                    source.emplace_back(int(i), v);
                    for (int c = 0; c < 3; ++c) {
                        xyz.push_back(component_value(&data[v * element], pa.componentType,
                                                      pa.normalized, c));
                    }
                }
                indices.push_back(static_cast<uint32_t>(local[v]));
            }
            report.input_vertices += p.vertex_count;
        }
        first_triangle.push_back(indices.size() / 3);
        report.triangles = indices.size() / 3;

        RapsHandles h;
        ProgressContext progress{
            &options,
            "mesh " + std::to_string(m) +
                (report.mesh_name.empty() ? std::string() : " '" + report.mesh_name + "'")};
        if (raps_mesh_create(&h.mesh) != RAPS_OK || raps_result_create(&h.result) != RAPS_OK ||
            raps_settings_clone(options.settings, &h.settings) != RAPS_OK ||
            raps_settings_set_int(h.settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS) != RAPS_OK) {
            throw GltfError("raps", "cannot create the library's handles");
        }
        if (options.progress) raps_settings_set_progress(h.settings, &forward_progress, &progress);
        if (raps_mesh_set_positions_f64(h.mesh, xyz.data(), xyz.size() / 3, 0) != RAPS_OK ||
            raps_mesh_set_indices_u32(h.mesh, indices.data(), indices.size()) != RAPS_OK) {
            throw GltfError("raps", progress.label + ": " + raps_mesh_last_error(h.mesh));
        }
        const auto start = std::chrono::steady_clock::now();
        if (raps_parameterize(h.mesh, h.settings, h.result) != RAPS_OK) {
            throw GltfError("raps", progress.label + ": " + raps_result_last_error(h.result));
        }
        report.total_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        for (int phase = 0; phase < RAPS_PHASE_COUNT; ++phase)
            report.phase_ms[phase] = raps_result_phase_ms(h.result, phase);
        report.stats.struct_size = sizeof(raps_stats);
        raps_result_get_stats(h.result, &report.stats);
        const size_t out_vertices = raps_result_vertex_count(h.result);
        std::vector<double> uv(2 * out_vertices);
        std::vector<uint32_t> out_indices(raps_result_index_count(h.result));
        std::vector<uint32_t> remap(out_vertices), charts(out_indices.size() / 3);
        raps_result_copy_uvs_f64(h.result, uv.data(), out_vertices, 0);
        raps_result_copy_indices_u32(h.result, out_indices.data(), out_indices.size());
        raps_result_copy_vertex_remap(h.result, remap.data(), out_vertices);
        raps_result_copy_chart_ids(h.result, charts.data(), charts.size());
        if (out_indices.size() != indices.size()) {
            throw GltfError("internal", "the library returned another triangle count");
        }
        // The contract the gathering relies on: corner k of output triangle t is a copy of corner
        // k of input triangle t.
        for (size_t i = 0; i < indices.size(); ++i) {
            if (out_indices[i] >= out_vertices || remap[out_indices[i]] != indices[i]) {
                throw GltfError("internal", "the library's vertex map breaks corner order");
            }
        }

        PreviewGeometry preview;
        preview.mesh = m;
        preview.atlas_width = report.stats.atlas_width;
        preview.atlas_height = report.stats.atlas_height;
        std::vector<Json> edits;
        std::vector<size_t> primitive_reports;
        for (size_t i = 0; i < group.size(); ++i) {
            const PrimitiveInput& p = group[i];
            const Json& prim = *p.json;
            PrimitiveReport pr;
            pr.mesh = m;
            pr.primitive = p.index;
            pr.input_mode = p.mode;
            pr.input_vertices = p.vertex_count;
            pr.triangles = first_triangle[i + 1] - first_triangle[i];
            // This primitive's output vertices, numbered by first use; each is a copy of one of
            // the primitive's own vertices.
            std::vector<int64_t> local(out_vertices, -1);
            std::vector<uint32_t> vertex_of, new_indices;
            std::vector<float> new_uv;
            for (size_t t = first_triangle[i]; t < first_triangle[i + 1]; ++t) {
                for (int k = 0; k < 3; ++k) {
                    const uint32_t o = out_indices[3 * t + k];
                    if (local[o] < 0) {
                        local[o] = static_cast<int64_t>(vertex_of.size());
                        vertex_of.push_back(source[remap[o]].second);
                        // raps puts v up; glTF's uv origin is the image's top-left corner.
                        new_uv.push_back(static_cast<float>(uv[2 * o]));
                        new_uv.push_back(static_cast<float>(1.0 - uv[2 * o + 1]));
                    }
                    new_indices.push_back(static_cast<uint32_t>(local[o]));
                }
                preview.chart_of_triangle.push_back(charts[t]);
            }
            pr.output_vertices = vertex_of.size();

            // The new uv set.
            std::vector<uint8_t> uv_bytes(new_uv.size() * sizeof(float));
            std::memcpy(uv_bytes.data(), new_uv.data(), uv_bytes.size());
            const int uv_accessor =
                writer.add(Json::object(), "VEC2", kFloat, vertex_of.size(), uv_bytes, true, true);

            // Every other attribute, gathered; TANGENT dropped when its uv set is rewritten.
            std::map<int, std::vector<uint8_t>> dense;
            auto copy_attribute = [&](const std::string& name, int accessor) {
                const tinygltf::Accessor& a = model.accessors[accessor];
                const std::string type = type_name(a.type);
                auto it = dense.find(accessor);
                if (it == dense.end())
                    it = dense.emplace(accessor, read_accessor(model, accessor)).first;
                const Json& like = doc["accessors"][accessor];
                return writer.add(
                    like, type, a.componentType, vertex_of.size(),
                    gather(it->second, element_size(type, a.componentType), vertex_of), true,
                    name == "POSITION" || like.contains("min") || like.contains("max"));
            };
            Json attributes = Json::object();
            const Json& old_attributes = prim["attributes"];
            for (auto it = old_attributes.begin(); it != old_attributes.end(); ++it) {
                if (it.key() == set_name) {
                    attributes[it.key()] = uv_accessor;
                } else if (it.key() == "TANGENT" && p.drop_tangents) {
                    pr.tangents_dropped = true;
                } else {
                    attributes[it.key()] = copy_attribute(it.key(), it.value().get<int>());
                }
            }
            if (!attributes.contains(set_name)) attributes[set_name] = uv_accessor;
            // The specification's continuity rule: TEXCOORD_0 .. TEXCOORD_{n-1} must exist. Missing
            // lower sets get the new uvs too (as glTF-Transform's unwrap does).
            for (int s = 0; s <= options.texcoord; ++s) {
                if (!attributes.contains(texcoord_name(s)))
                    attributes[texcoord_name(s)] = uv_accessor;
                if (attributes[texcoord_name(s)] == uv_accessor) pr.texcoord_sets.push_back(s);
            }
            for (auto it = attributes.begin(); it != attributes.end(); ++it)
                pr.attributes.push_back(it.key());

            Json edit = Json::object();
            edit["attributes"] = attributes;
            if (prim.contains("targets")) {
                Json targets = Json::array();
                for (const Json& target : prim["targets"]) {
                    Json out = Json::object();
                    for (auto it = target.begin(); it != target.end(); ++it) {
                        // Deltas of a rewritten uv set or of dropped tangents mean nothing now.
                        if ((it.key() == "TANGENT" && p.drop_tangents) || it.key() == set_name)
                            continue;
                        out[it.key()] = copy_attribute(it.key(), it.value().get<int>());
                    }
                    targets.push_back(out);
                }
                pr.targets = static_cast<int>(targets.size());
                edit["targets"] = targets;
            }
            // Indices: 16-bit while every index fits below the primitive-restart value 65535.
            const bool wide = vertex_of.size() > 65535;
            pr.index_component_type = wide ? kUnsignedInt : kUnsignedShort;
            std::vector<uint8_t> index_bytes(new_indices.size() * (wide ? 4 : 2));
            for (size_t k = 0; k < new_indices.size(); ++k) {
                if (wide) {
                    std::memcpy(&index_bytes[4 * k], &new_indices[k], 4);
                } else {
                    const uint16_t v = static_cast<uint16_t>(new_indices[k]);
                    std::memcpy(&index_bytes[2 * k], &v, 2);
                }
            }
            edit["indices"] = writer.add(Json::object(), "SCALAR", pr.index_component_type,
                                         new_indices.size(), index_bytes, false, false);
            if (prim.contains("mode") || p.mode != 4) edit["mode"] = 4;

            Json& out_prim = out_primitives[p.index];
            for (auto it = edit.begin(); it != edit.end(); ++it) out_prim[it.key()] = it.value();
            edits.push_back(edit);

            // Preview: positions of the new vertices.
            const tinygltf::Accessor& pa = model.accessors[old_attributes["POSITION"].get<int>()];
            const std::vector<uint8_t>& pdata = dense.at(old_attributes["POSITION"].get<int>());
            const uint64_t element = element_size("VEC3", pa.componentType);
            const uint32_t base = static_cast<uint32_t>(preview.positions.size() / 3);
            for (uint32_t v : vertex_of) {
                for (int c = 0; c < 3; ++c) {
                    preview.positions.push_back(static_cast<float>(
                        component_value(&pdata[v * element], pa.componentType, pa.normalized, c)));
                }
            }
            preview.uvs.insert(preview.uvs.end(), new_uv.begin(), new_uv.end());
            for (uint32_t k : new_indices) preview.indices.push_back(base + k);
            report.output_vertices += pr.output_vertices;
            primitive_reports.push_back(result.primitives.size());
            result.primitives.push_back(std::move(pr));
        }
        result.baked_triangles += report.triangles;
        done.emplace(key.dump(), Done{result.groups.size(), edits, primitive_reports});
        result.preview_of_group.push_back(static_cast<int>(result.preview.size()));
        result.groups.push_back(report);
        result.preview.push_back(std::move(preview));
    }

    size_t dropped = 0, continuity = 0;
    for (const PrimitiveReport& p : result.primitives) {
        dropped += p.tangents_dropped;
        continuity += p.texcoord_sets.size() > 1;
    }
    if (dropped) {
        result.notes.push_back(
            "TANGENT dropped on " + std::to_string(dropped) +
            " primitive(s): tangents follow the normal map's uv set, which was rewritten, and no "
            "MikkTSpace implementation is packaged in Debian; renderers generate MikkTSpace "
            "tangents when TANGENT is absent (glTF 2.0, 3.7.2.1)");
    }
    if (continuity) {
        result.notes.push_back(std::to_string(continuity) + " primitive(s) lacked lower " +
                               "TEXCOORD sets; they hold the new uvs too (glTF's continuity rule)");
    }
    if (options.texcoord > 0) {
        result.notes.push_back(set_name +
                               " is referenced by no material yet: gltfpack drops such "
                               "sets unless run with -kv");
    }
    return result;
}

}  // namespace raps_gltf
