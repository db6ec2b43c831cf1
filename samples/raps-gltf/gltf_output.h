// Writing the baked asset: .glb (one self-contained file) or .gltf (JSON plus one .bin, or one
// file with a data-uri buffer), chosen by the output's extension.
//
// The output document is the input's JSON with the bake's edits. Its bytes are laid out again
// in one buffer, bufferView by bufferView, each keeping its offset modulo 16 so that every
// alignment the input had still holds. When every extension the asset uses is one raps-gltf
// knows not to point at accessors or bufferViews, the accessors and bufferViews the bake left
// unused (the old vertex data of rewritten primitives) are removed and references renumbered;
// otherwise every byte is kept, since an unknown extension might still refer to them.
// Images are never decoded: in a .glb, images given by uri become bufferViews with the same
// bytes; in a .gltf, external images are copied beside the output under the same uri.
// Every file is written to a temporary file in its folder and renamed into place, the main file
// last, so a failure never leaves a partial output.
#pragma once

#include <string>
#include <vector>

#include "gltf_bake.h"
#include "gltf_load.h"

namespace raps_gltf {

struct WriteOptions {
    bool embed = false;  // .gltf only: the buffer as a data uri, no .bin beside it
};

struct WriteReport {
    std::vector<std::string> files;  // written, main file last
    uint64_t bytes = 0;              // of the main file plus its .bin
    bool pruned = false;
    std::string kept_unused_because;  // when not pruned
    size_t removed_accessors = 0, removed_buffer_views = 0;
    size_t repaired_buffer_views = 0;  // animation/skin bufferViews whose byteStride was removed
    std::vector<std::string> embedded_images, copied_images;
};

// Throws GltfError("io", ...) when a file cannot be written, or when an output file would be one
// of the input's files.
WriteReport write_output(const Asset& asset, BakeResult& bake, const std::string& path,
                         const WriteOptions& options);

// Writes bytes to path through a temporary file in the same folder and a rename.
void write_file_atomically(const std::string& path, const std::vector<uint8_t>& bytes);

}  // namespace raps_gltf
