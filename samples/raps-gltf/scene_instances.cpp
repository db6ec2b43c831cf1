#include "scene_instances.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "gltf_accessors.h"
#include "gltf_error.h"

namespace raps_gltf {

namespace {

constexpr Linear3 kIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1};

// Distinct transforms of one mesh whose areas are compared, at most: a forest of instances
// with their own scales would otherwise cost an area per instance.
constexpr size_t kMaxCandidates = 64;

Linear3 multiply(const Linear3& a, const Linear3& b) {
    Linear3 out{};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            for (int k = 0; k < 3; ++k) out[3 * r + c] += a[3 * r + k] * b[3 * k + c];
        }
    }
    return out;
}

// The numbers of node member `key`: exactly `count` finite ones, or none when it is absent.
std::vector<double> numbers(const Json& node, const char* key, size_t count,
                            const std::string& what) {
    const Json* value = member(node, key);
    if (!value) return {};
    std::vector<double> out;
    if (value->is_array() && value->size() == count) {
        for (const Json& v : *value) {
            if (!v.is_number() || !std::isfinite(v.get<double>())) break;
            out.push_back(v.get<double>());
        }
    }
    if (out.size() != count) {
        throw GltfError(
            "node", what + ": '" + key + "' must be " + std::to_string(count) + " finite numbers");
    }
    return out;
}

Linear3 rotation_scale(std::vector<double> q, const std::vector<double>& s) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n > 0) {
        for (double& v : q) v /= n;
    }
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const Linear3 rotation = {
        1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
        2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
        2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
    return multiply(rotation, {s[0], 0, 0, 0, s[1], 0, 0, 0, s[2]});
}

// The linear part of a node's local transform: its matrix (column-major), or rotation * scale.
Linear3 local_linear(const Json& node, const std::string& what) {
    const std::vector<double> m = numbers(node, "matrix", 16, what);
    if (!m.empty()) {
        Linear3 out{};
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) out[3 * r + c] = m[4 * c + r];
        }
        return out;
    }
    std::vector<double> q = numbers(node, "rotation", 4, what);
    std::vector<double> s = numbers(node, "scale", 3, what);
    if (q.empty()) q = {0, 0, 0, 1};
    if (s.empty()) s = {1, 1, 1};
    return rotation_scale(q, s);
}

// An EXT_mesh_gpu_instancing attribute's values (`components` per instance), or none when the
// node lacks it or it is not of the type the extension defines.
std::vector<double> instance_values(const Asset& asset, const Json* attributes, const char* name,
                                    const char* type) {
    const Json* index = attributes ? member(*attributes, name) : nullptr;
    if (!index) return {};
    const int accessor = index->get<int>();
    const AccessorLayout a = accessor_layout(asset.doc, accessor);
    if (a.type != type || !accessor_has_data(asset, accessor)) return {};
    const std::vector<uint8_t> data = read_accessor(asset, accessor);
    const int n = component_count(a.type);
    const uint64_t element = element_size(a.type, a.component_type);
    std::vector<double> out(a.count * n);
    for (uint64_t i = 0; i < a.count; ++i) {
        for (int c = 0; c < n; ++c)
            out[i * n + c] = component_value(&data[i * element], a.component_type, a.normalized, c);
    }
    return out;
}

// The linear maps a node draws its mesh under: `linear`, or with EXT_mesh_gpu_instancing one
// per instance, linear * rotation_i * scale_i (its translations do not change areas).
std::vector<Linear3> node_instances(const Asset& asset, const Json& node, const Linear3& linear) {
    const Json* extensions = member(node, "extensions");
    const Json* instancing = extensions && extensions->is_object()
                                 ? member(*extensions, "EXT_mesh_gpu_instancing")
                                 : nullptr;
    const Json* attributes =
        instancing && instancing->is_object() ? member(*instancing, "attributes") : nullptr;
    const std::vector<double> rotations = instance_values(asset, attributes, "ROTATION", "VEC4");
    const std::vector<double> scales = instance_values(asset, attributes, "SCALE", "VEC3");
    if (rotations.empty() && scales.empty()) return {linear};
    const size_t count = rotations.empty() ? scales.size() / 3
                         : scales.empty()  ? rotations.size() / 4
                                           : std::min(scales.size() / 3, rotations.size() / 4);
    std::vector<Linear3> out;
    for (size_t i = 0; i < count; ++i) {
        const std::vector<double> q =
            rotations.empty() ? std::vector<double>{0, 0, 0, 1}
                              : std::vector<double>(&rotations[4 * i], &rotations[4 * i + 4]);
        const std::vector<double> s = scales.empty()
                                          ? std::vector<double>{1, 1, 1}
                                          : std::vector<double>(&scales[3 * i], &scales[3 * i + 3]);
        out.push_back(multiply(linear, rotation_scale(q, s)));
    }
    return out;
}

// World linear parts of every node (the document's nodes form a forest, checked on loading).
std::vector<Linear3> world_linears(const Json& doc) {
    const Json& nodes = array_of(doc, "nodes");
    std::vector<int64_t> parent(nodes.size(), -1);
    for (size_t i = 0; i < nodes.size(); ++i) {
        if (const Json* children = member(nodes[i], "children")) {
            for (const Json& c : *children) parent[c.get<size_t>()] = static_cast<int64_t>(i);
        }
    }
    std::vector<Linear3> world(nodes.size());
    std::vector<bool> done(nodes.size(), false);
    for (size_t i = 0; i < nodes.size(); ++i) {
        std::vector<size_t> chain;  // i and its ancestors not done yet, nearest first
        for (int64_t at = static_cast<int64_t>(i); at >= 0 && !done[at]; at = parent[at])
            chain.push_back(static_cast<size_t>(at));
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const Linear3 local = local_linear(nodes[*it], "node " + std::to_string(*it));
            world[*it] = parent[*it] < 0 ? local : multiply(world[parent[*it]], local);
            done[*it] = true;
        }
    }
    return world;
}

// A skinned mesh's bind pose in the world: world(joint 0) * inverseBindMatrices[0] (its node's
// own transform is not applied, glTF 2.0 3.7.3.3).
Linear3 skinned_linear(const Asset& asset, const Json& skin, const std::vector<Linear3>& world,
                       const Linear3& node_world) {
    const Json* joints = member(skin, "joints");
    if (!joints || !joints->is_array() || joints->empty()) return node_world;
    const Linear3& joint = world[(*joints)[0].get<size_t>()];
    const Json* ibm = member(skin, "inverseBindMatrices");
    if (!ibm) return joint;
    const int accessor = ibm->get<int>();
    const AccessorLayout a = accessor_layout(asset.doc, accessor);
    if (a.type != "MAT4" || a.component_type != kFloat || a.count == 0 ||
        !accessor_has_data(asset, accessor)) {
        return joint;
    }
    const std::vector<uint8_t> data = read_accessor(asset, accessor);
    Linear3 inverse{};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c)
            inverse[3 * r + c] = component_value(data.data(), kFloat, false, 4 * c + r);
    }
    return multiply(joint, inverse);
}

// The library's test for a transform that would flatten a mesh (raps_mesh_set_transform).
bool regular(const Linear3& m) {
    const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                       m[2] * (m[3] * m[7] - m[4] * m[6]);
    double rows = 1;
    for (int r = 0; r < 3; ++r) {
        rows *= std::sqrt(m[3 * r] * m[3 * r] + m[3 * r + 1] * m[3 * r + 1] +
                          m[3 * r + 2] * m[3 * r + 2]);
    }
    return std::isfinite(det) && std::fabs(det) > 1e-12 * rows;
}

int default_scene(const Json& doc, bool* implied) {
    *implied = !member(doc, "scene");
    if (!*implied) return (*member(doc, "scene")).get<int>();
    return array_of(doc, "scenes").empty() ? -1 : 0;
}

// Each node the scene draws a mesh with, and the linear map it draws it under.
std::vector<std::pair<int, Linear3>> drawn_meshes(const Asset& asset, int scene,
                                                  const std::vector<Linear3>& world,
                                                  std::vector<bool>* skinned) {
    std::vector<std::pair<int, Linear3>> out;
    const Json& nodes = array_of(asset.doc, "nodes");
    std::vector<size_t> stack;
    if (const Json* roots = member(array_of(asset.doc, "scenes")[scene], "nodes")) {
        for (const Json& r : *roots) stack.push_back(r.get<size_t>());
    }
    while (!stack.empty()) {
        const size_t n = stack.back();
        stack.pop_back();
        const Json& node = nodes[n];
        if (const Json* children = member(node, "children")) {
            for (const Json& c : *children) stack.push_back(c.get<size_t>());
        }
        const Json* mesh = member(node, "mesh");
        if (!mesh) continue;
        const int m = mesh->get<int>();
        Linear3 linear = world[n];
        if (const Json* skin = member(node, "skin")) {
            linear = skinned_linear(asset, array_of(asset.doc, "skins")[skin->get<size_t>()], world,
                                    world[n]);
            (*skinned)[m] = true;
        }
        for (const Linear3& instance : node_instances(asset, node, linear))
            out.emplace_back(m, instance);
    }
    return out;
}

// How much a linear map can enlarge an area: the Frobenius norm of its cofactor matrix, which
// maps a triangle's normal to its image's (|cof(L) n| times the area), bounds it for every
// orientation; for a uniform scale s it is sqrt(3) s^2.
double area_bound(const Linear3& m) {
    const double cof[9] = {
        m[4] * m[8] - m[5] * m[7], m[5] * m[6] - m[3] * m[8], m[3] * m[7] - m[4] * m[6],
        m[2] * m[7] - m[1] * m[8], m[0] * m[8] - m[2] * m[6], m[1] * m[6] - m[0] * m[7],
        m[1] * m[5] - m[2] * m[4], m[2] * m[3] - m[0] * m[5], m[0] * m[4] - m[1] * m[3]};
    double sum = 0;
    for (double c : cof) sum += c * c;
    return std::sqrt(sum);
}

}  // namespace

SceneInstances scene_instances(const Asset& asset) {
    SceneInstances out;
    out.meshes.resize(array_of(asset.doc, "meshes").size());
    out.scene = default_scene(asset.doc, &out.scene_implied);
    if (out.scene < 0) return out;
    const std::vector<Linear3> world = world_linears(asset.doc);
    std::vector<bool> skinned(out.meshes.size(), false);
    std::vector<std::set<Linear3>> distinct(out.meshes.size());
    for (const auto& drawn : drawn_meshes(asset, out.scene, world, &skinned)) {
        MeshInstances& m = out.meshes[drawn.first];
        ++m.instances;
        m.skinned = m.skinned || skinned[drawn.first];
        if (regular(drawn.second)) distinct[drawn.first].insert(drawn.second);
    }
    for (size_t i = 0; i < out.meshes.size(); ++i) {
        std::vector<Linear3>& kept = out.meshes[i].distinct;
        kept.assign(distinct[i].begin(), distinct[i].end());
        if (kept.size() <= kMaxCandidates) continue;
        std::partial_sort(
            kept.begin(), kept.begin() + kMaxCandidates, kept.end(),
            [](const Linear3& a, const Linear3& b) { return area_bound(a) > area_bound(b); });
        kept.resize(kMaxCandidates);
    }
    return out;
}

ChosenInstance choose_instance(const std::vector<Linear3>& candidates,
                               const std::function<double(const Linear3&)>& area) {
    ChosenInstance out;
    out.transform = kIdentity;
    const double own = area(kIdentity);
    double best = -1;
    for (const Linear3& t : candidates) {
        const double a = area(t);
        const double scale = own > 0 ? std::sqrt(a / own) : 1.0;
        out.scales.push_back(scale);
        if (a > best) {
            best = a;
            out.transform = t;
            out.scale = scale;
        }
    }
    std::sort(out.scales.begin(), out.scales.end());
    // Transforms that differ by a rotation only give the same figure: one scale.
    out.scales.erase(std::unique(out.scales.begin(), out.scales.end(),
                                 [](double a, double b) { return std::fabs(a - b) <= 1e-9 * b; }),
                     out.scales.end());
    return out;
}

bool is_similarity(const Linear3& m) {
    double g[3][3];  // the Gram matrix of the columns
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            g[i][j] = m[i] * m[j] + m[3 + i] * m[3 + j] + m[6 + i] * m[6 + j];
        }
    }
    const double scale = (g[0][0] + g[1][1] + g[2][2]) / 3;
    if (!(scale > 0)) return false;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (std::fabs(g[i][j] - (i == j ? scale : 0)) > 1e-6 * scale) return false;
        }
    }
    return true;
}

}  // namespace raps_gltf
