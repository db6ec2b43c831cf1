// A chart's lookup from the ids of surface elements to its own positions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace raps {

// Where each surface element (triangle, vertex) sits in a chart's list of them, or -1: an array
// over the whole surface, filled per chart. Searching the chart's sorted list instead, for charts
// under 1/64 of the surface, took 12% fewer instructions on the ten-mesh scene (callgrind) but
// 10% more CPU time (mispredicted branches of the searches against one memset).
class LocalIndex {
  public:
    // ids[i]: the element at position i (the first position wins); `universe`: how many
    // elements the surface has.
    LocalIndex(const std::vector<int32_t>& ids, size_t universe) : position_(universe, -1) {
        for (size_t i = ids.size(); i-- > 0;) position_[ids[i]] = static_cast<int32_t>(i);
    }
    int32_t operator()(int32_t id) const { return position_[id]; }

  private:
    std::vector<int32_t> position_;
};

}  // namespace raps
