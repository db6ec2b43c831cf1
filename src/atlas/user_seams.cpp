#include "atlas/user_seams.h"

#include <algorithm>

#include "core/error.h"

namespace raps {
namespace {

uint64_t edge_key(uint32_t a, uint32_t b) {
    return static_cast<uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
}

std::string lead(const std::string& name) {
    return name.empty() ? std::string() : name + ": ";
}

}  // namespace

void check_user_seams(const TriangleMesh& mesh, const std::string& name) {
    if (!mesh.triangle_group.empty() && mesh.triangle_group.size() != mesh.triangles.size()) {
        throw Error(ErrorCode::kGroupCount,
                    lead(name) + "the triangle groups number " +
                        std::to_string(mesh.triangle_group.size()) + " but the mesh has " +
                        std::to_string(mesh.triangles.size()) + " triangles");
    }
    if (!mesh.triangle_polygon.empty() && mesh.triangle_polygon.size() != mesh.triangles.size()) {
        throw Error(ErrorCode::kGroupCount,
                    lead(name) + "the triangle polygons number " +
                        std::to_string(mesh.triangle_polygon.size()) + " but the mesh has " +
                        std::to_string(mesh.triangles.size()) + " triangles");
    }
    if (mesh.seam_edges.empty()) return;
    std::vector<uint64_t> edges;
    edges.reserve(3 * mesh.triangles.size());
    for (const Triangle& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            edges.push_back(
                edge_key(static_cast<uint32_t>(t[k]), static_cast<uint32_t>(t[(k + 1) % 3])));
        }
    }
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < mesh.seam_edges.size(); ++i) {
        const std::array<uint32_t, 2>& pair = mesh.seam_edges[i];
        const std::string which = lead(name) + "seam edge " + std::to_string(i) + " (" +
                                  std::to_string(pair[0]) + ", " + std::to_string(pair[1]) + ")";
        const uint32_t largest = std::max(pair[0], pair[1]);
        if (largest >= mesh.positions.size()) {
            throw Error(ErrorCode::kIndexOutOfRange,
                        which + " names vertex " + std::to_string(largest) +
                            " but the mesh has only " + std::to_string(mesh.positions.size()) +
                            " vertices");
        }
        if (!std::binary_search(edges.begin(), edges.end(), edge_key(pair[0], pair[1]))) {
            throw Error(ErrorCode::kSeamNotAnEdge,
                        which + " is not an edge of any triangle of the mesh");
        }
    }
}

UserSeams::UserSeams(const TriangleMesh& mesh, bool keep_input_seams)
    : mesh_(mesh), keep_input_seams_(keep_input_seams) {
    seam_keys_.reserve(mesh.seam_edges.size());
    for (const std::array<uint32_t, 2>& pair : mesh.seam_edges)
        seam_keys_.push_back(edge_key(pair[0], pair[1]));
    std::sort(seam_keys_.begin(), seam_keys_.end());
    any_ = keep_input_seams || !seam_keys_.empty() || !mesh.triangle_group.empty();
}

bool UserSeams::cuts(int32_t a, int k, int32_t b, int l) const {
    if (group(a) != group(b)) return true;
    const uint32_t p = static_cast<uint32_t>(mesh_.triangles[a][k]);
    const uint32_t q = static_cast<uint32_t>(mesh_.triangles[a][(k + 1) % 3]);
    const uint32_t r = static_cast<uint32_t>(mesh_.triangles[b][l]);
    const uint32_t s = static_cast<uint32_t>(mesh_.triangles[b][(l + 1) % 3]);
    if (keep_input_seams_ && (p != s || q != r)) return true;
    return std::binary_search(seam_keys_.begin(), seam_keys_.end(), edge_key(p, q)) ||
           std::binary_search(seam_keys_.begin(), seam_keys_.end(), edge_key(r, s));
}

}  // namespace raps
