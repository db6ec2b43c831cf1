#include "gltf_document.h"

#include <algorithm>
#include <set>

#include "gltf_accessors.h"
#include "gltf_error.h"

namespace raps_gltf {

namespace {

// Integers in the document are bounded here so that every later sum and product of offsets,
// strides and counts fits in 64 bits without a check of its own.
constexpr uint64_t kMaxOffset = uint64_t(1) << 40;
constexpr uint64_t kMaxCount = (uint64_t(1) << 31) - 1;
constexpr uint64_t kMaxAccessorBytes = uint64_t(1) << 31;

struct ViewInfo {
    uint64_t offset, length, stride;
};

struct AccessorInfo {
    uint64_t count = 0;
    bool known = false;  // a type and componentType glTF defines
};

std::string str(uint64_t v) {
    return std::to_string(v);
}

std::vector<ViewInfo> check_views(const Json& doc, const std::vector<uint64_t>& buffer_sizes) {
    const Json& views = array_of(doc, "bufferViews");
    std::vector<ViewInfo> out;
    for (size_t i = 0; i < views.size(); ++i) {
        const Json& v = views[i];
        const std::string what = "bufferView " + str(i);
        const size_t buffer =
            static_cast<size_t>(get_index(v, "buffer", buffer_sizes.size(), what, true));
        ViewInfo info;
        info.offset = get_uint(v, "byteOffset", what, false, 0, 0, kMaxOffset);
        info.length = get_uint(v, "byteLength", what, true, 0, 1, kMaxOffset);
        info.stride = get_uint(v, "byteStride", what, false, 0, 4, 252);
        if (info.stride % 4 != 0)
            throw GltfError("buffer", what + ": byteStride is not a multiple of 4");
        if (info.offset + info.length > buffer_sizes[buffer]) {
            throw GltfError("buffer", what + ": bytes [" + str(info.offset) + ", " +
                                          str(info.offset + info.length) + ") run past buffer " +
                                          str(buffer) + " (" + str(buffer_sizes[buffer]) +
                                          " bytes)");
        }
        out.push_back(info);
    }
    return out;
}

void check_dense_range(const Json& a, const std::string& what, const std::vector<ViewInfo>& views,
                       uint64_t count, uint64_t element, int size) {
    const int64_t view = get_index(a, "bufferView", views.size(), what, false);
    const uint64_t offset = get_uint(a, "byteOffset", what, false, 0, 0, kMaxOffset);
    if (view < 0) {
        if (member(a, "byteOffset"))
            throw GltfError("accessor", what + ": byteOffset without a bufferView");
        return;
    }
    const ViewInfo& v = views[static_cast<size_t>(view)];
    if (v.stride && v.stride < element) {
        throw GltfError("accessor", what + ": element of " + str(element) +
                                        " bytes is longer than the byteStride " + str(v.stride));
    }
    if (offset % size != 0 || (v.offset + offset) % size != 0) {
        throw GltfError("accessor", what + ": byte offset is not a multiple of the component size");
    }
    const uint64_t stride = v.stride ? v.stride : element;
    const uint64_t end = offset + stride * (count - 1) + element;
    if (end > v.length) {
        throw GltfError("accessor", what + ": " + str(count) + " elements of " + str(element) +
                                        " bytes (stride " + str(stride) + ") from offset " +
                                        str(offset) + " need " + str(end) +
                                        " bytes but bufferView " + str(view) + " has " +
                                        str(v.length));
    }
}

void check_sparse(const Json& sparse, const std::string& what, const std::vector<ViewInfo>& views,
                  uint64_t count, uint64_t element, int size) {
    if (!sparse.is_object()) throw GltfError("json", what + ": 'sparse' is not an object");
    const uint64_t n = get_uint(sparse, "count", what + " sparse", true, 0, 1, count);
    const Json* indices = member(sparse, "indices");
    const Json* values = member(sparse, "values");
    if (!indices || !indices->is_object() || !values || !values->is_object()) {
        throw GltfError("json", what + ": sparse needs 'indices' and 'values' objects");
    }
    const int index_type = static_cast<int>(
        get_uint(*indices, "componentType", what + " sparse indices", true, 0, 0, 1u << 16));
    if (index_type != kUnsignedByte && index_type != kUnsignedShort && index_type != kUnsignedInt) {
        throw GltfError("accessor", what + ": sparse indices must be unsigned integers");
    }
    const struct {
        const Json* object;
        uint64_t bytes;
        int alignment;
        const char* name;
    } parts[2] = {{indices, n * component_size(index_type), component_size(index_type), "indices"},
                  {values, n * element, size, "values"}};
    for (const auto& part : parts) {
        const std::string where = what + " sparse " + part.name;
        const int64_t pv = get_index(*part.object, "bufferView", views.size(), where, true);
        const uint64_t po = get_uint(*part.object, "byteOffset", where, false, 0, 0, kMaxOffset);
        const ViewInfo& v = views[static_cast<size_t>(pv)];
        if (v.stride) throw GltfError("accessor", where + ": bufferView has a byteStride");
        if ((v.offset + po) % part.alignment != 0)
            throw GltfError("accessor", where + ": misaligned");
        if (po + part.bytes > v.length) {
            throw GltfError("accessor", where + ": run past bufferView " + str(pv));
        }
    }
}

// An accessor of a type glTF does not define is kept as it is when nothing raps-gltf reads uses
// it (the validator accepts such an unused accessor); a use of one is refused where it is found.
std::vector<AccessorInfo> check_accessors(const Json& doc, const std::vector<ViewInfo>& views) {
    const Json& accessors = array_of(doc, "accessors");
    std::vector<AccessorInfo> out;
    for (size_t i = 0; i < accessors.size(); ++i) {
        const Json& a = accessors[i];
        const std::string what = "accessor " + str(i);
        AccessorInfo info;
        const int component_type =
            static_cast<int>(get_uint(a, "componentType", what, true, 0, 0, 1u << 16));
        const Json* type = member(a, "type");
        const uint64_t element =
            type && type->is_string() ? element_size(type->get<std::string>(), component_type) : 0;
        info.count = get_uint(a, "count", what, true, 0, 1, kMaxCount);
        info.known = element != 0;
        if (!info.known) {
            out.push_back(info);
            continue;
        }
        // Reading materialises count elements (zeros without a bufferView, or sparse): bound
        // that memory, since a count alone costs the file nothing.
        if (info.count * element > kMaxAccessorBytes) {
            throw GltfError("accessor", what + ": " + str(info.count) + " elements of " +
                                            str(element) + " bytes exceed " +
                                            str(kMaxAccessorBytes) + " bytes");
        }
        if (const Json* normalized = member(a, "normalized");
            normalized && !normalized->is_boolean()) {
            throw GltfError("json", what + ": 'normalized' is not a boolean");
        }
        const int size = component_size(component_type);
        check_dense_range(a, what, views, info.count, element, size);
        if (const Json* sparse = member(a, "sparse")) {
            check_sparse(*sparse, what, views, info.count, element, size);
        }
        out.push_back(info);
    }
    return out;
}

int64_t accessor_use(const Json& object, const char* key,
                     const std::vector<AccessorInfo>& accessors, const std::string& what,
                     bool required) {
    const int64_t a = get_index(object, key, accessors.size(), what, required);
    if (a >= 0 && !accessors[static_cast<size_t>(a)].known) {
        throw GltfError("accessor", what + ": accessor " + str(a) +
                                        " has a type or componentType glTF does not define");
    }
    return a;
}

void check_primitive(const Json& prim, const std::string& what,
                     const std::vector<AccessorInfo>& accessors, size_t materials) {
    if (!prim.is_object()) throw GltfError("json", what + " is not an object");
    get_uint(prim, "mode", what, false, 4, 0, 6);
    accessor_use(prim, "indices", accessors, what, false);
    get_index(prim, "material", materials, what, false);
    const Json* attributes = member(prim, "attributes");
    if (!attributes || !attributes->is_object()) {
        throw GltfError("mesh", what + " has no attributes object");
    }
    std::vector<const Json*> maps = {attributes};
    if (const Json* targets = member(prim, "targets")) {
        if (!targets->is_array()) throw GltfError("json", what + ": 'targets' is not an array");
        for (const Json& target : *targets) {
            if (!target.is_object()) throw GltfError("json", what + ": a target is not an object");
            maps.push_back(&target);
        }
    }
    int64_t vertices = -1;
    for (const Json* map : maps) {
        for (auto it = map->begin(); it != map->end(); ++it) {
            const std::string where = what + " attribute " + it.key();
            const int64_t a = accessor_use(*map, it.key().c_str(), accessors, where, true);
            const uint64_t count = accessors[static_cast<size_t>(a)].count;
            if (vertices >= 0 && count != static_cast<uint64_t>(vertices)) {
                throw GltfError("mesh", where + ": accessor " + str(a) + " has " + str(count) +
                                            " elements, other attributes " + str(vertices));
            }
            vertices = static_cast<int64_t>(count);
        }
    }
}

void check_meshes(const Json& doc, const std::vector<AccessorInfo>& accessors) {
    const Json& meshes = array_of(doc, "meshes");
    const size_t materials = array_of(doc, "materials").size();
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Json* primitives = member(meshes[m], "primitives");
        if (!primitives || !primitives->is_array() || primitives->empty()) {
            throw GltfError("mesh", "mesh " + str(m) + " has no primitives");
        }
        for (size_t p = 0; p < primitives->size(); ++p) {
            check_primitive((*primitives)[p], "mesh " + str(m) + " primitive " + str(p), accessors,
                            materials);
        }
    }
}

// The other accessor references the output renumbers when it prunes (gltf_output.cpp).
void check_other_accessor_users(const Json& doc, const std::vector<AccessorInfo>& accessors) {
    const Json& skins = array_of(doc, "skins");
    for (size_t i = 0; i < skins.size(); ++i) {
        accessor_use(skins[i], "inverseBindMatrices", accessors, "skin " + str(i), false);
    }
    const Json& animations = array_of(doc, "animations");
    for (size_t i = 0; i < animations.size(); ++i) {
        const Json& samplers = array_of(animations[i], "samplers");
        for (size_t k = 0; k < samplers.size(); ++k) {
            const std::string where = "animation " + str(i) + " sampler " + str(k);
            accessor_use(samplers[k], "input", accessors, where, true);
            accessor_use(samplers[k], "output", accessors, where, true);
        }
        const Json& channels = array_of(animations[i], "channels");
        for (size_t k = 0; k < channels.size(); ++k) {
            get_index(channels[k], "sampler", samplers.size(),
                      "animation " + str(i) + " channel " + str(k), true);
        }
    }
    const Json& nodes = array_of(doc, "nodes");
    for (size_t i = 0; i < nodes.size(); ++i) {
        const Json* extensions = member(nodes[i], "extensions");
        const Json* instancing = extensions && extensions->is_object()
                                     ? member(*extensions, "EXT_mesh_gpu_instancing")
                                     : nullptr;
        const Json* attributes =
            instancing && instancing->is_object() ? member(*instancing, "attributes") : nullptr;
        if (!attributes || !attributes->is_object()) continue;
        for (auto it = attributes->begin(); it != attributes->end(); ++it) {
            accessor_use(*attributes, it.key().c_str(), accessors,
                         "node " + str(i) + " EXT_mesh_gpu_instancing attribute " + it.key(), true);
        }
    }
}

std::vector<uint64_t> index_list(const Json& object, const char* key, size_t count,
                                 const std::string& what) {
    std::vector<uint64_t> out;
    const Json* list = member(object, key);
    if (!list) return out;
    if (!list->is_array()) throw GltfError("json", what + ": '" + key + "' is not an array");
    for (const Json& item : *list) {
        const Json wrapped = {{key, item}};
        out.push_back(static_cast<uint64_t>(get_index(wrapped, key, count, what, true)));
    }
    return out;
}

// A scene is a forest: a node with two parents, or a node among its own ancestors, would be
// copied into the output, where any traversal of the scene visits it twice or never ends.
void check_node_graph(const Json& doc) {
    const Json& nodes = array_of(doc, "nodes");
    const size_t n = nodes.size();
    std::vector<int64_t> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
        const std::string what = "node " + str(i);
        get_index(nodes[i], "mesh", array_of(doc, "meshes").size(), what, false);
        get_index(nodes[i], "skin", array_of(doc, "skins").size(), what, false);
        get_index(nodes[i], "camera", array_of(doc, "cameras").size(), what, false);
        for (uint64_t child : index_list(nodes[i], "children", n, what)) {
            if (child == i) throw GltfError("node", what + " is its own child (a cycle)");
            if (parent[child] >= 0) {
                throw GltfError("node", "node " + str(child) + " has two parents (nodes " +
                                            str(parent[child]) + " and " + str(i) +
                                            "): a scene must be a forest");
            }
            parent[child] = static_cast<int64_t>(i);
        }
    }
    // One parent each: a cycle is a parent chain that comes back to where it started.
    std::vector<uint8_t> state(n, 0);  // 0 unseen, 1 on the current chain, 2 known to reach a root
    for (size_t start = 0; start < n; ++start) {
        std::vector<size_t> chain;
        int64_t at = static_cast<int64_t>(start);
        while (at >= 0 && state[at] == 0) {
            state[at] = 1;
            chain.push_back(static_cast<size_t>(at));
            at = parent[at];
        }
        if (at >= 0 && state[at] == 1) {
            throw GltfError("node", "nodes form a cycle through node " + str(at) +
                                        " (each is an ancestor of itself)");
        }
        for (size_t c : chain) state[c] = 2;
    }
    const Json& skins = array_of(doc, "skins");
    for (size_t i = 0; i < skins.size(); ++i) {
        index_list(skins[i], "joints", n, "skin " + str(i));
        get_index(skins[i], "skeleton", n, "skin " + str(i), false);
    }
    const Json& scenes = array_of(doc, "scenes");
    for (size_t i = 0; i < scenes.size(); ++i) index_list(scenes[i], "nodes", n, "scene " + str(i));
    get_index(doc, "scene", scenes.size(), "the document", false);
    const Json& animations = array_of(doc, "animations");
    for (size_t i = 0; i < animations.size(); ++i) {
        const Json& channels = array_of(animations[i], "channels");
        for (size_t k = 0; k < channels.size(); ++k) {
            const Json* target = member(channels[k], "target");
            if (target && target->is_object()) {
                get_index(*target, "node", n, "animation " + str(i) + " channel " + str(k), false);
            }
        }
    }
}

}  // namespace

const std::vector<std::string>& refused_extensions() {
    static const std::vector<std::string> names = {
        "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"};
    return names;
}

void check_header(const Json& doc) {
    if (!doc.is_object()) throw GltfError("json", "the document is not a JSON object");
    const Json* asset = member(doc, "asset");
    if (!asset || !asset->is_object()) throw GltfError("json", "no 'asset' object (not glTF 2.0)");
    const std::string version = get_string(*asset, "version", "asset");
    if (version.compare(0, 2, "2.") != 0) {
        throw GltfError("unsupported", "asset.version is '" + version + "', not glTF 2.x");
    }
    const std::vector<std::string> required = string_list(doc, "extensionsRequired");
    const std::vector<std::string> used = string_list(doc, "extensionsUsed");
    for (const std::string& name : refused_extensions()) {
        const bool is_required = std::count(required.begin(), required.end(), name) > 0;
        // Draco beside uncompressed accessors is read from those (drop_draco_fallback_copies).
        const bool has_fallback = name == "KHR_draco_mesh_compression" && !is_required;
        if (is_required || (!has_fallback && std::count(used.begin(), used.end(), name) > 0)) {
            throw GltfError("unsupported",
                            "the asset " + std::string(is_required ? "requires" : "uses") + " " +
                                name +
                                ", which raps-gltf does not decode: its geometry is compressed, "
                                "and splitting vertices at seams would invalidate the compressed "
                                "data (decompress it first, e.g. gltf-transform copy)");
        }
    }
    for (const std::string& name : required) {
        if (!extension_is_known(name)) {
            throw GltfError("unsupported", "the asset requires " + name +
                                               ", which raps-gltf does not know: it may change "
                                               "what the geometry means, so the asset is not read");
        }
    }
}

std::string drop_draco_fallback_copies(Json& doc) {
    const char* kDraco = "KHR_draco_mesh_compression";
    const std::vector<std::string> used = string_list(doc, "extensionsUsed");
    if (std::count(used.begin(), used.end(), kDraco) == 0) return "";
    const Json& accessors = array_of(doc, "accessors");
    size_t dropped = 0;
    if (doc.contains("meshes") && doc["meshes"].is_array()) {
        for (size_t m = 0; m < doc["meshes"].size(); ++m) {
            Json& mesh = doc["meshes"][m];
            if (!mesh.is_object() || !mesh.contains("primitives")) continue;
            for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
                Json& primitive = mesh["primitives"][p];
                if (!primitive.is_object() || !primitive.contains("extensions") ||
                    !primitive["extensions"].is_object() ||
                    !primitive["extensions"].contains(kDraco))
                    continue;
                const Json* attributes = member(primitive, "attributes");
                const Json* position = attributes ? member(*attributes, "POSITION") : nullptr;
                const bool readable = position && position->is_number_unsigned() &&
                                      position->get<uint64_t>() < accessors.size() &&
                                      (member(accessors[position->get<size_t>()], "bufferView") ||
                                       member(accessors[position->get<size_t>()], "sparse"));
                if (!readable) {
                    throw GltfError("unsupported",
                                    "mesh " + std::to_string(m) + " primitive " +
                                        std::to_string(p) + " has its geometry only in " + kDraco +
                                        ", which raps-gltf does not decode (decompress it first, "
                                        "e.g. gltf-transform copy)");
                }
                primitive["extensions"].erase(kDraco);
                if (primitive["extensions"].empty()) primitive.erase("extensions");
                ++dropped;
            }
        }
    }
    Json kept = Json::array();
    for (const std::string& name : used) {
        if (name != kDraco) kept.push_back(name);
    }
    if (kept.empty()) {
        doc.erase("extensionsUsed");
    } else {
        doc["extensionsUsed"] = kept;
    }
    if (dropped == 0) return "";
    return "read the uncompressed accessors of " + std::to_string(dropped) +
           " Draco-compressed primitive(s) and dropped their compressed copies, which would not "
           "carry the new uvs";
}

void check_document(const Json& doc, const std::vector<uint64_t>& buffer_sizes) {
    const std::vector<ViewInfo> views = check_views(doc, buffer_sizes);
    const std::vector<AccessorInfo> accessors = check_accessors(doc, views);
    check_meshes(doc, accessors);
    check_other_accessor_users(doc, accessors);
    check_node_graph(doc);
    const Json& images = array_of(doc, "images");
    for (size_t i = 0; i < images.size(); ++i) {
        const bool has_view = member(images[i], "bufferView") != nullptr;
        if (has_view == (member(images[i], "uri") != nullptr)) {
            throw GltfError("json", "image " + str(i) + " needs exactly one of uri and bufferView");
        }
        if (has_view) get_index(images[i], "bufferView", views.size(), "image " + str(i), true);
    }
}

bool extension_is_known(const std::string& name) {
    static const std::set<std::string> kKnown = {
        "KHR_texture_transform",  "KHR_mesh_quantization",  "KHR_lights_punctual",
        "KHR_texture_basisu",     "EXT_texture_webp",       "EXT_texture_avif",
        "KHR_materials_variants", "KHR_xmp_json_ld",        "EXT_mesh_gpu_instancing",
        "KHR_animation_pointer",  "EXT_lights_image_based", "KHR_materials_pbrSpecularGlossiness"};
    return kKnown.count(name) || name.compare(0, 14, "KHR_materials_") == 0;
}

}  // namespace raps_gltf
