#include "gltf_accessor_writer.h"

#include <algorithm>
#include <cstring>

#include "gltf_accessors.h"

namespace raps_gltf {

int AccessorWriter::add_view(std::vector<uint8_t> bytes, uint64_t stride, int target) {
    Json view = Json::object();
    view["buffer"] = 0;  // the writer lays out every bufferView in its one output buffer
    view["byteLength"] = bytes.size();
    if (stride) view["byteStride"] = stride;
    if (target) view["target"] = target;
    Json& views = result_.doc["bufferViews"];
    views.push_back(view);
    result_.new_views.push_back(std::move(bytes));
    return static_cast<int>(views.size() - 1);
}

int AccessorWriter::add_accessor(Json accessor, const Json& like, const std::vector<uint8_t>& data,
                                 bool with_min_max) {
    static const char* kReplaced[] = {"bufferView", "byteOffset", "componentType", "count",
                                      "type",       "min",        "max",           "sparse"};
    for (auto it = like.begin(); like.is_object() && it != like.end(); ++it) {
        const bool replaced = std::any_of(std::begin(kReplaced), std::end(kReplaced),
                                          [&](const char* key) { return it.key() == key; });
        if (!replaced) accessor[it.key()] = it.value();
    }
    if (with_min_max) {
        Json lo, hi;
        min_max(data, accessor["type"].get<std::string>(), accessor["componentType"].get<int>(),
                &lo, &hi);
        accessor["min"] = lo;
        accessor["max"] = hi;
    }
    Json& accessors = result_.doc["accessors"];
    accessors.push_back(accessor);
    return static_cast<int>(accessors.size() - 1);
}

int AccessorWriter::add(const Json& like, const std::string& type, int component_type,
                        uint64_t count, const std::vector<uint8_t>& data, bool vertex_attribute,
                        bool with_min_max) {
    const uint64_t element = element_size(type, component_type);
    const uint64_t stride = vertex_attribute ? (element + 3) / 4 * 4 : element;
    std::vector<uint8_t> bytes(stride * count, 0);
    for (uint64_t i = 0; i < count; ++i)
        std::memcpy(&bytes[i * stride], &data[i * element], element);
    Json accessor = Json::object();
    accessor["bufferView"] = add_view(std::move(bytes), stride != element ? stride : 0,
                                      vertex_attribute ? 34962 : 34963);
    accessor["componentType"] = component_type;
    accessor["count"] = count;
    accessor["type"] = type;
    return add_accessor(std::move(accessor), like, data, with_min_max);
}

int AccessorWriter::copy(const Asset& asset, int source, const std::vector<uint32_t>& vertex_of,
                         const std::vector<uint8_t>& gathered, bool with_min_max) {
    const AccessorLayout a = accessor_layout(asset.doc, source);
    const Json& like = asset.doc["accessors"][static_cast<size_t>(source)];
    if (a.view >= 0) {
        return add(like, a.type, a.component_type, vertex_of.size(), gathered, true, with_min_max);
    }
    Json accessor = Json::object();
    accessor["componentType"] = a.component_type;
    accessor["count"] = vertex_of.size();
    accessor["type"] = a.type;
    const std::vector<uint32_t> substituted = read_sparse_indices(asset, source);
    std::vector<uint8_t> indices, values;
    const uint64_t element = element_size(a.type, a.component_type);
    uint32_t entries = 0;
    for (uint32_t k = 0; k < vertex_of.size(); ++k) {
        if (!std::binary_search(substituted.begin(), substituted.end(), vertex_of[k])) continue;
        indices.insert(indices.end(), reinterpret_cast<const uint8_t*>(&k),
                       reinterpret_cast<const uint8_t*>(&k) + 4);
        values.insert(values.end(), &gathered[k * element], &gathered[k * element] + element);
        ++entries;
    }
    if (entries) {
        // Sparse bufferViews carry no target and no stride (glTF 2.0, 3.6.2.3).
        while (values.size() % 4) values.push_back(0);
        Json sparse = Json::object();
        sparse["count"] = entries;
        sparse["indices"] = {{"bufferView", add_view(std::move(indices), 0, 0)},
                             {"componentType", kUnsignedInt}};
        sparse["values"] = {{"bufferView", add_view(std::move(values), 0, 0)}};
        accessor["sparse"] = sparse;
    }
    return add_accessor(std::move(accessor), like, gathered, with_min_max);
}

}  // namespace raps_gltf
