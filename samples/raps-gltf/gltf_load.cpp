#include "gltf_load.h"

#include <algorithm>
#include <limits>

#include "gltf_accessors.h"
#include "gltf_error.h"
#include "gltf_safety.h"

namespace raps_gltf {

namespace {

// Integers in the document are bounded here so that every later sum and product of offsets,
// strides and counts fits in 64 bits without a check of its own.
constexpr uint64_t kMaxOffset = uint64_t(1) << 40;
constexpr uint64_t kMaxCount = (uint64_t(1) << 31) - 1;
constexpr uint64_t kMaxAccessorBytes = uint64_t(1) << 31;

const Json* member(const Json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

const Json& array_of(const Json& doc, const char* key) {
    static const Json empty = Json::array();
    const Json* value = member(doc, key);
    if (!value) return empty;
    if (!value->is_array()) throw GltfError("json", std::string("'") + key + "' is not an array");
    for (const Json& item : *value) {
        if (!item.is_object()) {
            throw GltfError("json", std::string("an entry of '") + key + "' is not an object");
        }
    }
    return *value;
}

// An unsigned integer member: absent -> fallback (or an error when required), otherwise it must
// be a JSON integer in [minimum, maximum].
uint64_t get_uint(const Json& object, const char* key, const std::string& what, bool required,
                  uint64_t fallback, uint64_t minimum, uint64_t maximum) {
    const Json* value = member(object, key);
    if (!value) {
        if (required) throw GltfError("json", what + ": '" + key + "' is missing");
        return fallback;
    }
    if (!value->is_number_integer() ||
        (value->is_number_integer() && !value->is_number_unsigned() && value->get<int64_t>() < 0)) {
        throw GltfError("json", what + ": '" + key + "' is not a non-negative integer");
    }
    const uint64_t v = value->get<uint64_t>();
    if (v < minimum || v > maximum) {
        throw GltfError("json", what + ": '" + key + "' = " + std::to_string(v) + " is outside [" +
                                    std::to_string(minimum) + ", " + std::to_string(maximum) + "]");
    }
    return v;
}

int64_t get_index(const Json& object, const char* key, size_t count, const std::string& what,
                  bool required) {
    const Json* value = member(object, key);
    if (!value && !required) return -1;
    const uint64_t v = get_uint(object, key, what, true, 0, 0, kMaxCount);
    if (v >= count) {
        throw GltfError("json", what + ": '" + key + "' = " + std::to_string(v) +
                                    " refers to nothing (there are " + std::to_string(count) + ")");
    }
    return static_cast<int64_t>(v);
}

std::string get_string(const Json& object, const char* key, const std::string& what) {
    const Json* value = member(object, key);
    if (!value) return "";
    if (!value->is_string()) throw GltfError("json", what + ": '" + key + "' is not a string");
    return value->get<std::string>();
}

std::vector<std::string> string_list(const Json& doc, const char* key) {
    std::vector<std::string> out;
    const Json* value = member(doc, key);
    if (!value) return out;
    if (!value->is_array()) throw GltfError("json", std::string("'") + key + "' is not an array");
    for (const Json& item : *value) {
        if (!item.is_string())
            throw GltfError("json", std::string("'") + key + "' holds a non-string");
        out.push_back(item.get<std::string>());
    }
    return out;
}

struct ViewInfo {
    uint64_t offset, length, stride;
    size_t buffer;
};

// Checks the document's structure that tinygltf would trust, in the order data depends on it:
// buffers (and their sizes), bufferViews, accessors (sparse included), meshes, images.
void check_document(const Json& doc, const std::string& folder, const GlbParts* glb) {
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
        if (is_required || std::count(used.begin(), used.end(), name) > 0) {
            throw GltfError("unsupported",
                            "the asset " + std::string(is_required ? "requires" : "uses") + " " +
                                name +
                                ", which raps-gltf does not decode: its geometry is compressed, "
                                "and splitting vertices at seams would invalidate the compressed "
                                "data (decompress it first, e.g. gltf-transform copy)");
        }
    }

    // Buffers: the bytes each one really has must match its byteLength.
    const Json& buffers = array_of(doc, "buffers");
    std::vector<uint64_t> buffer_size;
    for (size_t i = 0; i < buffers.size(); ++i) {
        const Json& b = buffers[i];
        const std::string what = "buffer " + std::to_string(i);
        const uint64_t length = get_uint(b, "byteLength", what, true, 0, 1, kMaxOffset);
        const Json* uri_value = member(b, "uri");
        if (!uri_value) {
            if (!glb || i != 0) {
                throw GltfError("buffer", what +
                                              " has no uri (only a GLB's first buffer may "
                                              "live in its BIN chunk)");
            }
            if (!glb->has_bin) throw GltfError("buffer", what + ": the GLB has no BIN chunk");
            if (length > glb->bin_size || glb->bin_size - length > 3) {
                throw GltfError("buffer", what + ": byteLength " + std::to_string(length) +
                                              " does not match the BIN chunk's " +
                                              std::to_string(glb->bin_size) + " bytes");
            }
        } else {
            const std::string uri = get_string(b, "uri", what);
            uint64_t actual = 0;
            if (is_data_uri(uri)) {
                actual = decode_data_uri(uri, what).bytes.size();
            } else {
                const std::string path = resolve_inside(folder, uri, what);
                if (path.empty()) {
                    throw GltfError("io", what + ": '" + uri + "' not found in the asset's folder");
                }
                actual = read_file(path, kMaxFileBytes).size();
            }
            if (actual != length) {
                throw GltfError("buffer", what + ": byteLength " + std::to_string(length) +
                                              " but its data has " + std::to_string(actual) +
                                              " bytes");
            }
        }
        buffer_size.push_back(length);
    }

    const Json& views = array_of(doc, "bufferViews");
    std::vector<ViewInfo> view_info;
    for (size_t i = 0; i < views.size(); ++i) {
        const Json& v = views[i];
        const std::string what = "bufferView " + std::to_string(i);
        ViewInfo info;
        info.buffer = static_cast<size_t>(get_index(v, "buffer", buffers.size(), what, true));
        info.offset = get_uint(v, "byteOffset", what, false, 0, 0, kMaxOffset);
        info.length = get_uint(v, "byteLength", what, true, 0, 1, kMaxOffset);
        info.stride = get_uint(v, "byteStride", what, false, 0, 4, 252);
        if (info.stride % 4 != 0)
            throw GltfError("buffer", what + ": byteStride is not a multiple of 4");
        if (info.offset + info.length > buffer_size[info.buffer]) {
            throw GltfError("buffer", what + ": bytes [" + std::to_string(info.offset) + ", " +
                                          std::to_string(info.offset + info.length) +
                                          ") run past buffer " + std::to_string(info.buffer) +
                                          " (" + std::to_string(buffer_size[info.buffer]) +
                                          " bytes)");
        }
        view_info.push_back(info);
    }

    const Json& accessors = array_of(doc, "accessors");
    std::vector<uint64_t> accessor_count;
    for (size_t i = 0; i < accessors.size(); ++i) {
        const Json& a = accessors[i];
        const std::string what = "accessor " + std::to_string(i);
        const int component_type =
            static_cast<int>(get_uint(a, "componentType", what, true, 0, 0, 1u << 16));
        const std::string type = get_string(a, "type", what);
        const uint64_t element = element_size(type, component_type);
        if (element == 0) {
            throw GltfError("accessor", what + ": unknown type '" + type + "' or componentType " +
                                            std::to_string(component_type));
        }
        const uint64_t count = get_uint(a, "count", what, true, 0, 1, kMaxCount);
        // Reading materialises count elements (zeros without a bufferView, or sparse): bound
        // that memory, since a count alone costs the file nothing.
        if (count * element > kMaxAccessorBytes) {
            throw GltfError("accessor", what + ": " + std::to_string(count) + " elements of " +
                                            std::to_string(element) + " bytes exceed " +
                                            std::to_string(kMaxAccessorBytes) + " bytes");
        }
        if (const Json* normalized = member(a, "normalized");
            normalized && !normalized->is_boolean()) {
            throw GltfError("json", what + ": 'normalized' is not a boolean");
        }
        const int64_t view = get_index(a, "bufferView", views.size(), what, false);
        const uint64_t offset = get_uint(a, "byteOffset", what, false, 0, 0, kMaxOffset);
        const int size = component_size(component_type);
        if (view >= 0) {
            const ViewInfo& v = view_info[static_cast<size_t>(view)];
            if (v.stride && v.stride < element) {
                throw GltfError("accessor", what + ": element of " + std::to_string(element) +
                                                " bytes is longer than the byteStride " +
                                                std::to_string(v.stride));
            }
            if (offset % size != 0 || (v.offset + offset) % size != 0) {
                throw GltfError("accessor", what +
                                                ": byte offset is not a multiple of the "
                                                "component size");
            }
            const uint64_t stride = v.stride ? v.stride : element;
            const uint64_t end = offset + stride * (count - 1) + element;
            if (end > v.length) {
                throw GltfError("accessor", what + ": " + std::to_string(count) + " elements of " +
                                                std::to_string(element) + " bytes (stride " +
                                                std::to_string(stride) + ") from offset " +
                                                std::to_string(offset) + " need " +
                                                std::to_string(end) + " bytes but bufferView " +
                                                std::to_string(view) + " has " +
                                                std::to_string(v.length));
            }
        } else if (member(a, "byteOffset")) {
            throw GltfError("accessor", what + ": byteOffset without a bufferView");
        }
        if (const Json* sparse = member(a, "sparse")) {
            if (!sparse->is_object()) throw GltfError("json", what + ": 'sparse' is not an object");
            const uint64_t n = get_uint(*sparse, "count", what + " sparse", true, 0, 1, count);
            const Json* indices = member(*sparse, "indices");
            const Json* values = member(*sparse, "values");
            if (!indices || !indices->is_object() || !values || !values->is_object()) {
                throw GltfError("json", what + ": sparse needs 'indices' and 'values' objects");
            }
            const int index_type = static_cast<int>(get_uint(
                *indices, "componentType", what + " sparse indices", true, 0, 0, 1u << 16));
            if (index_type != kUnsignedByte && index_type != kUnsignedShort &&
                index_type != kUnsignedInt) {
                throw GltfError("accessor", what + ": sparse indices must be unsigned integers");
            }
            const struct {
                const Json* object;
                uint64_t bytes;
                int alignment;
                const char* name;
            } parts[2] = {
                {indices, n * component_size(index_type), component_size(index_type), "indices"},
                {values, n * element, size, "values"}};
            for (const auto& part : parts) {
                const std::string where = what + " sparse " + part.name;
                const int64_t pv = get_index(*part.object, "bufferView", views.size(), where, true);
                const uint64_t po =
                    get_uint(*part.object, "byteOffset", where, false, 0, 0, kMaxOffset);
                const ViewInfo& v = view_info[static_cast<size_t>(pv)];
                if (v.stride) throw GltfError("accessor", where + ": bufferView has a byteStride");
                if ((v.offset + po) % part.alignment != 0) {
                    throw GltfError("accessor", where + ": misaligned");
                }
                if (po + part.bytes > v.length) {
                    throw GltfError("accessor",
                                    where + ": run past bufferView " + std::to_string(pv));
                }
            }
        }
        accessor_count.push_back(count);
    }

    const Json& meshes = array_of(doc, "meshes");
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Json* primitives = member(meshes[m], "primitives");
        if (!primitives || !primitives->is_array() || primitives->empty()) {
            throw GltfError("mesh", "mesh " + std::to_string(m) + " has no primitives");
        }
        for (size_t p = 0; p < primitives->size(); ++p) {
            const Json& prim = (*primitives)[p];
            const std::string what =
                "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            if (!prim.is_object()) throw GltfError("json", what + " is not an object");
            get_uint(prim, "mode", what, false, 4, 0, 6);
            get_index(prim, "indices", accessors.size(), what, false);
            const Json* attributes = member(prim, "attributes");
            if (!attributes || !attributes->is_object()) {
                throw GltfError("mesh", what + " has no attributes object");
            }
            std::vector<const Json*> maps = {attributes};
            if (const Json* targets = member(prim, "targets")) {
                if (!targets->is_array())
                    throw GltfError("json", what + ": 'targets' is not an array");
                for (const Json& target : *targets) {
                    if (!target.is_object())
                        throw GltfError("json", what + ": a target is not an object");
                    maps.push_back(&target);
                }
            }
            int64_t vertices = -1;
            for (const Json* map : maps) {
                for (auto it = map->begin(); it != map->end(); ++it) {
                    const std::string where = what + " attribute " + it.key();
                    const int64_t a =
                        get_index(*map, it.key().c_str(), accessors.size(), where, true);
                    const uint64_t count = accessor_count[static_cast<size_t>(a)];
                    if (vertices >= 0 && count != static_cast<uint64_t>(vertices)) {
                        throw GltfError("mesh", where + ": accessor " + std::to_string(a) +
                                                    " has " + std::to_string(count) +
                                                    " elements, other attributes " +
                                                    std::to_string(vertices));
                    }
                    vertices = static_cast<int64_t>(count);
                }
            }
        }
    }

    // The other accessor references the output renumbers when it prunes (gltf_output.cpp).
    const Json& skins = array_of(doc, "skins");
    for (size_t i = 0; i < skins.size(); ++i) {
        get_index(skins[i], "inverseBindMatrices", accessors.size(), "skin " + std::to_string(i),
                  false);
    }
    const Json& animations = array_of(doc, "animations");
    for (size_t i = 0; i < animations.size(); ++i) {
        const std::string what = "animation " + std::to_string(i);
        const Json& samplers = array_of(animations[i], "samplers");
        for (size_t k = 0; k < samplers.size(); ++k) {
            const std::string where = what + " sampler " + std::to_string(k);
            get_index(samplers[k], "input", accessors.size(), where, true);
            get_index(samplers[k], "output", accessors.size(), where, true);
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
            get_index(
                *attributes, it.key().c_str(), accessors.size(),
                "node " + std::to_string(i) + " EXT_mesh_gpu_instancing attribute " + it.key(),
                true);
        }
    }

    const Json& images = array_of(doc, "images");
    for (size_t i = 0; i < images.size(); ++i) {
        const Json& image = images[i];
        const std::string what = "image " + std::to_string(i);
        const bool has_view = member(image, "bufferView") != nullptr;
        const bool has_uri = member(image, "uri") != nullptr;
        if (has_view == has_uri)
            throw GltfError("json", what + " needs exactly one of uri and bufferView");
        if (has_view) {
            get_index(image, "bufferView", views.size(), what, true);
            continue;
        }
        const std::string uri = get_string(image, "uri", what);
        if (is_data_uri(uri)) {
            decode_data_uri(uri, what);
        } else if (resolve_inside(folder, uri, what).empty()) {
            throw GltfError("io", what + ": '" + uri + "' not found in the asset's folder");
        }
    }
}

// Images pass through untouched: raps-gltf never decodes or re-encodes them.
bool keep_image_bytes(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                      const unsigned char*, int, void*) {
    return true;
}

}  // namespace

const std::vector<std::string>& refused_extensions() {
    static const std::vector<std::string> names = {
        "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"};
    return names;
}

Asset load_asset(const std::string& path) {
    Asset asset;
    asset.path = path;
    const std::vector<uint8_t> bytes = read_file(path, kMaxFileBytes);
    asset.folder = real_folder_of(path);
    asset.binary = looks_like_glb(bytes);
    GlbParts glb;
    const char* text = reinterpret_cast<const char*>(bytes.data());
    size_t text_size = bytes.size();
    if (asset.binary) {
        glb = split_glb(bytes);
        text += glb.json_offset;
        text_size = glb.json_size;
    }
    check_json_depth(text, text_size, kMaxJsonDepth);
    try {
        asset.doc = Json::parse(text, text + text_size);
    } catch (const nlohmann::json::exception& e) {
        throw GltfError("json", std::string("invalid JSON: ") + e.what());
    }
    check_document(asset.doc, asset.folder, asset.binary ? &glb : nullptr);

    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&keep_image_bytes, nullptr);
    loader.SetFsCallbacks(confined_fs_callbacks(&asset.folder));
    std::string err, warn;
    bool ok;
    if (asset.binary) {
        ok = loader.LoadBinaryFromMemory(&asset.model, &err, &warn, bytes.data(),
                                         static_cast<unsigned int>(bytes.size()), asset.folder);
    } else {
        ok = loader.LoadASCIIFromString(&asset.model, &err, &warn, text,
                                        static_cast<unsigned int>(text_size), asset.folder);
    }
    if (!ok) {
        while (!err.empty() && err.back() == '\n') err.pop_back();
        throw GltfError("gltf", "tinygltf refused the asset: " + err);
    }
    for (size_t start = 0; start < warn.size();) {
        const size_t end = std::min(warn.find('\n', start), warn.size());
        if (end > start) asset.warnings.push_back(warn.substr(start, end - start));
        start = end + 1;
    }
    // Both views must describe the same arrays, or indices into one would not fit the other.
    if (asset.model.accessors.size() != array_of(asset.doc, "accessors").size() ||
        asset.model.meshes.size() != array_of(asset.doc, "meshes").size() ||
        asset.model.bufferViews.size() != array_of(asset.doc, "bufferViews").size() ||
        asset.model.buffers.size() != array_of(asset.doc, "buffers").size()) {
        throw GltfError("internal", "tinygltf and the JSON disagree on the document's arrays");
    }
    for (size_t i = 0; i < asset.model.buffers.size(); ++i) {
        const uint64_t declared = asset.doc["buffers"][i]["byteLength"].get<uint64_t>();
        if (asset.model.buffers[i].data.size() < declared) {
            throw GltfError("buffer", "buffer " + std::to_string(i) + " loaded short");
        }
    }
    return asset;
}

}  // namespace raps_gltf
