#include "solver/leaf_bisection.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace raps {
namespace {

// Pieces of at most this many vertices keep their order: bisecting them down to three vertices
// saved 0.3% of the fill on face.obj x16 for 5% more ordering work. Bisection down to here
// leaves less fill than minimum degree on pieces of up to 32 vertices, which the leaves had
// before (docs/bench-solver.md).
constexpr int32_t kKeepOrderSize = 8;

}  // namespace

// The leaf's induced subgraph is copied into compact local arrays, which stay in cache while
// the bisection passes over them.
void LeafBisection::order(GraphLevel& fine, int32_t mark, const int32_t* ids, int32_t m,
                          std::vector<int32_t>& order) {
    if (m == 0) return;
    for (int32_t k = 0; k < m; ++k) {
        fine.stamp[ids[k]] = mark;
        fine.local[ids[k]] = k;
    }
    copy_subgraph(fine, mark, ids, m);
    piece_.assign(m, 0);
    position_.resize(m);
    side_.resize(m);
    copy_.resize(m);
    order_.clear();
    std::vector<int32_t> local_ids(m);
    std::iota(local_ids.begin(), local_ids.end(), 0);
    bisect(local_ids.data(), m);
    for (int32_t k : order_) order.push_back(ids[k]);
}

void LeafBisection::copy_subgraph(const GraphLevel& fine, int32_t mark, const int32_t* ids,
                                  int32_t m) {
    offsets_.resize(m + 1);
    adjacency_.clear();
    points_.resize(m);
    offsets_[0] = 0;
    for (int32_t k = 0; k < m; ++k) {
        const int32_t v = ids[k];
        for (int32_t p = fine.offsets[v]; p < fine.offsets[v + 1]; ++p) {
            const int32_t u = fine.neighbors[p];
            if (fine.stamp[u] == mark && u != v) adjacency_.push_back(fine.local[u]);
        }
        offsets_[k + 1] = static_cast<int32_t>(adjacency_.size());
        points_[k] = fine.points[v];
    }
}

// Recursive coordinate bisection: the best axis-aligned cut over the three axes and 32
// positions each, within 35-65% balance, scored by the smaller one-sided boundary; a single
// pass over the edges scores all 96 candidates (for each vertex, the lowest and highest bin
// among its neighbours tell which cuts it touches). Works in place on local ids.
void LeafBisection::bisect(int32_t* ids, int32_t m) {
    if (m <= kKeepOrderSize) {
        order_.insert(order_.end(), ids, ids + m);
        return;
    }
    const int32_t piece = ++piece_count_;
    Histogram histogram;
    bin_points(ids, m, piece, histogram);
    assign_sides(ids, m, piece, best_cut(histogram, m));
    split(ids, m);
}

// Fills bins_ (each vertex's bin per axis, and the lowest and highest among its neighbours in
// the piece) and the histogram; marks the piece's vertices with their positions.
void LeafBisection::bin_points(const int32_t* ids, int32_t m, int32_t piece, Histogram& histogram) {
    Eigen::Vector3d lo = points_[ids[0]], hi = lo;
    for (int32_t k = 0; k < m; ++k) {
        piece_[ids[k]] = piece;
        position_[ids[k]] = k;
        lo = lo.cwiseMin(points_[ids[k]]);
        hi = hi.cwiseMax(points_[ids[k]]);
    }
    const size_t size3 = 3 * static_cast<size_t>(m);
    if (bins_.size() < 3 * size3) bins_.resize(3 * size3);
    int* bin = bins_.data();  // three per vertex, one per axis
    int* low = bin + size3;   // lowest neighbour bin
    int* high = low + size3;  // highest neighbour bin
    for (int ax = 0; ax < 3; ++ax) {
        scale_[ax] = hi[ax] > lo[ax] ? kBins / (hi[ax] - lo[ax]) : 0.0;
    }
    for (int32_t k = 0; k < m; ++k) {
        const Eigen::Vector3d& x = points_[ids[k]];
        for (int ax = 0; ax < 3; ++ax) {
            bin[3 * k + ax] = std::min(kBins - 1, static_cast<int>((x[ax] - lo[ax]) * scale_[ax]));
        }
    }
    for (int32_t k = 0; k < m; ++k) {
        const int32_t v = ids[k];
        const int own[3] = {bin[3 * k], bin[3 * k + 1], bin[3 * k + 2]};
        int l0 = own[0], l1 = own[1], l2 = own[2], h0 = own[0], h1 = own[1], h2 = own[2];
        for (int32_t p = offsets_[v]; p < offsets_[v + 1]; ++p) {
            const int32_t u = adjacency_[p];
            if (piece_[u] != piece) continue;
            const int* bu = bin + 3 * position_[u];
            l0 = std::min(l0, bu[0]);
            h0 = std::max(h0, bu[0]);
            l1 = std::min(l1, bu[1]);
            h1 = std::max(h1, bu[1]);
            l2 = std::min(l2, bu[2]);
            h2 = std::max(h2, bu[2]);
        }
        const int lows[3] = {l0, l1, l2}, highs[3] = {h0, h1, h2};
        for (int ax = 0; ax < 3; ++ax) {
            low[3 * k + ax] = lows[ax];
            high[3 * k + ax] = highs[ax];
            ++histogram.count[ax][own[ax]];
            ++histogram.lt[ax][own[ax] + 1];
            --histogram.lt[ax][highs[ax] + 1];
            ++histogram.rt[ax][lows[ax] + 1];
            --histogram.rt[ax][own[ax] + 1];
        }
    }
}

LeafBisection::Cut LeafBisection::best_cut(const Histogram& histogram, int32_t m) const {
    Cut cut;
    int64_t best = std::numeric_limits<int64_t>::max();
    for (int ax = 0; ax < 3; ++ax) {
        if (scale_[ax] == 0.0) continue;
        const auto& lt = histogram.lt[ax];
        const auto& rt = histogram.rt[ax];
        int64_t below = histogram.count[ax][0], ls = lt[0] + lt[1], rs = rt[0] + rt[1];
        for (int b = 1; b < kBins; ++b) {
            if (below >= 0.35 * m && below <= 0.65 * m && std::min(ls, rs) < best) {
                best = std::min(ls, rs);
                cut.axis = ax;
                cut.bin = b;
                cut.left_boundary = ls <= rs;
                cut.found = true;
            }
            below += histogram.count[ax][b];
            ls += lt[b + 1];
            rs += rt[b + 1];
        }
    }
    return cut;
}

void LeafBisection::assign_sides(const int32_t* ids, int32_t m, int32_t piece, const Cut& cut) {
    int8_t* side = side_.data();
    if (!cut.found) {
        // No axis splits it (coincident points): halve by position, one-sided boundary.
        for (int32_t k = 0; k < m; ++k) {
            side[k] = k < m / 2 ? 0 : 2;
            if (k >= m / 2) continue;
            const int32_t v = ids[k];
            for (int32_t p = offsets_[v]; p < offsets_[v + 1]; ++p) {
                const int32_t u = adjacency_[p];
                if (piece_[u] == piece && position_[u] >= m / 2) side[k] = 1;
            }
        }
        return;
    }
    const size_t size3 = 3 * static_cast<size_t>(m);
    const int* bin = bins_.data();
    const int* low = bin + size3;
    const int* high = low + size3;
    const int ax = cut.axis;
    for (int32_t k = 0; k < m; ++k) {
        if (bin[3 * k + ax] < cut.bin) {
            side[k] = cut.left_boundary && high[3 * k + ax] >= cut.bin ? 1 : 0;
        } else {
            side[k] = !cut.left_boundary && low[3 * k + ax] < cut.bin ? 1 : 2;
        }
    }
}

// In place: left, right, separator; orders both halves, then the separator.
void LeafBisection::split(int32_t* ids, int32_t m) {
    int32_t* copy = copy_.data();
    std::copy(ids, ids + m, copy);
    int32_t at = 0, sizes[2] = {0, 0};
    for (int8_t which : {0, 2, 1}) {
        for (int32_t k = 0; k < m; ++k) {
            if (side_[k] == which) ids[at++] = copy[k];
        }
        if (which != 1) sizes[which / 2] = at - (which == 0 ? 0 : sizes[0]);
    }
    bisect(ids, sizes[0]);
    bisect(ids + sizes[0], sizes[1]);
    order_.insert(order_.end(), ids + sizes[0] + sizes[1], ids + m);
}

}  // namespace raps
