#include "gltf_primitive_select.h"

#include <cmath>

#include "gltf_accessors.h"
#include "gltf_error.h"

namespace raps_gltf {

namespace {

const char* kModeNames[] = {"points",    "lines",          "line loop",   "line strip",
                            "triangles", "triangle strip", "triangle fan"};

// glTF 2.0 section 3.7.2.1: triangle i of a strip is (i, i+1+i%2, i+2-i%2), of a fan
// (i+1, i+2, 0), so that every triangle keeps the strip's or fan's winding.
std::vector<uint32_t> triangle_list(int mode, const std::vector<uint32_t>& v) {
    std::vector<uint32_t> out;
    if (v.size() < 3) return out;
    if (mode == 4) {
        out.assign(v.begin(), v.begin() + (v.size() / 3) * 3);
    } else if (mode == 5) {
        for (size_t i = 0; i + 2 < v.size(); ++i) {
            out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
        }
    } else if (mode == 6) {
        for (size_t i = 0; i + 2 < v.size(); ++i) out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
    return out;
}

const Json* texture_info(const Json& object, const char* key) {
    const auto it = object.find(key);
    return it != object.end() && it->is_object() ? &*it : nullptr;
}

// The set a texture reads: KHR_texture_transform's texCoord, when given, overrides the
// textureInfo's own.
int texcoord_of(const Json& info) {
    const Json* extensions = member(info, "extensions");
    const Json* transform = extensions && extensions->is_object()
                                ? member(*extensions, "KHR_texture_transform")
                                : nullptr;
    if (transform && transform->is_object()) {
        const auto set = transform->find("texCoord");
        if (set != transform->end() && set->is_number_unsigned()) return set->get<int>();
    }
    const auto set = info.find("texCoord");
    return set != info.end() && set->is_number_unsigned() ? set->get<int>() : 0;
}

// Tangents belong to the uv set of the material's normal texture (or, without one, of its
// KHR_materials_anisotropy texture, which must use the same set). When that set is rewritten,
// the old tangents are wrong: dropped when the material has a normal texture (renderers then
// generate them, as the specification asks), generated anew when the material still needs a
// tangent space and has no normal texture (the validator's MESH_PRIMITIVE_NO_TANGENT_SPACE).
TangentPolicy tangent_policy(const Json& doc, const Json& primitive, int texcoord) {
    if (!primitive["attributes"].contains("TANGENT")) return TangentPolicy::kKeep;
    const Json* material = nullptr;
    const auto m = primitive.find("material");
    const auto materials = doc.find("materials");
    if (m != primitive.end() && materials != doc.end()) material = &(*materials)[m->get<size_t>()];
    const Json* normal = material ? texture_info(*material, "normalTexture") : nullptr;
    const Json* anisotropy = nullptr;
    if (material && material->contains("extensions") && (*material)["extensions"].is_object()) {
        const Json& extensions = (*material)["extensions"];
        const auto a = extensions.find("KHR_materials_anisotropy");
        if (a != extensions.end() && a->is_object()) anisotropy = &*a;
    }
    const Json* anisotropy_texture =
        anisotropy ? texture_info(*anisotropy, "anisotropyTexture") : nullptr;
    const int set = normal               ? texcoord_of(*normal)
                    : anisotropy_texture ? texcoord_of(*anisotropy_texture)
                                         : 0;
    if (set != texcoord) return TangentPolicy::kKeep;
    if (normal || !anisotropy || !primitive["attributes"].contains("NORMAL"))
        return TangentPolicy::kDrop;
    return TangentPolicy::kGenerate;
}

// The primitive-restart value (the largest of the index type) is forbidden in glTF indices; an
// output would carry it into every renderer that enables restart.
void check_indices(const std::vector<uint32_t>& indices, int component_type, uint64_t vertex_count,
                   const std::string& where) {
    const uint64_t restart = component_type == kUnsignedByte    ? 0xFFu
                             : component_type == kUnsignedShort ? 0xFFFFu
                                                                : 0xFFFFFFFFu;
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] == restart) {
            throw GltfError("accessor", where + ": index " + std::to_string(i) + " is " +
                                            std::to_string(restart) +
                                            ", the primitive-restart value, which glTF forbids");
        }
        if (indices[i] >= vertex_count) {
            throw GltfError("accessor", where + ": index " + std::to_string(i) + " is " +
                                            std::to_string(indices[i]) +
                                            ", past the vertex count " +
                                            std::to_string(vertex_count));
        }
    }
}

// The positions at the triangles' corners, three per triangle, read only there (a primitive
// may use a few vertices of an accessor that hundreds of primitives share).
std::vector<double> corner_positions(const Asset& asset, int accessor,
                                     const std::vector<uint32_t>& triangles,
                                     const std::string& where) {
    const AccessorLayout a = accessor_layout(asset.doc, accessor);
    const std::vector<uint8_t> data = read_accessor_at(asset, accessor, triangles);
    const uint64_t element = element_size("VEC3", a.component_type);
    std::vector<double> xyz(3 * triangles.size());
    for (size_t k = 0; k < triangles.size(); ++k) {
        for (int c = 0; c < 3; ++c) {
            xyz[3 * k + c] = component_value(&data[k * element], a.component_type, a.normalized, c);
            // NaN would poison the map and every min/max.
            if (!std::isfinite(xyz[3 * k + c])) {
                throw GltfError("accessor", where + ": POSITION accessor " +
                                                std::to_string(accessor) + " vertex " +
                                                std::to_string(triangles[k]) + " is not finite");
            }
        }
    }
    return xyz;
}

// Whether a triangle has area: neither two corners the same vertex nor the three collinear.
bool any_triangle_has_area(const std::vector<uint32_t>& t, const std::vector<double>& corners) {
    for (size_t i = 0; i + 2 < t.size(); i += 3) {
        if (t[i] == t[i + 1] || t[i + 1] == t[i + 2] || t[i] == t[i + 2]) continue;
        const double* a = &corners[3 * i];
        const double* b = &corners[3 * i + 3];
        const double* c = &corners[3 * i + 6];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]};
        if (n[0] != 0 || n[1] != 0 || n[2] != 0) return true;
    }
    return false;
}

// The first accessor the primitive reads whose data is not in the file ("" when none is).
std::string missing_data(const Asset& asset, const Json& prim) {
    std::vector<std::pair<std::string, const Json*>> maps = {{"", &prim["attributes"]}};
    if (prim.contains("targets")) {
        for (const Json& target : prim["targets"]) maps.emplace_back("morph target ", &target);
    }
    for (const auto& map : maps) {
        for (auto it = map.second->begin(); it != map.second->end(); ++it) {
            if (!accessor_has_data(asset, it.value().get<int>())) return map.first + it.key();
        }
    }
    if (prim.contains("indices") && !accessor_has_data(asset, prim["indices"].get<int>())) {
        return "indices";
    }
    return "";
}

// An accessor without a bufferView or a sparse substitution holds zeros (glTF 2.0, 3.6.2.3):
// every vertex at the origin, or every index 0. Known without reading what may be a billion of
// them (a 300-byte file once took 4 GB to find its triangles degenerate).
bool all_zeros(const Asset& asset, int accessor) {
    const AccessorLayout a = accessor_layout(asset.doc, accessor);
    return a.view < 0 && !a.sparse;
}

// The primitive's indices, checked; false when they are all zeros (without reading them).
bool read_checked_indices(const Asset& asset, int accessor, uint64_t vertex_count,
                          const std::string& where, std::vector<uint32_t>* vertices) {
    const AccessorLayout a = accessor_layout(asset.doc, accessor);
    if (a.type != "SCALAR" ||
        (a.component_type != kUnsignedByte && a.component_type != kUnsignedShort &&
         a.component_type != kUnsignedInt)) {
        throw GltfError("accessor", where + ": indices must be an unsigned SCALAR accessor");
    }
    if (all_zeros(asset, accessor)) return false;
    *vertices = read_indices(asset, accessor);
    check_indices(*vertices, a.component_type, vertex_count, where);
    return true;
}

// One primitive: its triangles, or the reason it is left as it is (returned; "" when baked).
std::string read_primitive(const Asset& asset, const BakeOptions& options, const Json& prim,
                           const std::string& where, PrimitiveInput* input) {
    const int mode = prim.contains("mode") ? prim["mode"].get<int>() : 4;
    if (mode < 4) return std::string(kModeNames[mode]) + " primitive left as it is";
    const Json& attributes = prim["attributes"];
    if (!attributes.contains("POSITION")) return "no POSITION attribute: nothing to bake";
    const std::string set_name = "TEXCOORD_" + std::to_string(options.texcoord);
    if (attributes.contains(set_name) && !options.overwrite) {
        throw GltfError("texcoord_exists", where + " already has " + set_name +
                                               "; pass --overwrite to replace it, or --texcoord N "
                                               "to write another set");
    }
    const std::string missing = missing_data(asset, prim);
    if (!missing.empty()) {
        return missing + " lies in a placeholder buffer (no data in the file): left as it is";
    }
    const int position = attributes["POSITION"].get<int>();
    const AccessorLayout pa = accessor_layout(asset.doc, position);
    if (pa.type != "VEC3" ||
        (pa.component_type != kFloat && component_size(pa.component_type) > 2)) {
        throw GltfError("accessor", where +
                                        ": POSITION must be VEC3 (float, or "
                                        "KHR_mesh_quantization integers)");
    }
    input->mode = mode;
    input->vertex_count = pa.count;
    std::vector<uint32_t> vertices;
    const char* zeros =
        "every triangle is degenerate (POSITION or indices all zeros: no "
        "bufferView, no sparse substitution): nothing to map";
    if (prim.contains("indices")) {
        if (!read_checked_indices(asset, prim["indices"].get<int>(), pa.count, where, &vertices))
            return zeros;
    } else if (!all_zeros(asset, position)) {
        vertices.resize(input->vertex_count);
        for (uint32_t i = 0; i < vertices.size(); ++i) vertices[i] = i;
    }
    if (all_zeros(asset, position)) return zeros;
    input->triangles = triangle_list(mode, vertices);
    if (input->triangles.empty()) return "no complete triangle";
    if (!any_triangle_has_area(input->triangles,
                               corner_positions(asset, position, input->triangles, where))) {
        return "every triangle is degenerate (repeated vertices or zero area): nothing to map";
    }
    input->tangents = tangent_policy(asset.doc, prim, options.texcoord);
    return "";
}

}  // namespace

Selection select_primitives(const Asset& asset, const BakeOptions& options,
                            std::vector<SkipReport>* skipped, const std::vector<bool>* drawn) {
    Selection selection;
    const Json& meshes = array_of(asset.doc, "meshes");
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Json& primitives = meshes[m]["primitives"];
        if (drawn && !(*drawn)[m]) {
            for (size_t p = 0; p < primitives.size(); ++p) {
                skipped->push_back({int(m), int(p),
                                    "the default scene does not draw this mesh, or only under "
                                    "transforms that flatten it (a zero scale) or overflow "
                                    "doubles (a scale near 1e308): left as it is"});
            }
            continue;
        }
        std::vector<PrimitiveInput> mesh_group;
        for (size_t p = 0; p < primitives.size(); ++p) {
            const std::string where =
                "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            PrimitiveInput input;
            input.index = static_cast<int>(p);
            input.json = &primitives[p];
            const std::string reason = read_primitive(asset, options, primitives[p], where, &input);
            if (!reason.empty()) {
                skipped->push_back({int(m), int(p), reason});
            } else if (options.grouping != Grouping::kPrimitive) {
                mesh_group.push_back(std::move(input));
            } else {
                selection.groups.push_back({std::move(input)});
                selection.group_mesh.push_back(int(m));
            }
        }
        if (!mesh_group.empty()) {
            selection.groups.push_back(std::move(mesh_group));
            selection.group_mesh.push_back(int(m));
        }
    }
    return selection;
}

}  // namespace raps_gltf
