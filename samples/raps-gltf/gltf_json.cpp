#include "gltf_json.h"

#include <cmath>
#include <set>

#include "gltf_error.h"

namespace raps_gltf {

namespace {

bool is_integral(const Json& value) {
    if (value.is_number_integer()) return true;
    if (!value.is_number_float()) return false;
    const double v = value.get<double>();
    return std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 9007199254740992.0 &&
           !(v == 0 && std::signbit(v));
}

void make_integer(Json& value) {
    if (value.is_number_float() && is_integral(value)) {
        const double v = value.get<double>();
        if (v < 0) {
            value = static_cast<int64_t>(v);
        } else {
            value = static_cast<uint64_t>(v);
        }
    }
}

void normalize(Json& value) {
    static const std::set<std::string> kScalars = {"buffer",
                                                   "bufferView",
                                                   "byteOffset",
                                                   "byteLength",
                                                   "byteStride",
                                                   "target",
                                                   "componentType",
                                                   "count",
                                                   "mode",
                                                   "indices",
                                                   "material",
                                                   "mesh",
                                                   "skin",
                                                   "camera",
                                                   "scene",
                                                   "skeleton",
                                                   "inverseBindMatrices",
                                                   "input",
                                                   "output",
                                                   "sampler",
                                                   "source",
                                                   "index",
                                                   "texCoord",
                                                   "magFilter",
                                                   "minFilter",
                                                   "wrapS",
                                                   "wrapT",
                                                   "node",
                                                   "light"};
    static const std::set<std::string> kArrays = {"children", "nodes", "joints", "variants"};
    if (value.is_array()) {
        for (Json& item : value) normalize(item);
        return;
    }
    if (!value.is_object()) return;
    for (auto it = value.begin(); it != value.end(); ++it) {
        const std::string& key = it.key();
        Json& v = it.value();
        if (key == "extras") continue;  // the user's own data, kept as written
        if (kScalars.count(key)) {
            make_integer(v);
        } else if (kArrays.count(key) && v.is_array()) {
            for (Json& item : v) make_integer(item);
        } else if (key == "attributes" && v.is_object()) {
            for (auto a = v.begin(); a != v.end(); ++a) make_integer(a.value());
        } else if (key == "targets" && v.is_array()) {
            for (Json& target : v) {
                if (!target.is_object()) continue;
                for (auto a = target.begin(); a != target.end(); ++a) make_integer(a.value());
            }
        }
        normalize(v);
    }
}

}  // namespace

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

uint64_t get_uint(const Json& object, const char* key, const std::string& what, bool required,
                  uint64_t fallback, uint64_t minimum, uint64_t maximum) {
    const Json* value = member(object, key);
    if (!value) {
        if (required) throw GltfError("json", what + ": '" + key + "' is missing");
        return fallback;
    }
    if (!is_integral(*value) ||
        (value->is_number_integer() && !value->is_number_unsigned() && value->get<int64_t>() < 0) ||
        (value->is_number_float() && value->get<double>() < 0)) {
        throw GltfError("json", what + ": '" + key + "' is not a non-negative integer");
    }
    const uint64_t v = value->is_number_float() ? static_cast<uint64_t>(value->get<double>())
                                                : value->get<uint64_t>();
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
    const uint64_t v = get_uint(object, key, what, true, 0, 0, (uint64_t(1) << 31) - 1);
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

void normalize_integers(Json& doc) {
    normalize(doc);
}

}  // namespace raps_gltf
