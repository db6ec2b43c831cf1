// The library's side of a bake: a group of primitives handed to raps's atlas domain as one mesh,
// alone (raps_parameterize) or with every other group of a scene (raps_parameterize_scene), and
// the map read back.
//
// A group's library mesh holds its primitives side by side, only the vertices that triangles
// use (an unused vertex would be an isolated vertex to the library). With --keep-uv-seams each
// primitive's vertices that share a position and a TEXCOORD_0 value become one library vertex,
// and the library keeps every other vertex split as a chart boundary: the seams of the asset's
// own uvs, not those of its normals or colours. Primitives never share a chart then (their
// vertices are never welded), and a primitive without TEXCOORD_0 is welded by position alone.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gltf_bake.h"
#include "gltf_primitive_select.h"
#include "scene_instances.h"

namespace raps_gltf {

struct GroupGeometry {
    std::vector<double> xyz;             // per library vertex
    std::vector<uint32_t> indices;       // three library vertices per triangle, primitives in order
    std::vector<size_t> first_triangle;  // per primitive, then the total
    uint64_t input_vertices = 0;
};

struct GroupMap {
    std::vector<size_t> first_triangle;  // per primitive, then the total
    std::vector<double> uv;              // per output vertex, v up, in [0, 1] of its page
    std::vector<uint32_t> indices;       // output vertices; corner k of triangle t copies corner
                                         // k of the group's input triangle t
    std::vector<uint32_t> charts;        // per triangle (the atlas's chart ids)
    uint32_t page = 0;
    uint64_t page_width = 0, page_height = 0;  // texels
};

GroupGeometry group_geometry(const Asset& asset, const std::vector<PrimitiveInput>& group,
                             bool weld_by_uv);

// One group, one atlas, in the group's own space or, when `shape` is given, under that linear
// map. Fills the report's stats and times.
GroupMap map_group(const GroupGeometry& geometry, const Linear3* shape, const BakeOptions& options,
                   const std::string& label, GroupReport* report);

// Every group in one atlas; transforms[i] places geometries[i] in the world. Fills the scene's
// stats, times and chart records.
std::vector<GroupMap> map_scene(const std::vector<const GroupGeometry*>& geometries,
                                const std::vector<Linear3>& transforms, const BakeOptions& options,
                                SceneReport* report);

// The mesh's surface area under a linear map.
double surface_area(const GroupGeometry& geometry, const Linear3& linear);

}  // namespace raps_gltf
