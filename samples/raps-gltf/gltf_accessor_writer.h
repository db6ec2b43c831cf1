// New accessors for the baked primitives, each with bufferViews of its own appended to the
// bake's result (the output writer lays them into its one buffer).
//
// Values are copied, never invented: an attribute whose accessor had no bufferView (all zeros by
// the specification, then its sparse substitution) gets an accessor without a bufferView too,
// with a sparse substitution for exactly the output vertices that copy a substituted input
// vertex. Writing such zeros out explicitly would hand the validator values it never checked
// (zero normals, zero tangent signs) and make a valid asset invalid.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gltf_bake.h"

namespace raps_gltf {

class AccessorWriter {
  public:
    explicit AccessorWriter(BakeResult& result) : result_(result) {}

    // An accessor holding `data` (count tightly packed elements), padded to a 4-byte stride for
    // vertex attributes as glTF requires. `like` is the accessor whose members (name,
    // normalized, extensions, extras) the new one keeps.
    int add(const Json& like, const std::string& type, int component_type, uint64_t count,
            const std::vector<uint8_t>& data, bool vertex_attribute, bool with_min_max);

    // Element vertex_of[k] of input accessor `source` for every output vertex k, laid out as the
    // source was (see above). `gathered` holds those elements, already read.
    int copy(const Asset& asset, int source, const std::vector<uint32_t>& vertex_of,
             const std::vector<uint8_t>& gathered, bool with_min_max);

  private:
    int add_view(std::vector<uint8_t> bytes, uint64_t stride, int target);
    int add_accessor(Json accessor, const Json& like, const std::vector<uint8_t>& data,
                     bool with_min_max);

    BakeResult& result_;
};

}  // namespace raps_gltf
