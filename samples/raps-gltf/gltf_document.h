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

// asset.version and the extensions raps-gltf refuses (compressed geometry it cannot decode).
void check_header(const Json& doc);

// Everything after the buffers: `buffer_sizes` are the buffers' byteLengths, whose bytes (or
// absence, for placeholders) the loader already checked.
void check_document(const Json& doc, const std::vector<uint64_t>& buffer_sizes);

// Extensions whose presence (used or required) makes raps-gltf refuse the asset: the geometry is
// compressed, and re-splitting vertices would invalidate the compressed stream.
const std::vector<std::string>& refused_extensions();

}  // namespace raps_gltf
