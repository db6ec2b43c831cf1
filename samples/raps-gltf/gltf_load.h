// Loading a glTF 2.0 asset (.gltf with external or data-uri buffers, or .glb) for baking.
//
// Two views of one document, from the same bytes:
//   - `doc`, the JSON as written (nlohmann::ordered_json, member order kept). The output is this
//     document edited in place, so whatever raps-gltf does not understand (extensions, extras,
//     unknown members, accessor-level extensions) is written back unchanged; tinygltf 2.7 would
//     drop some of it on a save (see shared/design/gltf.md).
//   - `model`, tinygltf's typed model, from which geometry is read.
// Before tinygltf sees anything, the GLB framing, the JSON nesting depth, the required
// extensions, every uri (confined to the asset's folder), every buffer's size and every
// bufferView and accessor range are checked on `doc`; tinygltf then loads through file callbacks
// that cannot leave the folder and an image loader that decodes nothing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

namespace raps_gltf {

using Json = nlohmann::ordered_json;

struct Asset {
    std::string path;    // as given
    std::string folder;  // the asset's folder, real path: every uri must resolve inside it
    bool binary = false;
    Json doc;
    tinygltf::Model model;
    std::vector<std::string> warnings;  // tinygltf's warnings, for the report
};

// Extensions whose presence (used or required) makes raps-gltf refuse the asset: the geometry is
// compressed, and re-splitting vertices would invalidate the compressed stream.
const std::vector<std::string>& refused_extensions();

// Loads and checks. Throws GltfError naming the first problem found.
Asset load_asset(const std::string& path);

}  // namespace raps_gltf
