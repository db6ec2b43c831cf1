#include "gltf_bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <unordered_map>

#include "gltf_accessor_writer.h"
#include "gltf_accessors.h"
#include "gltf_error.h"
#include "gltf_library_map.h"
#include "gltf_primitive_select.h"
#include "tangent_frames.h"

namespace raps_gltf {

namespace {

std::string texcoord_name(int set) {
    return "TEXCOORD_" + std::to_string(set);
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

// One primitive's share of a group's map: its output vertices (numbered by first use, each a
// copy of one of the primitive's own vertices), their uvs and its triangles. An output vertex
// that stands for several of the primitive's vertices (welded along kept uv seams) is split
// again, one copy per vertex, so that every other attribute keeps its value.
struct PrimitiveShare {
    std::vector<uint32_t> vertex_of, indices;
    std::vector<float> uv;  // glTF's convention: origin at the image's top-left corner
};

PrimitiveShare share_of(const GroupMap& map, const PrimitiveInput& p, size_t i,
                        PreviewGeometry* preview) {
    PrimitiveShare share;
    std::unordered_map<uint64_t, uint32_t> local;  // (output vertex, input vertex) -> new vertex
    const size_t first = map.first_triangle[i];
    for (size_t t = first; t < map.first_triangle[i + 1]; ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t o = map.indices[3 * t + k];
            const uint32_t v = p.triangles[3 * (t - first) + k];
            const auto added = local.emplace((uint64_t(o) << 32) | v,
                                             static_cast<uint32_t>(share.vertex_of.size()));
            if (added.second) {
                share.vertex_of.push_back(v);
                // raps puts v up; glTF's uv origin is the image's top-left corner.
                share.uv.push_back(static_cast<float>(map.uv[2 * o]));
                share.uv.push_back(static_cast<float>(1.0 - map.uv[2 * o + 1]));
            }
            share.indices.push_back(added.first->second);
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

// The input's accessors read at a primitive's output vertices, each accessor once.
class GatheredAttributes {
  public:
    GatheredAttributes(const Asset& asset, const std::vector<uint32_t>& vertex_of)
        : asset_(asset), vertex_of_(vertex_of) {}
    const std::vector<uint8_t>& bytes(int accessor) {
        auto it = gathered_.find(accessor);
        if (it == gathered_.end()) {
            const AccessorLayout a = accessor_layout(asset_.doc, accessor);
            it = gathered_
                     .emplace(accessor, gather(read_accessor(asset_, accessor),
                                               element_size(a.type, a.component_type), vertex_of_))
                     .first;
        }
        return it->second;
    }
    std::vector<float> floats(int accessor) {
        return as_floats(bytes(accessor), accessor_layout(asset_.doc, accessor));
    }

  private:
    const Asset& asset_;
    const std::vector<uint32_t>& vertex_of_;
    std::map<int, std::vector<uint8_t>> gathered_;
};

// Everything one primitive's accessors are written with.
struct PrimitiveWrite {
    const Asset& asset;
    const BakeOptions& options;
    AccessorWriter& writer;
    const PrimitiveInput& input;
    const PrimitiveShare& share;
    GatheredAttributes gathered;
};

int write_texcoords(PrimitiveWrite& w, const GroupMap& map, PrimitiveReport* pr,
                    double* error_texels) {
    const EncodedTexcoords uv =
        encode_texcoords(w.share.uv, w.options.uv_format, map.page_width, map.page_height);
    *error_texels = std::max(*error_texels, uv.max_error_texels);
    pr->texcoord_component_type = uv.component_type;
    const Json like = uv.normalized ? Json{{"normalized", true}} : Json::object();
    return w.writer.add(like, "VEC2", uv.component_type, w.share.vertex_of.size(), uv.bytes, true,
                        true);
}

int copy_attribute(PrimitiveWrite& w, const std::string& name, int accessor) {
    const Json& like = w.asset.doc["accessors"][static_cast<size_t>(accessor)];
    return w.writer.copy(w.asset, accessor, w.share.vertex_of, w.gathered.bytes(accessor),
                         name == "POSITION" || like.contains("min") || like.contains("max"));
}

// New tangent frames for the new uvs (tangent_frames.h), in an accessor like the old one.
int write_generated_tangents(PrimitiveWrite& w, const Json& old_attributes, int old_tangents) {
    const std::vector<float> frames = tangent_frames(
        w.gathered.floats(old_attributes["POSITION"].get<int>()),
        w.gathered.floats(old_attributes["NORMAL"].get<int>()), w.share.uv, w.share.indices);
    std::vector<uint8_t> bytes(frames.size() * sizeof(float));
    std::memcpy(bytes.data(), frames.data(), bytes.size());
    return w.writer.add(w.asset.doc["accessors"][static_cast<size_t>(old_tangents)], "VEC4", kFloat,
                        w.share.vertex_of.size(), bytes, true, false);
}

// The primitive's attributes, the new set among them; lower sets it lacks get the new uvs too
// (the specification's continuity rule: TEXCOORD_0 .. TEXCOORD_{n-1} must exist), as
// glTF-Transform's unwrap does.
Json write_attributes(PrimitiveWrite& w, int uv_accessor, PrimitiveReport* pr) {
    const std::string set_name = texcoord_name(w.options.texcoord);
    const Json& old_attributes = (*w.input.json)["attributes"];
    Json attributes = Json::object();
    for (auto it = old_attributes.begin(); it != old_attributes.end(); ++it) {
        if (it.key() == set_name) {
            attributes[it.key()] = uv_accessor;
        } else if (it.key() == "TANGENT" && w.input.tangents == TangentPolicy::kDrop) {
            pr->tangents_dropped = true;
        } else if (it.key() == "TANGENT" && w.input.tangents == TangentPolicy::kGenerate) {
            attributes[it.key()] =
                write_generated_tangents(w, old_attributes, it.value().get<int>());
            pr->tangents_generated = true;
        } else {
            attributes[it.key()] = copy_attribute(w, it.key(), it.value().get<int>());
        }
    }
    if (!attributes.contains(set_name)) attributes[set_name] = uv_accessor;
    for (int s = 0; s <= w.options.texcoord; ++s) {
        if (!attributes.contains(texcoord_name(s))) attributes[texcoord_name(s)] = uv_accessor;
        if (attributes[texcoord_name(s)] == uv_accessor) pr->texcoord_sets.push_back(s);
    }
    for (auto it = attributes.begin(); it != attributes.end(); ++it)
        pr->attributes.push_back(it.key());
    return attributes;
}

// Morph targets at the output vertices. Deltas of a rewritten uv set or of replaced tangents
// mean nothing now.
Json write_targets(PrimitiveWrite& w, PrimitiveReport* pr) {
    const std::string set_name = texcoord_name(w.options.texcoord);
    Json targets = Json::array();
    for (const Json& target : (*w.input.json)["targets"]) {
        Json out = Json::object();
        for (auto it = target.begin(); it != target.end(); ++it) {
            if ((it.key() == "TANGENT" && w.input.tangents != TangentPolicy::kKeep) ||
                it.key() == set_name)
                continue;
            out[it.key()] = copy_attribute(w, it.key(), it.value().get<int>());
        }
        targets.push_back(out);
    }
    pr->targets = static_cast<int>(targets.size());
    return targets;
}

void add_to_preview(PrimitiveWrite& w, PreviewGeometry* preview) {
    const std::vector<float> xyz =
        w.gathered.floats((*w.input.json)["attributes"]["POSITION"].get<int>());
    const uint32_t base = static_cast<uint32_t>(preview->positions.size() / 3);
    preview->positions.insert(preview->positions.end(), xyz.begin(), xyz.end());
    preview->uvs.insert(preview->uvs.end(), w.share.uv.begin(), w.share.uv.end());
    for (uint32_t k : w.share.indices) preview->indices.push_back(base + k);
}

// Writes one primitive's new accessors; returns the members its JSON gets (attributes, targets,
// indices, mode).
Json write_primitive(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                     const PrimitiveInput& p, const PrimitiveShare& share, const GroupMap& map,
                     PrimitiveReport* pr, GroupReport* report, PreviewGeometry* preview) {
    PrimitiveWrite w{asset, options, writer, p, share, GatheredAttributes(asset, share.vertex_of)};
    Json edit = Json::object();
    edit["attributes"] =
        write_attributes(w, write_texcoords(w, map, pr, &report->uv_error_texels), pr);
    if (p.json->contains("targets")) edit["targets"] = write_targets(w, pr);
    pr->unnormalized_weights =
        unnormalized_weights(asset, (*p.json)["attributes"], share.vertex_of);
    edit["indices"] =
        write_indices(writer, share.indices, share.vertex_of.size(), &pr->index_component_type);
    if (p.json->contains("mode") || p.mode != 4) edit["mode"] = 4;
    add_to_preview(w, preview);
    pr->output_vertices = share.vertex_of.size();
    return edit;
}

void merge_into(Json& primitive, const Json& edit) {
    for (auto it = edit.begin(); it != edit.end(); ++it) primitive[it.key()] = it.value();
}

std::string figures(const std::vector<double>& values) {
    std::string out;
    for (double v : values) {
        char text[32];
        std::snprintf(text, sizeof(text), "%s%.6g", out.empty() ? "" : ", ", v);
        out += text;
    }
    return out;
}

void add_scene_notes(BakeResult& result) {
    const SceneReport& scene = result.scene;
    if (!scene.enabled) return;
    if (scene.scene_implied && scene.scene >= 0) {
        result.notes.push_back("the asset names no default scene: scene 0 was read");
    }
    for (const SceneMeshReport& m : scene.meshes) {
        if (m.scales.size() > 1) {
            result.notes.push_back("mesh " + std::to_string(m.mesh) + " is drawn at " +
                                   std::to_string(m.scales.size()) + " scales (" +
                                   figures(m.scales) + "): packed at the largest, " +
                                   figures({m.scale}) + ", so no instance gets fewer texels");
        }
        if (m.skinned) {
            result.notes.push_back("mesh " + std::to_string(m.mesh) +
                                   " is skinned: placed by its bind pose (joint 0's world "
                                   "matrix times its inverse bind matrix)");
        }
    }
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
    add_scene_notes(result);
    if (options.texcoord > 0) {
        result.notes.push_back(texcoord_name(options.texcoord) +
                               " is referenced by no material yet: gltfpack drops such "
                               "sets unless run with -kv");
    }
}

// Groups whose primitives read the same accessors the same way get the same new accessors.
std::string group_key(const std::vector<PrimitiveInput>& group) {
    Json key = Json::array();
    for (const PrimitiveInput& p : group) {
        key.push_back({p.mode, p.json->value("indices", Json()), (*p.json)["attributes"],
                       p.json->value("targets", Json()), int(p.tangents)});
    }
    return key.dump();
}

// A group baked once, whose edits later groups defined alike take.
struct Done {
    size_t group;
    std::vector<Json> edits;
    std::vector<size_t> primitive_reports;
};

GroupReport group_report(const Json& doc, int mesh, const std::vector<PrimitiveInput>& group) {
    GroupReport report;
    report.mesh = mesh;
    report.mesh_name = array_of(doc, "meshes")[mesh].value("name", std::string());
    for (const PrimitiveInput& p : group) report.primitives.push_back(p.index);
    return report;
}

std::string group_label(const GroupReport& report) {
    return "mesh " + std::to_string(report.mesh) +
           (report.mesh_name.empty() ? std::string() : " '" + report.mesh_name + "'");
}

// The group takes the edits of the first group defined alike.
void reuse_group(const Done& first, const std::vector<PrimitiveInput>& group, GroupReport report,
                 BakeResult& result) {
    const GroupReport& first_report = result.groups[first.group];
    report.input_vertices = first_report.input_vertices;
    report.output_vertices = first_report.output_vertices;
    report.triangles = first_report.triangles;
    report.stats = first_report.stats;
    report.page = first_report.page;
    report.uv_error_texels = first_report.uv_error_texels;
    report.reused_from_mesh = first_report.mesh;
    Json& out_primitives = result.doc["meshes"][report.mesh]["primitives"];
    for (size_t i = 0; i < group.size(); ++i) {
        merge_into(out_primitives[group[i].index], first.edits[i]);
        PrimitiveReport pr = result.primitives[first.primitive_reports[i]];
        pr.mesh = report.mesh;
        pr.primitive = group[i].index;
        result.primitives.push_back(pr);
    }
    result.baked_triangles += report.triangles;
    result.preview_of_group.push_back(result.preview_of_group[first.group]);
    result.groups.push_back(report);
}

// Writes the group's primitives from its map; returns what a group defined alike reuses.
Done write_group(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                 const std::vector<PrimitiveInput>& group, const GroupMap& map, GroupReport report,
                 BakeResult& result) {
    PreviewGeometry preview;
    preview.mesh = report.mesh;
    preview.atlas_width = map.page_width;
    preview.atlas_height = map.page_height;
    report.page = map.page;
    Done done{result.groups.size(), {}, {}};
    Json& out_primitives = result.doc["meshes"][report.mesh]["primitives"];
    for (size_t i = 0; i < group.size(); ++i) {
        const PrimitiveInput& p = group[i];
        PrimitiveReport pr;
        pr.mesh = report.mesh;
        pr.primitive = p.index;
        pr.input_mode = p.mode;
        pr.input_vertices = p.vertex_count;
        pr.triangles = map.first_triangle[i + 1] - map.first_triangle[i];
        const PrimitiveShare share = share_of(map, p, i, &preview);
        const Json edit =
            write_primitive(asset, options, writer, p, share, map, &pr, &report, &preview);
        merge_into(out_primitives[p.index], edit);
        done.edits.push_back(edit);
        report.output_vertices += pr.output_vertices;
        done.primitive_reports.push_back(result.primitives.size());
        result.primitives.push_back(std::move(pr));
    }
    result.baked_triangles += report.triangles;
    result.preview_of_group.push_back(static_cast<int>(result.preview.size()));
    result.groups.push_back(report);
    result.preview.push_back(std::move(preview));
    return done;
}

// --group mesh and --group primitive: an atlas per group.
void bake_groups(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                 BakeResult& result) {
    const Selection selection = select_primitives(asset, options, &result.skipped);
    std::map<std::string, Done> done;
    for (size_t g = 0; g < selection.groups.size(); ++g) {
        const std::vector<PrimitiveInput>& group = selection.groups[g];
        GroupReport report = group_report(asset.doc, selection.group_mesh[g], group);
        const std::string key = group_key(group);
        const auto cached = done.find(key);
        if (cached != done.end()) {
            reuse_group(cached->second, group, report, result);
            continue;
        }
        const GroupGeometry geometry = group_geometry(asset, group, options.keep_uv_seams);
        const GroupMap map = map_group(geometry, options, group_label(report), &report);
        done.emplace(key, write_group(asset, options, writer, group, map, report, result));
    }
}

// The meshes packed into a scene's atlas: one per set of groups defined alike, each at the
// largest instance of any of them.
struct ScenePacking {
    std::vector<size_t> first_group;       // per packed mesh, the group that defines it
    std::vector<int64_t> packed_of_group;  // per group, its packed mesh
    std::vector<GroupGeometry> geometries;
    std::vector<Linear3> transforms;
};

ScenePacking pack_scene_meshes(const Asset& asset, const BakeOptions& options,
                               const Selection& selection, const SceneInstances& instances,
                               SceneReport* report) {
    ScenePacking packing;
    std::map<std::string, size_t> packed_of_key;
    std::vector<std::vector<Linear3>> candidates;
    for (size_t g = 0; g < selection.groups.size(); ++g) {
        const int m = selection.group_mesh[g];
        const auto added =
            packed_of_key.emplace(group_key(selection.groups[g]), packing.first_group.size());
        if (added.second) {
            packing.first_group.push_back(g);
            packing.geometries.push_back(
                group_geometry(asset, selection.groups[g], options.keep_uv_seams));
            candidates.emplace_back();
        }
        const size_t k = added.first->second;
        packing.packed_of_group.push_back(static_cast<int64_t>(k));
        const std::vector<Linear3>& distinct = instances.meshes[m].distinct;
        candidates[k].insert(candidates[k].end(), distinct.begin(), distinct.end());
        SceneMeshReport mesh;
        mesh.mesh = m;
        mesh.instances = instances.meshes[m].instances;
        mesh.skinned = instances.meshes[m].skinned;
        if (!added.second) mesh.shares_atlas_of = selection.group_mesh[packing.first_group[k]];
        report->meshes.push_back(mesh);
    }
    for (size_t k = 0; k < packing.geometries.size(); ++k) {
        const GroupGeometry& geometry = packing.geometries[k];
        const ChosenInstance chosen = choose_instance(
            candidates[k], [&](const Linear3& t) { return surface_area(geometry, t); });
        packing.transforms.push_back(chosen.transform);
        report->packed_meshes.push_back(selection.group_mesh[packing.first_group[k]]);
        for (size_t g = 0; g < selection.groups.size(); ++g) {
            if (packing.packed_of_group[g] != static_cast<int64_t>(k)) continue;
            report->meshes[g].scale = chosen.scale;
            report->meshes[g].scales = chosen.scales;
        }
    }
    return packing;
}

// --group scene: every mesh the default scene draws in one atlas.
void bake_scene(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                BakeResult& result) {
    const SceneInstances instances = scene_instances(asset);
    SceneReport& scene = result.scene;
    scene.enabled = true;
    scene.scene = instances.scene;
    scene.scene_implied = instances.scene_implied;
    std::vector<bool> drawn;
    for (const MeshInstances& m : instances.meshes) drawn.push_back(m.drawn());
    const Selection selection = select_primitives(asset, options, &result.skipped, &drawn);
    if (selection.groups.empty()) return;
    const ScenePacking packing = pack_scene_meshes(asset, options, selection, instances, &scene);
    std::vector<const GroupGeometry*> geometries;
    for (const GroupGeometry& g : packing.geometries) geometries.push_back(&g);
    const std::vector<GroupMap> maps = map_scene(geometries, packing.transforms, options, &scene);
    std::vector<Done> done;
    for (size_t g = 0; g < selection.groups.size(); ++g) {
        const std::vector<PrimitiveInput>& group = selection.groups[g];
        GroupReport report = group_report(asset.doc, selection.group_mesh[g], group);
        const size_t k = static_cast<size_t>(packing.packed_of_group[g]);
        if (k < done.size()) {
            reuse_group(done[k], group, report, result);
            continue;
        }
        report.input_vertices = packing.geometries[k].input_vertices;
        report.triangles = packing.geometries[k].indices.size() / 3;
        report.stats = scene.stats;
        report.stats.chart_count = 0;
        for (const raps_chart& c : scene.charts) report.stats.chart_count += c.mesh == k;
        done.push_back(write_group(asset, options, writer, group, maps[k], report, result));
    }
}

// Scene atlases: each baked mesh's page and set in its extras, where an engine's importer finds
// which lightmap page to bind. Written last: inserting into a mesh object moves its members.
void write_page_extras(BakeResult& result) {
    for (const GroupReport& g : result.groups) {
        Json& mesh = result.doc["meshes"][g.mesh];
        if (mesh.contains("extras") && !mesh["extras"].is_object()) {
            result.notes.push_back("mesh " + std::to_string(g.mesh) +
                                   ": its extras are not an object; its atlas page is only in "
                                   "the report");
            continue;
        }
        mesh["extras"]["raps_atlas"] = {{"page", g.page}};
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
    AccessorWriter writer(result);
    if (options.grouping == Grouping::kScene) {
        bake_scene(asset, options, writer, result);
        write_page_extras(result);
    } else {
        bake_groups(asset, options, writer, result);
    }
    add_notes(options, result);
    return result;
}

}  // namespace raps_gltf
