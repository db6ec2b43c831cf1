// The artist's seams: what separates charts besides the geometry. A per-triangle group id
// (material, smoothing group, user region), marked seam edges (pairs of input vertices), and,
// when asked, the input's own vertex splits (vertices an exporter duplicated along its uv
// seams, which welding would otherwise join). The surface cuts every edge they name
// (atlas_surface.h), so no chart grows, merges or is mapped across one.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/triangle_mesh.h"

namespace raps {

// Refuses a group array whose length is not the triangle count, and a seam pair that names a
// vertex out of range or is not an edge of any triangle; `name` ("mesh 2", or "" for the one
// mesh) leads the message.
void check_user_seams(const TriangleMesh& mesh, const std::string& name);

class UserSeams {
  public:
    // `mesh` must outlive this; its seams must have passed check_user_seams.
    UserSeams(const TriangleMesh& mesh, bool keep_input_seams);
    bool any() const { return any_; }
    uint32_t group(int32_t triangle) const {
        return mesh_.triangle_group.empty() ? 0 : mesh_.triangle_group[triangle];
    }
    // Whether the edge from corner k of input triangle a to its next corner, which corner l of
    // input triangle b traverses the other way once welded, is a seam.
    bool cuts(int32_t a, int k, int32_t b, int l) const;

  private:
    const TriangleMesh& mesh_;
    std::vector<uint64_t> seam_keys_;  // sorted
    bool keep_input_seams_;
    bool any_;
};

}  // namespace raps
