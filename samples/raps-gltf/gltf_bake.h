// The rewrite: new texture coordinates for every triangle primitive of an asset.
//
// Per group of primitives (a mesh, or one primitive with --group primitive): positions and
// triangles (strips and fans converted, non-indexed ones numbered) go to raps's atlas domain
// (gltf_library_map.h), which returns output vertices (each the copy of one input vertex, split
// along seams) and the input triangles in input order. With --group scene every mesh the default
// scene draws goes to one run of raps_parameterize_scene, at its world scale. Every vertex
// attribute and every morph target delta is then gathered through that vertex map into new
// accessors (gltf_primitive_write.h); the new TEXCOORD_n is FLOAT VEC2 (or normalized unsigned
// shorts) with v flipped to glTF's top-left origin. A mesh is processed once however many nodes
// use it, and meshes whose primitives are defined alike (same accessors) share one result.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gltf_load.h"
#include "raps.h"
#include "texcoord_encoding.h"

namespace raps_gltf {

// What shares an atlas: each mesh's primitives, each primitive alone, or every mesh the default
// scene draws (scene_instances.h), placed at its world scale.
enum class Grouping { kMesh, kPrimitive, kScene };

struct BakeOptions {
    int texcoord = 0;        // TEXCOORD_<texcoord> is written
    bool overwrite = false;  // replace a set the asset already has
    Grouping grouping = Grouping::kMesh;
    bool keep_uv_seams = false;  // the seams of TEXCOORD_0 stay chart boundaries
    UvFormat uv_format = UvFormat::kFloat32;
    const raps_settings* settings = nullptr;  // the library's settings (domain set to atlas here)
    // Called from the library's progress callback: a label ("mesh 2/5 'wheels'"), the phase and
    // its fraction. Return false to cancel.
    std::function<bool(const std::string&, raps_phase, double)> progress;
};

struct PrimitiveReport {
    int mesh = 0, primitive = 0;
    int input_mode = 4;
    uint64_t input_vertices = 0, output_vertices = 0, triangles = 0;
    int index_component_type = 0;
    int texcoord_component_type = 0;      // of the new set: FLOAT or UNSIGNED_SHORT (normalized)
    std::vector<std::string> attributes;  // as written, in order
    std::vector<int> texcoord_sets;       // sets that now hold the new uvs (continuity copies)
    bool tangents_dropped = false;        // renderers derive them from the new uvs
    bool tangents_generated = false;      // new ones for the new uvs (tangent_frames.h)
    int targets = 0;
    // Output vertices whose WEIGHTS_n (summed over the sets) do not add up to 1: the input's own
    // values, copied as they are (seam copies repeat them).
    uint64_t unnormalized_weights = 0;
};

struct GroupReport {
    int mesh = 0;
    std::string mesh_name;
    std::vector<int> primitives;
    uint64_t input_vertices = 0, output_vertices = 0, triangles = 0;
    raps_stats stats{};
    double phase_ms[RAPS_PHASE_COUNT] = {};
    double total_ms = 0;
    int reused_from_mesh = -1;   // >= 0: the same primitives were baked for that mesh
    uint32_t page = 0;           // the atlas page its charts lie on
    double uv_error_texels = 0;  // unorm16: the largest move of a coordinate, in texels
};

// --group scene: the one atlas of the default scene.
struct SceneMeshReport {
    int mesh = 0;
    int instances = 0;
    bool skinned = false;
    double scale = 1;            // the instance it was packed at: sqrt(world area / own area)
    std::vector<double> scales;  // each of its distinct instances'; more than one: the largest
                                 // taken (or a larger one of a mesh it shares its place with)
    int shares_atlas_of = -1;    // >= 0: defined alike to that mesh, packed once with it
};

struct SceneReport {
    bool enabled = false;
    int scene = -1;              // the default scene
    bool scene_implied = false;  // no `scene` member: scenes[0]
    raps_stats stats{};
    double phase_ms[RAPS_PHASE_COUNT] = {};
    double total_ms = 0;
    std::vector<raps_chart> charts;  // chart.mesh: the index into packed_meshes
    std::vector<int> packed_meshes;  // the glTF mesh of each mesh packed
    std::vector<SceneMeshReport> meshes;
};

struct SkipReport {
    int mesh = 0, primitive = 0;
    std::string reason;
};

// What the preview draws for one baked group: new vertices and triangles of all its primitives.
struct PreviewGeometry {
    int mesh = 0;
    std::vector<float> positions;  // x, y, z per vertex
    std::vector<float> uvs;        // u, v per vertex (glTF: v down)
    std::vector<uint32_t> indices;
    std::vector<uint32_t> chart_of_triangle;
    uint64_t atlas_width = 0, atlas_height = 0;
};

struct BakeResult {
    Json doc;  // the edited document
    // Bytes of the bufferViews the bake appended: doc["bufferViews"][first_new_view + k].
    size_t first_new_view = 0;
    std::vector<std::vector<uint8_t>> new_views;
    std::vector<PrimitiveReport> primitives;
    std::vector<GroupReport> groups;
    SceneReport scene;
    std::vector<SkipReport> skipped;
    std::vector<std::string> notes;
    std::vector<PreviewGeometry> preview;
    std::vector<int> preview_of_group;  // per groups[i]: its preview (shared when reused)
    uint64_t baked_triangles = 0;
};

// Throws GltfError ("texcoord_exists" without overwrite, "mesh"/"accessor" for bad geometry,
// "raps" when the library fails).
BakeResult bake(const Asset& asset, const BakeOptions& options);

}  // namespace raps_gltf
