// Loading a glTF 2.0 asset (.gltf with external or data-uri buffers, or .glb) for baking.
//
// The document is kept as written (nlohmann::ordered_json, member order kept): the output is
// this document edited in place, so whatever raps-gltf does not understand (extensions, extras,
// unknown members, accessor-level extensions) is written back unchanged. Geometry is read from
// it and from the buffers' bytes by gltf_accessors, as the specification defines them; no
// loader's model stands between (tinygltf 2.7 refuses valid assets: accessors without a
// bufferView used as indices, placeholder buffers, data uris without ;base64, GLB padding).
// Before any byte of a buffer is read, the GLB framing, the JSON nesting depth, the required
// extensions and every uri (confined to the asset's folder) are checked; then every buffer's
// size and every bufferView and accessor range (gltf_document.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gltf_json.h"

namespace raps_gltf {

struct Asset {
    std::string path;    // as given
    std::string folder;  // the asset's folder, real path: every uri must resolve inside it
    bool binary = false;
    Json doc;
    // Each buffer's bytes, byteLength of them. A placeholder buffer (no uri, and not a GLB's BIN
    // chunk: the specification allows one, e.g. for an extension's fallback) has none: its
    // entry is empty and buffer_has_data false.
    std::vector<std::vector<uint8_t>> buffers;
    std::vector<bool> buffer_has_data;
    std::vector<std::string> warnings;  // what the loader accepted but a user should know
};

// Loads and checks. Throws GltfError naming the first problem found.
Asset load_asset(const std::string& path);

}  // namespace raps_gltf
