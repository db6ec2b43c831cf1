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

std::string type_name(int t) {
    switch (t) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "";
    }
}

std::vector<uint8_t> read_accessor(const tinygltf::Model& model, int index) {
    // load_asset checked every range used here against the buffers' sizes.
    const tinygltf::Accessor& a = model.accessors.at(static_cast<size_t>(index));
    const std::string type = type_name(a.type);
    const uint64_t element = element_size(type, a.componentType);
    if (element == 0)
        throw GltfError("accessor", "accessor " + std::to_string(index) + ": bad type");
    std::vector<uint8_t> out(a.count * element, 0);
    if (a.bufferView >= 0) {
        const tinygltf::BufferView& view = model.bufferViews.at(static_cast<size_t>(a.bufferView));
        const std::vector<unsigned char>& buffer = model.buffers.at(view.buffer).data;
        const uint64_t stride = view.byteStride ? view.byteStride : element;
        const uint64_t begin = view.byteOffset + a.byteOffset;
        if (begin + stride * (a.count - 1) + element > buffer.size()) {
            throw GltfError("accessor",
                            "accessor " + std::to_string(index) + " runs past its buffer");
        }
        for (size_t i = 0; i < a.count; ++i)
            std::memcpy(&out[i * element], &buffer[begin + i * stride], element);
    }
    if (a.sparse.isSparse) {
        const auto& s = a.sparse;
        const tinygltf::BufferView& iv = model.bufferViews.at(s.indices.bufferView);
        const tinygltf::BufferView& vv = model.bufferViews.at(s.values.bufferView);
        const std::vector<unsigned char>& ib = model.buffers.at(iv.buffer).data;
        const std::vector<unsigned char>& vb = model.buffers.at(vv.buffer).data;
        const int isize = component_size(s.indices.componentType);
        const uint64_t ibegin = iv.byteOffset + uint64_t(s.indices.byteOffset);
        const uint64_t vbegin = vv.byteOffset + uint64_t(s.values.byteOffset);
        const uint64_t n = uint64_t(s.count);
        if (ibegin + n * isize > ib.size() || vbegin + n * element > vb.size()) {
            throw GltfError("accessor", "accessor " + std::to_string(index) +
                                            ": sparse data runs past its buffer");
        }
        int64_t previous = -1;
        for (uint64_t k = 0; k < n; ++k) {
            const uint8_t* p = &ib[ibegin + k * isize];
            const uint64_t target = isize == 1   ? *p
                                    : isize == 2 ? load<uint16_t>(p)
                                                 : load<uint32_t>(p);
            if (static_cast<int64_t>(target) <= previous || target >= a.count) {
                throw GltfError("accessor", "accessor " + std::to_string(index) +
                                                ": sparse index " + std::to_string(target) +
                                                " is out of order or past the count " +
                                                std::to_string(a.count));
            }
            previous = static_cast<int64_t>(target);
            std::memcpy(&out[target * element], &vb[vbegin + k * element], element);
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

std::vector<uint32_t> read_indices(const tinygltf::Model& model, int accessor) {
    const tinygltf::Accessor& a = model.accessors.at(static_cast<size_t>(accessor));
    const std::vector<uint8_t> data = read_accessor(model, accessor);
    const int size = component_size(a.componentType);
    std::vector<uint32_t> out(a.count);
    for (size_t i = 0; i < a.count; ++i) {
        const uint8_t* p = &data[i * size];
        out[i] = size == 1 ? *p : size == 2 ? load<uint16_t>(p) : load<uint32_t>(p);
    }
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
