#include "gltf_bake.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <map>

#include "gltf_accessor_writer.h"
#include "gltf_accessors.h"
#include "gltf_error.h"
#include "gltf_primitive_select.h"
#include "tangent_frames.h"

namespace raps_gltf {

namespace {

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

// Gathers the elements of `source` (dense) at `vertices`.
std::vector<uint8_t> gather(const std::vector<uint8_t>& source, uint64_t element,
                            const std::vector<uint32_t>& vertices) {
    std::vector<uint8_t> out(vertices.size() * element);
    for (size_t i = 0; i < vertices.size(); ++i)
        std::memcpy(&out[i * element], &source[uint64_t(vertices[i]) * element], element);
    return out;
}

std::vector<float> as_floats(const std::vector<uint8_t>& data, const AccessorLayout& a) {
    const int components = component_count(a.type);
    const uint64_t element = element_size(a.type, a.component_type);
    const size_t n = element ? data.size() / element : 0;
    std::vector<float> out(n * components);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < components; ++c) {
            out[i * components + c] = static_cast<float>(
                component_value(&data[i * element], a.component_type, a.normalized, c));
        }
    }
    return out;
}

// The library's atlas of one group: its primitives side by side, only vertices that triangles
// use (an unused vertex would be an isolated vertex to the library).
struct GroupMap {
    std::vector<std::pair<int, uint32_t>> source;  // per library vertex: (primitive, vertex)
    std::vector<size_t> first_triangle;            // per primitive, then the total
    std::vector<double> uv;
    std::vector<uint32_t> indices, remap, charts;
};

GroupMap map_group(const Asset& asset, const BakeOptions& options,
                   const std::vector<PrimitiveInput>& group, const std::string& label,
                   GroupReport* report) {
    GroupMap map;
    std::vector<double> xyz;
    std::vector<uint32_t> indices;
    for (size_t i = 0; i < group.size(); ++i) {
        const PrimitiveInput& p = group[i];
        const int position = (*p.json)["attributes"]["POSITION"].get<int>();
        const AccessorLayout pa = accessor_layout(asset.doc, position);
        const std::vector<uint8_t> data = read_accessor(asset, position);
        const uint64_t element = element_size("VEC3", pa.component_type);
        std::vector<int64_t> local(p.vertex_count, -1);
        map.first_triangle.push_back(indices.size() / 3);
        for (uint32_t v : p.triangles) {
            if (local[v] < 0) {
                local[v] = static_cast<int64_t>(map.source.size());
                map.source.emplace_back(int(i), v);
                for (int c = 0; c < 3; ++c) {
                    xyz.push_back(
                        component_value(&data[v * element], pa.component_type, pa.normalized, c));
                }
            }
            indices.push_back(static_cast<uint32_t>(local[v]));
        }
        report->input_vertices += p.vertex_count;
    }
    map.first_triangle.push_back(indices.size() / 3);
    report->triangles = indices.size() / 3;

    RapsHandles h;
    ProgressContext progress{&options, label};
    if (raps_mesh_create(&h.mesh) != RAPS_OK || raps_result_create(&h.result) != RAPS_OK ||
        raps_settings_clone(options.settings, &h.settings) != RAPS_OK ||
        raps_settings_set_int(h.settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS) != RAPS_OK) {
        throw GltfError("raps", "cannot create the library's handles");
    }
    if (options.progress) raps_settings_set_progress(h.settings, &forward_progress, &progress);
    if (raps_mesh_set_positions_f64(h.mesh, xyz.data(), xyz.size() / 3, 0) != RAPS_OK ||
        raps_mesh_set_indices_u32(h.mesh, indices.data(), indices.size()) != RAPS_OK) {
        throw GltfError("raps", label + ": " + raps_mesh_last_error(h.mesh));
    }
    const auto start = std::chrono::steady_clock::now();
    if (raps_parameterize(h.mesh, h.settings, h.result) != RAPS_OK) {
        throw GltfError("raps", label + ": " + raps_result_last_error(h.result));
    }
    report->total_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    for (int phase = 0; phase < RAPS_PHASE_COUNT; ++phase)
        report->phase_ms[phase] = raps_result_phase_ms(h.result, phase);
    report->stats.struct_size = sizeof(raps_stats);
    raps_result_get_stats(h.result, &report->stats);
    const size_t out_vertices = raps_result_vertex_count(h.result);
    map.uv.resize(2 * out_vertices);
    map.indices.resize(raps_result_index_count(h.result));
    map.remap.resize(out_vertices);
    map.charts.resize(map.indices.size() / 3);
    if (raps_result_copy_uvs_f64(h.result, map.uv.data(), out_vertices, 0) != RAPS_OK ||
        raps_result_copy_indices_u32(h.result, map.indices.data(), map.indices.size()) != RAPS_OK ||
        raps_result_copy_vertex_remap(h.result, map.remap.data(), out_vertices) != RAPS_OK ||
        raps_result_copy_chart_ids(h.result, map.charts.data(), map.charts.size()) != RAPS_OK) {
        throw GltfError("raps", label + ": " + raps_result_last_error(h.result));
    }
    if (map.indices.size() != indices.size()) {
        throw GltfError("internal", "the library returned another triangle count");
    }
    // The contract the gathering relies on: corner k of output triangle t is a copy of corner k
    // of input triangle t.
    for (size_t i = 0; i < indices.size(); ++i) {
        if (map.indices[i] >= out_vertices || map.remap[map.indices[i]] != indices[i]) {
            throw GltfError("internal", "the library's vertex map breaks corner order");
        }
    }
    return map;
}

// One primitive's share of a group's map: its output vertices (numbered by first use, each a
// copy of one of the primitive's own vertices), their uvs and its triangles.
struct PrimitiveShare {
    std::vector<uint32_t> vertex_of, indices;
    std::vector<float> uv;
};

PrimitiveShare share_of(const GroupMap& map, size_t i, PreviewGeometry* preview) {
    PrimitiveShare share;
    std::vector<int64_t> local(map.remap.size(), -1);
    for (size_t t = map.first_triangle[i]; t < map.first_triangle[i + 1]; ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t o = map.indices[3 * t + k];
            if (local[o] < 0) {
                local[o] = static_cast<int64_t>(share.vertex_of.size());
                share.vertex_of.push_back(map.source[map.remap[o]].second);
                // raps puts v up; glTF's uv origin is the image's top-left corner.
                share.uv.push_back(static_cast<float>(map.uv[2 * o]));
                share.uv.push_back(static_cast<float>(1.0 - map.uv[2 * o + 1]));
            }
            share.indices.push_back(static_cast<uint32_t>(local[o]));
        }
        preview->chart_of_triangle.push_back(map.charts[t]);
    }
    return share;
}

// Output vertices whose weights, summed over every WEIGHTS_n set, are not 1 (the validator's
// ACCESSOR_WEIGHTS_NON_NORMALIZED): counted for the report, never changed.
uint64_t unnormalized_weights(const Asset& asset, const Json& attributes,
                              const std::vector<uint32_t>& vertex_of) {
    std::vector<double> sum(vertex_of.size(), 0.0);
    bool any = false;
    for (auto it = attributes.begin(); it != attributes.end(); ++it) {
        if (it.key().compare(0, 8, "WEIGHTS_") != 0) continue;
        const int accessor = it.value().get<int>();
        const AccessorLayout a = accessor_layout(asset.doc, accessor);
        const std::vector<float> w = as_floats(read_accessor(asset, accessor), a);
        const int n = component_count(a.type);
        for (size_t k = 0; k < vertex_of.size(); ++k) {
            for (int c = 0; c < n; ++c) sum[k] += w[size_t(vertex_of[k]) * n + c];
        }
        any = true;
    }
    uint64_t count = 0;
    for (double s : sum) count += any && std::fabs(s - 1.0) > 1e-3;
    return count;
}

// Indices: 16-bit while every index fits below the primitive-restart value 65535.
int write_indices(AccessorWriter& writer, const std::vector<uint32_t>& indices, size_t vertices,
                  int* component_type) {
    const bool wide = vertices > 65535;
    *component_type = wide ? kUnsignedInt : kUnsignedShort;
    std::vector<uint8_t> bytes(indices.size() * (wide ? 4 : 2));
    for (size_t k = 0; k < indices.size(); ++k) {
        if (wide) {
            std::memcpy(&bytes[4 * k], &indices[k], 4);
        } else {
            const uint16_t v = static_cast<uint16_t>(indices[k]);
            std::memcpy(&bytes[2 * k], &v, 2);
        }
    }
    return writer.add(Json::object(), "SCALAR", *component_type, indices.size(), bytes, false,
                      false);
}

// Writes one primitive's new accessors; returns the members its JSON gets (attributes, targets,
// indices, mode).
Json write_primitive(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                     const PrimitiveInput& p, const PrimitiveShare& share, PrimitiveReport* pr,
                     PreviewGeometry* preview) {
    const Json& prim = *p.json;
    const std::string set_name = texcoord_name(options.texcoord);
    std::vector<uint8_t> uv_bytes(share.uv.size() * sizeof(float));
    std::memcpy(uv_bytes.data(), share.uv.data(), uv_bytes.size());
    const int uv_accessor =
        writer.add(Json::object(), "VEC2", kFloat, share.vertex_of.size(), uv_bytes, true, true);

    std::map<int, std::vector<uint8_t>> gathered;  // per input accessor, at the output vertices
    auto gathered_of = [&](int accessor) -> const std::vector<uint8_t>& {
        auto it = gathered.find(accessor);
        if (it == gathered.end()) {
            const AccessorLayout a = accessor_layout(asset.doc, accessor);
            it = gathered
                     .emplace(accessor,
                              gather(read_accessor(asset, accessor),
                                     element_size(a.type, a.component_type), share.vertex_of))
                     .first;
        }
        return it->second;
    };
    auto copy_attribute = [&](const std::string& name, int accessor) {
        const Json& like = asset.doc["accessors"][static_cast<size_t>(accessor)];
        return writer.copy(asset, accessor, share.vertex_of, gathered_of(accessor),
                           name == "POSITION" || like.contains("min") || like.contains("max"));
    };
    const Json& old_attributes = prim["attributes"];
    Json attributes = Json::object();
    for (auto it = old_attributes.begin(); it != old_attributes.end(); ++it) {
        if (it.key() == set_name) {
            attributes[it.key()] = uv_accessor;
        } else if (it.key() == "TANGENT" && p.tangents == TangentPolicy::kDrop) {
            pr->tangents_dropped = true;
        } else if (it.key() == "TANGENT" && p.tangents == TangentPolicy::kGenerate) {
            const int normal = old_attributes["NORMAL"].get<int>();
            const std::vector<float> frames = tangent_frames(
                as_floats(gathered_of(old_attributes["POSITION"].get<int>()),
                          accessor_layout(asset.doc, old_attributes["POSITION"].get<int>())),
                as_floats(gathered_of(normal), accessor_layout(asset.doc, normal)), share.uv,
                share.indices);
            std::vector<uint8_t> bytes(frames.size() * sizeof(float));
            std::memcpy(bytes.data(), frames.data(), bytes.size());
            attributes[it.key()] =
                writer.add(asset.doc["accessors"][it.value().get<size_t>()], "VEC4", kFloat,
                           share.vertex_of.size(), bytes, true, false);
            pr->tangents_generated = true;
        } else {
            attributes[it.key()] = copy_attribute(it.key(), it.value().get<int>());
        }
    }
    if (!attributes.contains(set_name)) attributes[set_name] = uv_accessor;
    // The specification's continuity rule: TEXCOORD_0 .. TEXCOORD_{n-1} must exist. Missing lower
    // sets get the new uvs too (as glTF-Transform's unwrap does).
    for (int s = 0; s <= options.texcoord; ++s) {
        if (!attributes.contains(texcoord_name(s))) attributes[texcoord_name(s)] = uv_accessor;
        if (attributes[texcoord_name(s)] == uv_accessor) pr->texcoord_sets.push_back(s);
    }
    for (auto it = attributes.begin(); it != attributes.end(); ++it)
        pr->attributes.push_back(it.key());

    Json edit = Json::object();
    edit["attributes"] = attributes;
    if (prim.contains("targets")) {
        Json targets = Json::array();
        for (const Json& target : prim["targets"]) {
            Json out = Json::object();
            for (auto it = target.begin(); it != target.end(); ++it) {
                // Deltas of a rewritten uv set or of replaced tangents mean nothing now.
                if ((it.key() == "TANGENT" && p.tangents != TangentPolicy::kKeep) ||
                    it.key() == set_name)
                    continue;
                out[it.key()] = copy_attribute(it.key(), it.value().get<int>());
            }
            targets.push_back(out);
        }
        pr->targets = static_cast<int>(targets.size());
        edit["targets"] = targets;
    }
    pr->unnormalized_weights = unnormalized_weights(asset, old_attributes, share.vertex_of);
    edit["indices"] =
        write_indices(writer, share.indices, share.vertex_of.size(), &pr->index_component_type);
    if (prim.contains("mode") || p.mode != 4) edit["mode"] = 4;

    const int position = old_attributes["POSITION"].get<int>();
    const std::vector<float> xyz =
        as_floats(gathered_of(position), accessor_layout(asset.doc, position));
    const uint32_t base = static_cast<uint32_t>(preview->positions.size() / 3);
    preview->positions.insert(preview->positions.end(), xyz.begin(), xyz.end());
    preview->uvs.insert(preview->uvs.end(), share.uv.begin(), share.uv.end());
    for (uint32_t k : share.indices) preview->indices.push_back(base + k);
    pr->output_vertices = share.vertex_of.size();
    return edit;
}

void merge_into(Json& primitive, const Json& edit) {
    for (auto it = edit.begin(); it != edit.end(); ++it) primitive[it.key()] = it.value();
}

void add_notes(const BakeOptions& options, BakeResult& result) {
    size_t dropped = 0, generated = 0, continuity = 0;
    uint64_t unnormalized = 0;
    for (const PrimitiveReport& p : result.primitives) {
        unnormalized += p.unnormalized_weights;
        dropped += p.tangents_dropped;
        generated += p.tangents_generated;
        continuity += p.texcoord_sets.size() > 1;
    }
    if (dropped) {
        result.notes.push_back(
            "TANGENT dropped on " + std::to_string(dropped) +
            " primitive(s): tangents follow the normal map's uv set, which was rewritten; "
            "renderers generate MikkTSpace tangents when TANGENT is absent (glTF 2.0, 3.7.2.1)");
    }
    if (generated) {
        result.notes.push_back(
            "TANGENT generated for the new uvs on " + std::to_string(generated) +
            " primitive(s) whose material needs a tangent space but has no normal texture "
            "(KHR_materials_anisotropy): per-vertex tangents, not MikkTSpace");
    }
    if (unnormalized) {
        result.notes.push_back(
            std::to_string(unnormalized) +
            " output vertices carry skin weights that do not sum to 1: the input's own values, "
            "copied unchanged (vertices split at seams repeat them, so the validator's "
            "ACCESSOR_WEIGHTS_NON_NORMALIZED count can grow; the asset is no less valid)");
    }
    if (continuity) {
        result.notes.push_back(std::to_string(continuity) + " primitive(s) lacked lower " +
                               "TEXCOORD sets; they hold the new uvs too (glTF's continuity rule)");
    }
    if (options.texcoord > 0) {
        result.notes.push_back(texcoord_name(options.texcoord) +
                               " is referenced by no material yet: gltfpack drops such "
                               "sets unless run with -kv");
    }
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
    result.first_new_view = array_of(asset.doc, "bufferViews").size();
    const Selection selection = select_primitives(asset, options, &result.skipped);
    const Json& meshes = array_of(asset.doc, "meshes");

    AccessorWriter writer(result);
    // Groups whose primitives read the same accessors the same way get the same new accessors.
    struct Done {
        size_t group;
        std::vector<Json> edits;
        std::vector<size_t> primitive_reports;
    };
    std::map<std::string, Done> done;
    for (size_t g = 0; g < selection.groups.size(); ++g) {
        const std::vector<PrimitiveInput>& group = selection.groups[g];
        const int m = selection.group_mesh[g];
        GroupReport report;
        report.mesh = m;
        report.mesh_name = meshes[m].value("name", std::string());
        Json key = Json::array();
        for (const PrimitiveInput& p : group) {
            report.primitives.push_back(p.index);
            key.push_back({p.mode, p.json->value("indices", Json()), (*p.json)["attributes"],
                           p.json->value("targets", Json()), int(p.tangents)});
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
                merge_into(out_primitives[group[i].index], first.edits[i]);
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

        const std::string label =
            "mesh " + std::to_string(m) +
            (report.mesh_name.empty() ? std::string() : " '" + report.mesh_name + "'");
        const GroupMap map = map_group(asset, options, group, label, &report);
        PreviewGeometry preview;
        preview.mesh = m;
        preview.atlas_width = report.stats.atlas_width;
        preview.atlas_height = report.stats.atlas_height;
        std::vector<Json> edits;
        std::vector<size_t> primitive_reports;
        for (size_t i = 0; i < group.size(); ++i) {
            const PrimitiveInput& p = group[i];
            PrimitiveReport pr;
            pr.mesh = m;
            pr.primitive = p.index;
            pr.input_mode = p.mode;
            pr.input_vertices = p.vertex_count;
            pr.triangles = map.first_triangle[i + 1] - map.first_triangle[i];
            const PrimitiveShare share = share_of(map, i, &preview);
            const Json edit = write_primitive(asset, options, writer, p, share, &pr, &preview);
            merge_into(out_primitives[p.index], edit);
            edits.push_back(edit);
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
    add_notes(options, result);
    return result;
}

}  // namespace raps_gltf
