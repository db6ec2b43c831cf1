// The one error type of raps-gltf: a message naming the problem and a short kind, which the CLI
// prints in its JSON ("glb", "json", "uri", "buffer", "accessor", "mesh", "unsupported",
// "texcoord_exists", "raps", "io", "internal").
#pragma once

#include <stdexcept>
#include <string>

namespace raps_gltf {

struct GltfError : std::runtime_error {
    GltfError(std::string kind_, const std::string& message)
        : std::runtime_error(message), kind(std::move(kind_)) {}
    std::string kind;
};

}  // namespace raps_gltf
