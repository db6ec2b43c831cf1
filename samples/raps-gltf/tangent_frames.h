// Per-vertex tangents for new texture coordinates, for materials that need a tangent space but
// give renderers no normal texture to derive one from (KHR_materials_anisotropy without a
// normalTexture). Each triangle's tangent and bitangent are the directions of increasing u and v
// on its plane (E. Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh", 2001);
// a vertex sums those of its triangles, the sum is made orthogonal to the vertex normal and unit
// (Gram-Schmidt), and w is the handedness glTF defines (bitangent = cross(normal, tangent) * w).
// This is not MikkTSpace: a normal map baked against MikkTSpace tangents of these uvs shades
// slightly differently. A vertex whose triangles give no direction (zero uv area) gets a unit
// tangent orthogonal to its normal.
#pragma once

#include <cstdint>
#include <vector>

namespace raps_gltf {

// positions and normals: x, y, z per vertex; uvs: u, v per vertex; triangles: 3 indices each.
// Returns x, y, z, w per vertex, xyz of unit length and w = +1 or -1.
std::vector<float> tangent_frames(const std::vector<float>& positions,
                                  const std::vector<float>& normals, const std::vector<float>& uvs,
                                  const std::vector<uint32_t>& triangles);

}  // namespace raps_gltf
