// One primitive's new accessors: its share of its group's map (output vertices, uvs, triangles)
// and every vertex attribute and morph target delta gathered through that vertex map. The new
// TEXCOORD_n is written as texcoord_encoding.h says, v flipped to glTF's top-left origin.
// Accessors are never changed in place: the edited primitive points at new ones, so accessors
// shared with other meshes keep their data.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gltf_accessor_writer.h"
#include "gltf_bake.h"
#include "gltf_library_map.h"
#include "gltf_primitive_select.h"

namespace raps_gltf {

std::string texcoord_name(int set);

// One primitive's share of a group's map: its output vertices (numbered by first use, each a
// copy of one of the primitive's own vertices), their uvs and its triangles. An output vertex
// that stands for several of the primitive's vertices (welded along kept uv seams) is split
// again, one copy per vertex, so that every other attribute keeps its value.
struct PrimitiveShare {
    std::vector<uint32_t> vertex_of, indices;
    std::vector<float> uv;  // glTF's convention: origin at the image's top-left corner
};

// Primitive i of its group (input p).
PrimitiveShare share_of(const GroupMap& map, const PrimitiveInput& p, size_t i,
                        PreviewGeometry* preview);

// Writes one primitive's new accessors; returns the members its JSON gets (attributes, targets,
// indices, mode). Adds the primitive's new geometry to the preview.
Json write_primitive(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                     const PrimitiveInput& p, const PrimitiveShare& share, const GroupMap& map,
                     PrimitiveReport* pr, GroupReport* report, PreviewGeometry* preview);

}  // namespace raps_gltf
