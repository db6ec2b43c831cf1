#include "tangent_frames.h"

#include <cmath>

#include "vec3.h"

namespace raps_gltf {

namespace {

Vec3 at(const std::vector<float>& v, uint32_t i) {
    return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}

bool normalize(Vec3& v) {
    const double length = std::sqrt(dot(v, v));
    if (!(length > 1e-20) || !std::isfinite(length)) return false;
    for (double& c : v) c /= length;
    return true;
}

// Any unit vector orthogonal to n (n unit).
Vec3 orthogonal(const Vec3& n) {
    Vec3 t = std::fabs(n[0]) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0});
    normalize(t);
    return t;
}

}  // namespace

std::vector<float> tangent_frames(const std::vector<float>& positions,
                                  const std::vector<float>& normals, const std::vector<float>& uvs,
                                  const std::vector<uint32_t>& triangles) {
    const size_t n = positions.size() / 3;
    std::vector<Vec3> tangent(n, Vec3{0, 0, 0}), bitangent(n, Vec3{0, 0, 0});
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
        const uint32_t i0 = triangles[t], i1 = triangles[t + 1], i2 = triangles[t + 2];
        const Vec3 e1 = sub(at(positions, i1), at(positions, i0));
        const Vec3 e2 = sub(at(positions, i2), at(positions, i0));
        const double du1 = uvs[2 * i1] - uvs[2 * i0], dv1 = uvs[2 * i1 + 1] - uvs[2 * i0 + 1];
        const double du2 = uvs[2 * i2] - uvs[2 * i0], dv2 = uvs[2 * i2 + 1] - uvs[2 * i0 + 1];
        const double r = du1 * dv2 - du2 * dv1;
        if (r == 0 || !std::isfinite(r)) continue;
        Vec3 s, b;
        for (int c = 0; c < 3; ++c) {
            s[c] = (e1[c] * dv2 - e2[c] * dv1) / r;
            b[c] = (e2[c] * du1 - e1[c] * du2) / r;
        }
        for (uint32_t i : {i0, i1, i2}) {
            for (int c = 0; c < 3; ++c) {
                tangent[i][c] += s[c];
                bitangent[i][c] += b[c];
            }
        }
    }
    std::vector<float> out(4 * n);
    for (size_t i = 0; i < n; ++i) {
        Vec3 normal = at(normals, static_cast<uint32_t>(i));
        if (!normalize(normal)) normal = {0, 0, 1};
        Vec3 t = tangent[i];
        const double along = dot(normal, t);
        for (int c = 0; c < 3; ++c) t[c] -= normal[c] * along;
        if (!normalize(t)) t = orthogonal(normal);
        const double w = dot(cross(normal, t), bitangent[i]) < 0 ? -1.0 : 1.0;
        for (int c = 0; c < 3; ++c) out[4 * i + c] = static_cast<float>(t[c]);
        out[4 * i + 3] = static_cast<float>(w);
    }
    return out;
}

}  // namespace raps_gltf
