#include "gltf_bake.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "gltf_accessor_writer.h"
#include "gltf_error.h"
#include "gltf_library_map.h"
#include "gltf_primitive_select.h"
#include "gltf_primitive_write.h"

namespace raps_gltf {

namespace {

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
    std::map<int, size_t> shrunk;  // per glTF mesh, its charts shrunk to fit a page
    for (const raps_chart& c : scene.charts) {
        if (c.flags & RAPS_CHART_SCALED_DOWN) ++shrunk[scene.packed_meshes.at(c.mesh)];
    }
    for (const auto& entry : shrunk) {
        result.notes.push_back("mesh " + std::to_string(entry.first) + ": " +
                               std::to_string(entry.second) +
                               " chart(s) shrunk to fit a page, below the atlas's density "
                               "(a larger --max-size or a smaller --texels-per-unit avoids it)");
    }
    for (const SceneMeshReport& m : scene.meshes) {
        if (m.scales.size() > 1) {
            result.notes.push_back("mesh " + std::to_string(m.mesh) + " is drawn at " +
                                   std::to_string(m.scales.size()) + " scales (" +
                                   figures(m.scales) + "): packed at the largest, " +
                                   figures({m.scale}) + ", so no instance gets fewer texels");
        }
        if (m.shares_atlas_of >= 0) {
            result.notes.push_back("mesh " + std::to_string(m.mesh) +
                                   " reads the same data as mesh " +
                                   std::to_string(m.shares_atlas_of) +
                                   ": both share one place in the atlas, packed at scale " +
                                   figures({m.scale}) + ", the largest either is drawn at");
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

// The space a group of --group mesh or primitive is mapped in: its own, unless the default
// scene draws the mesh only under maps that are not similarities (KHR_mesh_quantization's
// dequantizing scales, a stretched node), where its own uvs would be stretched in the world.
// Then the instance it covers the most surface on, rescaled to the mesh's own area, so that a
// density stays per unit of the mesh's own surface. Returns whether `shape` was set.
bool group_shape(const SceneInstances& instances, int mesh, const GroupGeometry& geometry,
                 Linear3* shape) {
    const std::vector<Linear3>& distinct = instances.meshes[mesh].distinct;
    if (distinct.empty() || std::any_of(distinct.begin(), distinct.end(), is_similarity))
        return false;
    const ChosenInstance chosen =
        choose_instance(distinct, [&](const Linear3& t) { return surface_area(geometry, t); });
    if (!(chosen.scale > 0) || !std::isfinite(chosen.scale)) return false;
    for (int i = 0; i < 9; ++i) (*shape)[i] = chosen.transform[i] / chosen.scale;
    return true;
}

// The group mapped in the space group_shape gives. A shape so uneven that the library finds no
// map at double precision (a node scaling one axis by 1e18) falls back to the mesh's own space,
// where it mapped before, and a note says so.
GroupMap map_as_drawn(const GroupGeometry& geometry, const SceneInstances& instances,
                      const BakeOptions& options, GroupReport* report, BakeResult* result) {
    const std::string label = group_label(*report);
    Linear3 shape{};
    if (!group_shape(instances, report->mesh, geometry, &shape)) {
        return map_group(geometry, nullptr, options, label, report);
    }
    try {
        return map_group(geometry, &shape, options, label, report);
    } catch (const GltfError& e) {
        if (e.kind != "raps") throw;
        result->notes.push_back(label + ": mapped in its own space: as its node draws it, " +
                                e.what());
        return map_group(geometry, nullptr, options, label, report);
    }
}

// --group mesh and --group primitive: an atlas per group.
void bake_groups(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                 BakeResult& result) {
    const Selection selection = select_primitives(asset, options, &result.skipped);
    const SceneInstances instances = scene_instances(asset);
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
        const GroupMap map = map_as_drawn(geometry, instances, options, &report, &result);
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
        const GroupGeometry& geometry = packing.geometries[k];
        mesh.scales = choose_instance(distinct, [&](const Linear3& t) {
                          return surface_area(geometry, t);
                      }).scales;
        if (!added.second) mesh.shares_atlas_of = selection.group_mesh[packing.first_group[k]];
        report->meshes.push_back(mesh);
    }
    // Groups defined alike are packed once: at the largest instance of any of them.
    for (size_t k = 0; k < packing.geometries.size(); ++k) {
        const GroupGeometry& geometry = packing.geometries[k];
        const ChosenInstance chosen = choose_instance(
            candidates[k], [&](const Linear3& t) { return surface_area(geometry, t); });
        packing.transforms.push_back(chosen.transform);
        report->packed_meshes.push_back(selection.group_mesh[packing.first_group[k]]);
        for (size_t g = 0; g < selection.groups.size(); ++g) {
            if (packing.packed_of_group[g] == static_cast<int64_t>(k))
                report->meshes[g].scale = chosen.scale;
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
