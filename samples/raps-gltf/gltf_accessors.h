// Accessor layout rules (glTF 2.0 section 3.6) and reading accessor data into dense arrays.
// Every range is checked with 64-bit arithmetic on values already bounded by load_asset, so no
// product or sum can wrap; reads never leave their bufferView.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gltf_load.h"

namespace raps_gltf {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123,
              kUnsignedInt = 5125, kFloat = 5126;

// 0 for an unknown component type or type name.
int component_size(int component_type);
int component_count(const std::string& type);
// Bytes of one element, with the column padding matrices of 1- and 2-byte components get.
uint64_t element_size(const std::string& type, int component_type);
// tinygltf's numeric type (TINYGLTF_TYPE_*) as the glTF name.
std::string type_name(int tinygltf_type);

// The accessor's elements, tightly packed (count * element_size bytes), with its sparse
// substitution applied and zeros when it has no bufferView. Checks sparse indices (strictly
// increasing, below count).
std::vector<uint8_t> read_accessor(const tinygltf::Model& model, int accessor);

// Component c of element i of dense data as a double: integers as stored, or mapped to [-1, 1] /
// [0, 1] when normalized.
double component_value(const uint8_t* element, int component_type, bool normalized, int c);

// Indices of an index accessor (SCALAR, unsigned byte/short/int).
std::vector<uint32_t> read_indices(const tinygltf::Model& model, int accessor);

// min and max per component of dense data, in the accessor's own component type (the glTF rule:
// raw values, normalization ignored), as JSON arrays.
void min_max(const std::vector<uint8_t>& data, const std::string& type, int component_type,
             Json* min, Json* max);

}  // namespace raps_gltf
