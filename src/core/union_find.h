// The root of `v` in a union-find forest stored as parent indices (a root is its own parent),
// with path halving: the welding, instancing and repacking passes group vertices or triangles so.
#pragma once

#include <cstdint>
#include <vector>

namespace raps {

inline int32_t find_root(std::vector<int32_t>& parent, int32_t v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];  // path halving
        v = parent[v];
    }
    return v;
}

}  // namespace raps
