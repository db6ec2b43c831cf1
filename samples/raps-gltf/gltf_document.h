// The structure of an untrusted glTF 2.0 document, checked before any of its data is read:
// bufferViews and accessors (sparse included) inside their buffers, every index that raps-gltf
// follows or renumbers inside its array, the node hierarchy a forest (no cycle, one parent per
// node), required extensions raps-gltf can honour. What the specification allows is accepted as
// it says: accessors without a bufferView (zeros), placeholder buffers (no uri, no data),
// integers written as floats, unused accessors of a type glTF does not define. Every refusal is a
// GltfError naming the object and the defect.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gltf_json.h"

namespace raps_gltf {

// asset.version and the extensions: refuses compressed geometry raps-gltf cannot decode (see
// refused_extensions) and any required extension it does not know (a loader must not read an
// asset whose required extensions it does not support: they may change what the data means).
void check_header(const Json& doc);

// Draco-compressed primitives that carry uncompressed accessors too (the extension used, not
// required): the compressed copy is dropped from each primitive and from extensionsUsed, so the
// output's uvs and split vertices are in the only geometry left. Returns a warning per asset
// ("" if there was nothing to drop). Throws GltfError("unsupported") when such a primitive has
// no uncompressed POSITION to fall back on.
std::string drop_draco_fallback_copies(Json& doc);

// Extensions known not to refer to accessors or bufferViews by index (or whose references are
// renumbered here: EXT_mesh_gpu_instancing), and that change nothing raps-gltf reads.
bool extension_is_known(const std::string& name);

// Everything after the buffers: `buffer_sizes` are the buffers' byteLengths, whose bytes (or
// absence, for placeholders) the loader already checked.
void check_document(const Json& doc, const std::vector<uint64_t>& buffer_sizes);

// Extensions whose presence (used or required) makes raps-gltf refuse the asset: the geometry is
// compressed, and re-splitting vertices would invalidate the compressed stream.
const std::vector<std::string>& refused_extensions();

}  // namespace raps_gltf
