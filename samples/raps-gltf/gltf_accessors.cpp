#include "gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "gltf_error.h"

namespace raps_gltf {

namespace {

// Byte offset of component c inside one element: matrices with 1- and 2-byte components start
// each column on a 4-byte boundary.
uint64_t component_offset(const std::string& type, int component_type, int c) {
    const int size = component_size(component_type);
    const int rows = type == "MAT2" ? 2 : type == "MAT3" ? 3 : type == "MAT4" ? 4 : 0;
    if (rows == 0) return uint64_t(c) * size;
    const uint64_t column = (uint64_t(rows) * size + 3) / 4 * 4;
    return (c / rows) * column + (c % rows) * size;
}

template <typename T>
T load(const uint8_t* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    return value;
}

}  // namespace

int component_size(int component_type) {
    switch (component_type) {
        case kByte:
        case kUnsignedByte:
            return 1;
        case kShort:
        case kUnsignedShort:
            return 2;
        case kUnsignedInt:
        case kFloat:
            return 4;
        default:
            return 0;
    }
}

int component_count(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4" || type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    if (type == "MAT4") return 16;
    return 0;
}

uint64_t element_size(const std::string& type, int component_type) {
    const int count = component_count(type);
    if (count == 0 || component_size(component_type) == 0) return 0;
    return component_offset(type, component_type, count - 1) + component_size(component_type);
}

AccessorLayout accessor_layout(const Json& doc, int index) {
    const Json& a = doc["accessors"].at(static_cast<size_t>(index));
    AccessorLayout out;
    out.type = a["type"].get<std::string>();
    out.component_type = a["componentType"].get<int>();
    out.count = a["count"].get<uint64_t>();
    out.normalized = a.value("normalized", false);
    out.view = a.contains("bufferView") ? a["bufferView"].get<int64_t>() : -1;
    out.offset = a.value("byteOffset", uint64_t(0));
    out.sparse = a.contains("sparse");
    return out;
}

namespace {

struct ViewBytes {
    const std::vector<uint8_t>* buffer;
    uint64_t offset, length, stride;
};

ViewBytes view_bytes(const Asset& asset, uint64_t view) {
    const Json& v = asset.doc["bufferViews"].at(view);
    return {&asset.buffers.at(v["buffer"].get<size_t>()), v.value("byteOffset", uint64_t(0)),
            v["byteLength"].get<uint64_t>(), v.value("byteStride", uint64_t(0))};
}

bool view_has_data(const Asset& asset, uint64_t view) {
    return asset.buffer_has_data.at(asset.doc["bufferViews"].at(view)["buffer"].get<size_t>());
}

uint64_t load_index(const uint8_t* p, int size) {
    return size == 1 ? *p : size == 2 ? load<uint16_t>(p) : load<uint32_t>(p);
}

}  // namespace

bool accessor_has_data(const Asset& asset, int index) {
    const AccessorLayout a = accessor_layout(asset.doc, index);
    if (a.view >= 0 && !view_has_data(asset, static_cast<uint64_t>(a.view))) return false;
    if (!a.sparse) return true;
    const Json& s = asset.doc["accessors"][static_cast<size_t>(index)]["sparse"];
    return view_has_data(asset, s["indices"]["bufferView"].get<uint64_t>()) &&
           view_has_data(asset, s["values"]["bufferView"].get<uint64_t>());
}

std::vector<uint32_t> read_sparse_indices(const Asset& asset, int index) {
    const AccessorLayout a = accessor_layout(asset.doc, index);
    std::vector<uint32_t> out;
    if (!a.sparse) return out;
    const Json& s = asset.doc["accessors"][static_cast<size_t>(index)]["sparse"];
    const ViewBytes iv = view_bytes(asset, s["indices"]["bufferView"].get<uint64_t>());
    const int isize = component_size(s["indices"]["componentType"].get<int>());
    const uint64_t ibegin = iv.offset + s["indices"].value("byteOffset", uint64_t(0));
    const uint64_t n = s["count"].get<uint64_t>();
    if (ibegin + n * isize > iv.buffer->size()) {
        throw GltfError("accessor", "accessor " + std::to_string(index) +
                                        ": sparse indices run past their buffer");
    }
    int64_t previous = -1;
    for (uint64_t k = 0; k < n; ++k) {
        const uint64_t target = load_index(&(*iv.buffer)[ibegin + k * isize], isize);
        if (static_cast<int64_t>(target) <= previous || target >= a.count) {
            throw GltfError("accessor", "accessor " + std::to_string(index) + ": sparse index " +
                                            std::to_string(target) +
                                            " is out of order or past the count " +
                                            std::to_string(a.count));
        }
        previous = static_cast<int64_t>(target);
        out.push_back(static_cast<uint32_t>(target));
    }
    return out;
}

namespace {

// Element i of a run of elements in a buffer: `first` plus i strides.
struct Elements {
    const uint8_t* first;
    uint64_t stride;
    const uint8_t* at(size_t i) const { return first + i * stride; }
};

// The accessor's own elements in its bufferView, checked to lie inside the buffer.
Elements dense_elements(const Asset& asset, int index, const AccessorLayout& a, uint64_t element) {
    const ViewBytes view = view_bytes(asset, static_cast<uint64_t>(a.view));
    const uint64_t stride = view.stride ? view.stride : element;
    const uint64_t begin = view.offset + a.offset;
    if (begin + stride * (a.count - 1) + element > view.buffer->size())
        throw GltfError("accessor", "accessor " + std::to_string(index) + " runs past its buffer");
    return {view.buffer->data() + begin, stride};
}

// The sparse substitution's `count` values, checked to lie inside their buffer.
Elements sparse_values(const Asset& asset, int index, size_t count, uint64_t element) {
    const Json& s = asset.doc["accessors"][static_cast<size_t>(index)]["sparse"];
    const ViewBytes vv = view_bytes(asset, s["values"]["bufferView"].get<uint64_t>());
    const uint64_t vbegin = vv.offset + s["values"].value("byteOffset", uint64_t(0));
    if (vbegin + count * element > vv.buffer->size()) {
        throw GltfError("accessor", "accessor " + std::to_string(index) +
                                        ": sparse values run past their buffer");
    }
    return {vv.buffer->data() + vbegin, element};
}

}  // namespace

std::vector<uint8_t> read_accessor(const Asset& asset, int index) {
    // load_asset checked every range used here against the buffers' sizes.
    const AccessorLayout a = accessor_layout(asset.doc, index);
    const uint64_t element = element_size(a.type, a.component_type);
    if (element == 0)
        throw GltfError("accessor", "accessor " + std::to_string(index) + ": bad type");
    if (!accessor_has_data(asset, index)) {
        throw GltfError("accessor", "accessor " + std::to_string(index) +
                                        " reads a placeholder buffer, which has no data");
    }
    std::vector<uint8_t> out(a.count * element, 0);
    if (a.view >= 0) {
        const Elements dense = dense_elements(asset, index, a, element);
        for (size_t i = 0; i < a.count; ++i)
            std::memcpy(&out[i * element], dense.at(i), element);
    }
    if (a.sparse) {
        const std::vector<uint32_t> targets = read_sparse_indices(asset, index);
        const Elements values = sparse_values(asset, index, targets.size(), element);
        for (size_t k = 0; k < targets.size(); ++k)
            std::memcpy(&out[uint64_t(targets[k]) * element], values.at(k), element);
    }
    return out;
}

std::vector<uint8_t> read_accessor_at(const Asset& asset, int index,
                                      const std::vector<uint32_t>& vertices) {
    const AccessorLayout a = accessor_layout(asset.doc, index);
    const uint64_t element = element_size(a.type, a.component_type);
    // A primitive using most of the accessor: reading it whole is as fast, and checks it all.
    if (element == 0 || !accessor_has_data(asset, index) || vertices.size() >= a.count / 2) {
        const std::vector<uint8_t> whole = read_accessor(asset, index);
        std::vector<uint8_t> out(vertices.size() * element);
        for (size_t i = 0; i < vertices.size(); ++i)
            std::memcpy(&out[i * element], &whole[uint64_t(vertices[i]) * element], element);
        return out;
    }
    std::vector<uint8_t> out(vertices.size() * element, 0);
    if (a.view >= 0) {
        const Elements dense = dense_elements(asset, index, a, element);
        for (size_t i = 0; i < vertices.size(); ++i) {
            if (vertices[i] >= a.count) throw GltfError("internal", "vertex past the accessor");
            std::memcpy(&out[i * element], dense.at(vertices[i]), element);
        }
    }
    if (a.sparse) {
        const std::vector<uint32_t> targets = read_sparse_indices(asset, index);
        const Elements values = sparse_values(asset, index, targets.size(), element);
        for (size_t i = 0; i < vertices.size(); ++i) {  // targets are increasing
            const auto it = std::lower_bound(targets.begin(), targets.end(), vertices[i]);
            if (it == targets.end() || *it != vertices[i]) continue;
            std::memcpy(&out[i * element], values.at(static_cast<size_t>(it - targets.begin())),
                        element);
        }
    }
    return out;
}

double component_value(const uint8_t* element, int component_type, bool normalized, int c) {
    const uint8_t* p = element + uint64_t(c) * component_size(component_type);
    switch (component_type) {
        case kFloat:
            return load<float>(p);
        case kByte: {
            const double v = load<int8_t>(p);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case kUnsignedByte:
            return normalized ? *p / 255.0 : *p;
        case kShort: {
            const double v = load<int16_t>(p);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case kUnsignedShort:
            return normalized ? load<uint16_t>(p) / 65535.0 : load<uint16_t>(p);
        case kUnsignedInt:
            return load<uint32_t>(p);
        default:
            return 0;
    }
}

std::vector<uint32_t> read_indices(const Asset& asset, int accessor) {
    const AccessorLayout a = accessor_layout(asset.doc, accessor);
    const std::vector<uint8_t> data = read_accessor(asset, accessor);
    const int size = component_size(a.component_type);
    std::vector<uint32_t> out(a.count);
    for (size_t i = 0; i < a.count; ++i)
        out[i] = static_cast<uint32_t>(load_index(&data[i * size], size));
    return out;
}

void min_max(const std::vector<uint8_t>& data, const std::string& type, int component_type,
             Json* min, Json* max) {
    const int count = component_count(type);
    const uint64_t element = element_size(type, component_type);
    const size_t n = element ? data.size() / element : 0;
    *min = Json::array();
    *max = Json::array();
    for (int c = 0; c < count; ++c) {
        const uint64_t offset = component_offset(type, component_type, c);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (size_t i = 0; i < n; ++i) {
            const double v = component_value(&data[i * element + offset], component_type, false, 0);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
        if (component_type == kFloat) {
            min->push_back(lo);
            max->push_back(hi);
        } else {
            min->push_back(static_cast<int64_t>(lo));
            max->push_back(static_cast<int64_t>(hi));
        }
    }
}

}  // namespace raps_gltf
