// Where the default scene draws each mesh, and at which scale: the input of --group scene.
// A node with EXT_mesh_gpu_instancing draws its mesh once per instance (its ROTATION and SCALE
// after the node's transform).
//
// A node's world matrix is its parents' times its own (glTF 2.0, 3.5.3: a matrix, or translation,
// rotation and scale). Only the linear part matters for texel density; translations are dropped.
// A skinned mesh is drawn through its joints, not its node (3.7.3): its bind pose is placed by
// world(joint 0) * inverseBindMatrix 0, which is where the rest pose puts it. A mesh drawn by
// several nodes takes the instance on which it covers the most surface (its transformed area),
// so no instance gets fewer texels per world unit than the atlas's density.
//
// The default scene is `scene`, or scenes[0] when the document names none (what viewers show);
// a document without scenes draws nothing.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "gltf_load.h"

namespace raps_gltf {

using Linear3 = std::array<double, 9>;  // row-major 3x3

struct MeshInstances {
    int instances = 0;     // nodes of the default scene that draw it, singular ones included
    bool skinned = false;  // at least one instance is skinned
    // The regular (invertible) linear maps it is drawn under; when there are more than 64, the
    // 64 that can enlarge areas most (the Frobenius norm of their cofactor matrix).
    std::vector<Linear3> distinct;
    bool drawn() const { return !distinct.empty(); }
};

struct SceneInstances {
    int scene = -1;                     // the scene read; -1 when the document has none
    bool scene_implied = false;         // no `scene` member: scenes[0] was taken
    std::vector<MeshInstances> meshes;  // per mesh of the document
};

// Throws GltfError("node") for a node whose matrix, translation, rotation or scale is not an
// array of finite numbers of the right length.
SceneInstances scene_instances(const Asset& asset);

// The instance a mesh is packed at, among `candidates`: the one on which it covers the most
// surface, `area` giving its surface area under a linear map.
struct ChosenInstance {
    Linear3 transform{};
    double scale = 1;            // sqrt(its area / the mesh's own area)
    std::vector<double> scales;  // the same figure per distinct candidate, increasing
};
ChosenInstance choose_instance(const std::vector<Linear3>& candidates,
                               const std::function<double(const Linear3&)>& area);

// Whether the map keeps shapes (a rotation, a reflection and one uniform scale: its columns
// orthogonal and of one length, to 1e-6): a mesh's own uvs are then undistorted in the world.
bool is_similarity(const Linear3& m);

}  // namespace raps_gltf
