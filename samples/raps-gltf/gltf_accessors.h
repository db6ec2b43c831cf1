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

// An accessor's members, from a document load_asset checked (gltf_document.h).
struct AccessorLayout {
    std::string type;  // "SCALAR" .. "MAT4"
    int component_type = 0;
    uint64_t count = 0;
    bool normalized = false;
    int64_t view = -1;  // -1: no bufferView (zeros, then the sparse substitution)
    uint64_t offset = 0;
    bool sparse = false;
};
AccessorLayout accessor_layout(const Json& doc, int accessor);

// False when the accessor's bufferView, or one of its sparse bufferViews, lies in a placeholder
// buffer: its values are not in the file, and nothing can be read or copied from it.
bool accessor_has_data(const Asset& asset, int accessor);

// The accessor's elements, tightly packed (count * element_size bytes), with its sparse
// substitution applied and zeros when it has no bufferView. Checks sparse indices (strictly
// increasing, below count).
std::vector<uint8_t> read_accessor(const Asset& asset, int accessor);
// Its elements at `vertices` (each below its count), dense and in that order, read without
// decoding the rest: a primitive may use a few elements of a large accessor that hundreds of
// primitives share.
std::vector<uint8_t> read_accessor_at(const Asset& asset, int accessor,
                                      const std::vector<uint32_t>& vertices);

// The element indices an accessor's sparse substitution replaces, increasing (empty without one).
std::vector<uint32_t> read_sparse_indices(const Asset& asset, int accessor);

// Component c of element i of dense data as a double: integers as stored, or mapped to [-1, 1] /
// [0, 1] when normalized.
double component_value(const uint8_t* element, int component_type, bool normalized, int c);

// Indices of an index accessor (SCALAR, unsigned byte/short/int).
std::vector<uint32_t> read_indices(const Asset& asset, int accessor);

// min and max per component of dense data, in the accessor's own component type (the glTF rule:
// raw values, normalization ignored), as JSON arrays.
void min_max(const std::vector<uint8_t>& data, const std::string& type, int component_type,
             Json* min, Json* max);

}  // namespace raps_gltf
