// The input mesh as the algorithms see it: positions converted to double, triangles as vertex
// triples. Built by the C API from the caller's arrays; never modified afterwards. Indices are
// int32 because the sparse solver indexes with int32; the C API refuses meshes of 2^31 or more
// vertices or triangles.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace raps {

using Triangle = std::array<int32_t, 3>;

struct TriangleMesh {
    std::vector<Eigen::Vector3d> positions;
    std::vector<Triangle> triangles;
    // The artist's seams, which only the atlas reads (atlas/user_seams.h): per triangle its group
    // (empty: one group), and input vertex pairs that are seams. Checked when the mesh is used.
    std::vector<uint32_t> triangle_group;
    std::vector<std::array<uint32_t, 2>> seam_edges;
    // Per triangle its polygon (empty: each triangle its own), which the atlas keeps whole
    // (atlas/polygon_units.h). Checked when the mesh is used.
    std::vector<uint32_t> triangle_polygon;
    // The input's own uvs, per triangle corner 3t+k (empty: none), which only the atlas's
    // repacking reads (atlas/uv_repack.h). Checked when the mesh is used.
    std::vector<Eigen::Vector2d> corner_uv;

    int32_t vertex_count() const { return static_cast<int32_t>(positions.size()); }
    int32_t triangle_count() const { return static_cast<int32_t>(triangles.size()); }
};

}  // namespace raps
