// Reading members of an untrusted glTF document: every getter checks the JSON type and range and
// throws a GltfError naming the object and the member, so the code that uses a value never sees
// one of the wrong kind.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace raps_gltf {

using Json = nlohmann::ordered_json;

// nullptr when absent.
const Json* member(const Json& object, const char* key);

// The array doc[key] (empty when absent); every entry must be an object.
const Json& array_of(const Json& doc, const char* key);

// An unsigned integer member: absent -> fallback (or an error when required), otherwise a JSON
// integer (or a float with an integral value, which JSON does not tell apart) in [minimum,
// maximum].
uint64_t get_uint(const Json& object, const char* key, const std::string& what, bool required,
                  uint64_t fallback, uint64_t minimum, uint64_t maximum);

// An index into an array of `count` entries: -1 when absent and not required.
int64_t get_index(const Json& object, const char* key, size_t count, const std::string& what,
                  bool required);

// "" when absent.
std::string get_string(const Json& object, const char* key, const std::string& what);

std::vector<std::string> string_list(const Json& doc, const char* key);

// Integer-valued glTF members written as floats ("buffer": 1.0, which the specification's JSON
// allows and the validator accepts) become JSON integers, so that later code can compare and
// renumber them as integers. Only members that glTF defines as integers are touched.
void normalize_integers(Json& doc);

}  // namespace raps_gltf
