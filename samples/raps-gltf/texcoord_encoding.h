// The bytes of a new TEXCOORD_n accessor: FLOAT, or normalized UNSIGNED_SHORT (core glTF 2.0,
// 3.7.2.1), which halves the set's size.
//
// unorm16 keeps every vertex in the texel its float uv lies in: each coordinate is rounded to
// the nearest of the 65536 values that fall inside that texel of the page (a texel spans at least
// four of them, pages being at most 16384 texels wide). Charts placed on whole texels therefore
// touch the texels they touched, and their padding holds as the library measured it; gltfpack's
// own quantization of such a set then changes nothing.
#pragma once

#include <cstdint>
#include <vector>

namespace raps_gltf {

enum class UvFormat { kFloat32, kUnorm16 };

struct EncodedTexcoords {
    int component_type = 0;
    bool normalized = false;
    std::vector<uint8_t> bytes;
    double max_error_texels = 0;  // largest move of a coordinate, in texels of the page
};

// uv: u, v per vertex in glTF's convention (origin at the image's top-left corner), in [0, 1];
// width x height: the page's texels.
EncodedTexcoords encode_texcoords(const std::vector<float>& uv, UvFormat format, uint64_t width,
                                  uint64_t height);

}  // namespace raps_gltf
