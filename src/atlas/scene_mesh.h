// A scene for the atlas: several meshes, each placed in world units by its own transform, as one
// mesh of parts (atlas_pipeline.h), so that one texel density holds across all of them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "atlas/atlas_pipeline.h"
#include "core/triangle_mesh.h"

namespace raps {

struct SceneMesh {
    TriangleMesh mesh;  // every part's positions in world units, indices offset
    AtlasParts parts;
};

// Checks each mesh on its own (it has vertices and triangles, its indices name its own
// vertices, its transformed coordinates stay within 1e30 like any position) and joins them in
// the order given; a message names the mesh. transforms[i] is mesh i's [A | t], row-major.
// With `repack`, every mesh must have its corner uvs (uv_repack.h), which are joined too.
SceneMesh combine_scene(const std::vector<const TriangleMesh*>& meshes,
                        const std::vector<Eigen::Matrix<double, 3, 4>>& transforms, bool repack);

}  // namespace raps
