#include "texcoord_encoding.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gltf_accessors.h"

namespace raps_gltf {

namespace {

constexpr int64_t kSteps = 65535;

// The unorm16 value nearest to x in [0, 1] among those inside x's texel of a side of n texels:
// texel c = floor(x n) covers q / 65535 in [c / n, (c + 1) / n).
uint16_t quantize(double x, uint64_t n) {
    const double clamped = std::min(1.0, std::max(0.0, x));
    const int64_t nearest = std::llround(clamped * kSteps);
    if (n == 0) return static_cast<uint16_t>(nearest);
    const int64_t texels = static_cast<int64_t>(n);
    const int64_t c = std::min(texels - 1, static_cast<int64_t>(std::floor(clamped * texels)));
    const int64_t lo = (c * kSteps + texels - 1) / texels;  // ceil(c * 65535 / n)
    // Below (c + 1) / n; the last texel keeps 1 itself (floor(1 * n) is past the last texel,
    // which every reader clamps).
    const int64_t hi = c == texels - 1 ? kSteps : ((c + 1) * kSteps + texels - 1) / texels - 1;
    return static_cast<uint16_t>(std::min(std::max(nearest, lo), hi));
}

}  // namespace

EncodedTexcoords encode_texcoords(const std::vector<float>& uv, UvFormat format, uint64_t width,
                                  uint64_t height) {
    EncodedTexcoords out;
    if (format == UvFormat::kFloat32) {
        out.component_type = kFloat;
        out.bytes.resize(uv.size() * sizeof(float));
        std::memcpy(out.bytes.data(), uv.data(), out.bytes.size());
        return out;
    }
    out.component_type = kUnsignedShort;
    out.normalized = true;
    out.bytes.resize(uv.size() * sizeof(uint16_t));
    for (size_t i = 0; i < uv.size(); ++i) {
        const uint64_t side = i % 2 == 0 ? width : height;
        const uint16_t q = quantize(uv[i], side);
        std::memcpy(&out.bytes[2 * i], &q, 2);
        const double moved = std::fabs(q / double(kSteps) - uv[i]) * double(side);
        out.max_error_texels = std::max(out.max_error_texels, moved);
    }
    return out;
}

}  // namespace raps_gltf
