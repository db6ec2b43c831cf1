#include "atlas/scene_mesh.h"

#include <cmath>
#include <string>

#include "atlas/user_seams.h"
#include "atlas/uv_repack.h"
#include "core/error.h"

namespace raps {
namespace {

// As the C API refuses positions beyond this (products of a few coordinates must stay finite).
constexpr double kMaxCoordinate = 1e30;
// The library indexes with int32, up to 8 entries per triangle (c_api.cpp).
constexpr int64_t kMaxVertices = 0x7fffffff;
constexpr int64_t kMaxTriangles = int64_t{1} << 28;

void check_part(const TriangleMesh& mesh, size_t index, bool repack) {
    const std::string name = "mesh " + std::to_string(index);
    if (mesh.positions.empty() || mesh.triangles.empty()) {
        throw Error(ErrorCode::kEmptyMesh,
                    name + (mesh.positions.empty() ? " has no vertices (set its positions)"
                                                   : " has no triangles (set its indices)"));
    }
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const int32_t v = mesh.triangles[t][k];
            if (v < 0 || v >= mesh.vertex_count()) {
                throw Error(ErrorCode::kIndexOutOfRange,
                            name + ": index " + std::to_string(3 * static_cast<int64_t>(t) + k) +
                                " (triangle " + std::to_string(t) + ") is " + std::to_string(v) +
                                " but the mesh has only " + std::to_string(mesh.vertex_count()) +
                                " vertices");
            }
        }
    }
    check_user_seams(mesh, name);
    if (repack) check_corner_uvs(mesh, name);
}

}  // namespace

SceneMesh combine_scene(const std::vector<const TriangleMesh*>& meshes,
                        const std::vector<Eigen::Matrix<double, 3, 4>>& transforms, bool repack) {
    SceneMesh scene;
    int64_t vertices = 0, triangles = 0;
    bool any_groups = false, any_polygons = false;
    for (size_t i = 0; i < meshes.size(); ++i) {
        check_part(*meshes[i], i, repack);
        any_groups = any_groups || !meshes[i]->triangle_group.empty();
        any_polygons = any_polygons || !meshes[i]->triangle_polygon.empty();
        vertices += meshes[i]->vertex_count();
        triangles += meshes[i]->triangle_count();
    }
    if (vertices > kMaxVertices || triangles > kMaxTriangles) {
        throw Error(ErrorCode::kTooLarge,
                    "the scene has " + std::to_string(vertices) + " vertices and " +
                        std::to_string(triangles) +
                        " triangles together; raps accepts at most 2^31 - 1 and 2^28");
    }
    scene.mesh.positions.reserve(static_cast<size_t>(vertices));
    scene.mesh.triangles.reserve(static_cast<size_t>(triangles));
    scene.parts.first_vertex.push_back(0);
    scene.parts.first_triangle.push_back(0);
    for (size_t i = 0; i < meshes.size(); ++i) {
        const int32_t offset = static_cast<int32_t>(scene.mesh.positions.size());
        const Eigen::Matrix3d linear = transforms[i].leftCols<3>();
        const Eigen::Vector3d translation = transforms[i].col(3);
        for (size_t v = 0; v < meshes[i]->positions.size(); ++v) {
            const Eigen::Vector3d p = linear * meshes[i]->positions[v] + translation;
            if (!(p.cwiseAbs().maxCoeff() <= kMaxCoordinate)) {  // also NaN
                throw Error(ErrorCode::kNonFinitePosition,
                            "mesh " + std::to_string(i) + ": vertex " + std::to_string(v) +
                                " lies beyond 1e30 once transformed into world units");
            }
            scene.mesh.positions.push_back(p);
        }
        for (const Triangle& t : meshes[i]->triangles)
            scene.mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        // Parts are welded apart, so groups need not differ between meshes: a mesh without
        // groups is all group 0.
        if (any_groups) {
            const std::vector<uint32_t>& group = meshes[i]->triangle_group;
            if (group.empty()) {
                scene.mesh.triangle_group.resize(scene.mesh.triangles.size(), 0);
            } else {
                scene.mesh.triangle_group.insert(scene.mesh.triangle_group.end(), group.begin(),
                                                 group.end());
            }
        }
        // Polygon ids are only compared across an edge, which never joins two meshes; a mesh
        // without them gets one id per triangle (its scene triangle index: no two equal).
        if (any_polygons) {
            const std::vector<uint32_t>& polygon = meshes[i]->triangle_polygon;
            if (polygon.empty()) {
                for (size_t t = scene.mesh.triangle_polygon.size(); t < scene.mesh.triangles.size();
                     ++t)
                    scene.mesh.triangle_polygon.push_back(static_cast<uint32_t>(t));
            } else {
                scene.mesh.triangle_polygon.insert(scene.mesh.triangle_polygon.end(),
                                                   polygon.begin(), polygon.end());
            }
        }
        // uvs are not transformed: the repacking scales each chart to its world-unit area.
        if (repack) {
            scene.mesh.corner_uv.insert(scene.mesh.corner_uv.end(), meshes[i]->corner_uv.begin(),
                                        meshes[i]->corner_uv.end());
        }
        for (const std::array<uint32_t, 2>& pair : meshes[i]->seam_edges) {
            scene.mesh.seam_edges.push_back(
                {pair[0] + static_cast<uint32_t>(offset), pair[1] + static_cast<uint32_t>(offset)});
        }
        scene.parts.first_vertex.push_back(static_cast<int32_t>(scene.mesh.positions.size()));
        scene.parts.first_triangle.push_back(static_cast<int32_t>(scene.mesh.triangles.size()));
    }
    return scene;
}

}  // namespace raps
