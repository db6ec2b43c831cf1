// Which primitives of an asset are baked, read into triangle lists, and why the others are not.
//
// A primitive is baked when it has triangles (lists, strips or fans), POSITION, data for every
// attribute (no placeholder buffer), and at least one triangle with three distinct vertices and
// a non-zero area. Points and lines, primitives without POSITION, without data, or of degenerate
// triangles only are left as they are, with the reason. Defects the output would inherit are
// refused (GltfError): an index holding the primitive-restart value, an index past the vertex
// count, a position that is not finite, an existing texture coordinate set without --overwrite.
#pragma once

#include <cstdint>
#include <vector>

#include "gltf_bake.h"

namespace raps_gltf {

// What the rewritten set means for a primitive's TANGENT (tangents follow the uv set of the
// material's normal texture).
enum class TangentPolicy {
    kKeep,      // another set is rewritten, or the primitive has no TANGENT
    kDrop,      // renderers derive MikkTSpace tangents from the new uvs (glTF 2.0, 3.7.2.1)
    kGenerate,  // the material needs a tangent space without a normal texture to derive it from
};

struct PrimitiveInput {
    int index = 0;
    const Json* json = nullptr;
    int mode = 4;
    uint64_t vertex_count = 0;
    std::vector<uint32_t> triangles;  // primitive-local vertex ids
    TangentPolicy tangents = TangentPolicy::kKeep;
};

struct Selection {
    std::vector<std::vector<PrimitiveInput>> groups;  // each one atlas
    std::vector<int> group_mesh;
};

// Throws GltfError for a defect (see above); appends every primitive left as it is to `skipped`.
// `drawn` (--group scene): per mesh, whether the default scene draws it; the primitives of a mesh
// it does not draw are left as they are, unread.
Selection select_primitives(const Asset& asset, const BakeOptions& options,
                            std::vector<SkipReport>* skipped,
                            const std::vector<bool>* drawn = nullptr);

}  // namespace raps_gltf
