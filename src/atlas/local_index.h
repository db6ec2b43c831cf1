// A chart's lookup from the ids of surface elements to its own positions.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace raps {

// Where each surface element (triangle, vertex) sits in a chart's list of them, or -1. A chart
// much smaller than the surface (the unions merging tries on a scene of many meshes) searches
// its sorted list instead of filling an array over the whole surface for every chart tried.
class LocalIndex {
  public:
    // ids[i]: the element at position i; `universe`: how many elements the surface has.
    LocalIndex(const std::vector<int32_t>& ids, size_t universe) {
        if (ids.size() * kDenseShare >= universe) {
            dense_.assign(universe, -1);
            for (size_t i = ids.size(); i-- > 0;) dense_[ids[i]] = static_cast<int32_t>(i);
            return;
        }
        sorted_.resize(ids.size());
        for (size_t i = 0; i < ids.size(); ++i) sorted_[i] = {ids[i], static_cast<int32_t>(i)};
        if (!std::is_sorted(sorted_.begin(), sorted_.end()))
            std::sort(sorted_.begin(), sorted_.end());
    }
    // The first position of `id` in the list.
    int32_t operator()(int32_t id) const {
        if (!dense_.empty()) return dense_[id];
        const auto it = std::lower_bound(sorted_.begin(), sorted_.end(),
                                         std::make_pair(id, std::numeric_limits<int32_t>::min()));
        return it != sorted_.end() && it->first == id ? it->second : -1;
    }

  private:
    // A chart with at least 1 / kDenseShare of the surface's elements fills the array: its
    // memset costs less than the searches (callgrind, one thread: with 1 / 8, face.obj
    // subdivided once took 2% more instructions than with the array always, the ten-mesh scene
    // 10% fewer).
    static constexpr size_t kDenseShare = 64;
    std::vector<int32_t> dense_;
    std::vector<std::pair<int32_t, int32_t>> sorted_;  // (element, position)
};

}  // namespace raps
