// Phase B of the nested dissection (dissection.h): the tree found on a coarse level is
// projected level by level to the full graph, and on every second level each separator, top
// down, moves to the minimum vertex cut of a band around it (vertex_cut.h).
#include <cstdlib>
#include <limits>

#include "core/fill_in_runs.h"
#include "solver/dissection.h"

namespace raps {
namespace dissection {

// ---------------------------------------------------------------------------------------
// Phase B: every vertex of a level carries the tree node it belongs to (a leaf part or the
// separator of an inner node). Labels are projected to the next finer level, where every
// separator, top down, moves to the minimum cut of a band around it.

void Dissection::project_labels(size_t l) {
    const GraphLevel& level = levels_[l];
    // Phase B's share of this level (run() reports its end).
    const double step = (kRefined - kDissected) / static_cast<double>(base_);
    const double from = kDissected + step * static_cast<double>(base_ - l - 1);
    // Fresh pages touched in runs (11 MB on the finest level at 2.8M vertices: 50 ms at once).
    std::vector<int32_t> fine_label =
        filled_in_runs(static_cast<size_t>(level.size()), 0, progress_.part(from, from));
    for (int32_t v = 0; v < level.size(); ++v) {
        progress_.at(v, level.size(), from, from + step);
        fine_label[v] = label_[level.parent[v]];
    }
    label_.swap(fine_label);
}

void Dissection::refine_all(size_t l) {
    const GraphLevel& level = levels_[l];
    const int32_t count = static_cast<int32_t>(nodes_.size());
    // Weight of every subtree (an id range): prefix sums over the node ids.
    std::vector<int64_t> prefix(count + 1, 0);
    separators_.assign(count, {});
    for (int32_t v = 0; v < level.size(); ++v) {
        prefix[label_[v] + 1] += level.weights[v];
        if (internal(label_[v])) separators_[label_[v]].push_back(v);
    }
    for (int32_t i = 0; i < count; ++i) prefix[i + 1] += prefix[i];
    for (int32_t node = 0; node < count; ++node) {
        if (!internal(node)) continue;
        refine_separator(l, node, prefix);
        progress_.report(kDissected);  // a band around one separator
    }
}

void Dissection::refine_separator(size_t l, int32_t node, const std::vector<int64_t>& prefix) {
    const int32_t mark = ++stamp_;
    if (!grow_separator_band(l, node, prefix, mark)) return;
    build_separator_flow(l, node, mark);
    flow_.solve(std::numeric_limits<int64_t>::max());
    relabel_band(l, node, more_balanced_cut(l, node, prefix));
}

// The band: the separator (its list may hold stale or repeated entries) and layers of the
// subtrees on both sides, each side keeping at least half of its weight outside. Stamps
// the band with `mark`; returns false if the separator is empty.
bool Dissection::grow_separator_band(size_t l, int32_t node, const std::vector<int64_t>& prefix,
                                     int32_t mark) {
    GraphLevel& level = levels_[l];
    const int32_t a = nodes_[node].left, b = nodes_[node].right, end = nodes_[node].end;
    band_.clear();
    for (int32_t v : separators_[node]) {
        if (label_[v] == node && level.stamp[v] != mark) {
            level.stamp[v] = mark;
            band_.push_back(v);
        }
    }
    if (band_.empty()) return false;
    int64_t room[2] = {(prefix[b] - prefix[a]) / 2, (prefix[end] - prefix[b]) / 2};
    size_t layer_start = 0;
    for (int layer = 0; layer < kBandLayers; ++layer) {
        const size_t layer_end = band_.size();
        for (size_t i = layer_start; i < layer_end; ++i) {
            const int32_t v = band_[i];
            for (int32_t p = level.offsets[v]; p < level.offsets[v + 1]; ++p) {
                const int32_t u = level.neighbors[p];
                const int32_t lu = label_[u];
                if (lu <= node || lu >= end || level.stamp[u] == mark) continue;
                int64_t& r = room[lu < b ? 0 : 1];
                if (r < level.weights[u]) continue;
                r -= level.weights[u];
                level.stamp[u] = mark;
                band_.push_back(u);
            }
        }
        layer_start = layer_end;
    }
    return true;
}

// The flow network of the band: its vertices (local indices in level.local) are free, the
// left subtree's vertices around it are the source, the right subtree's the sink.
void Dissection::build_separator_flow(size_t l, int32_t node, int32_t mark) {
    GraphLevel& level = levels_[l];
    const int32_t a = nodes_[node].left, b = nodes_[node].right, end = nodes_[node].end;
    const int32_t f = static_cast<int32_t>(band_.size());
    for (int32_t x = 0; x < f; ++x) level.local[band_[x]] = x;
    flow_.begin(f);
    for (int32_t x = 0; x < f; ++x) {
        const int32_t v = band_[x];
        for (int32_t p = level.offsets[v]; p < level.offsets[v + 1]; ++p) {
            const int32_t u = level.neighbors[p];
            if (u == v) continue;
            if (level.stamp[u] == mark) {
                flow_.add_neighbor(level.local[u]);
                continue;
            }
            const int32_t lu = label_[u];
            if (lu < a || lu >= end) continue;  // outside the subtree: ancestors' separators
            if (lu < b) {
                flow_.touch_source();
            } else {
                flow_.touch_sink();
            }
        }
        flow_.end_vertex();
    }
}

// Of the two extreme minimum cuts, whether the one closest to the source is the more
// balanced (weights of the two subtrees after the cut).
bool Dissection::more_balanced_cut(size_t l, int32_t node,
                                   const std::vector<int64_t>& prefix) const {
    const GraphLevel& level = levels_[l];
    const int32_t a = nodes_[node].left, b = nodes_[node].right, end = nodes_[node].end;
    const int32_t f = static_cast<int32_t>(band_.size());
    int64_t band_left = 0, band_right = 0;
    for (int32_t x = 0; x < f; ++x) {
        const int32_t v = band_[x];
        if (label_[v] != node) (label_[v] < b ? band_left : band_right) += level.weights[v];
    }
    int64_t left[2] = {prefix[b] - prefix[a] - band_left, prefix[b] - prefix[a] - band_left};
    int64_t right[2] = {prefix[end] - prefix[b] - band_right, prefix[end] - prefix[b] - band_right};
    for (int32_t x = 0; x < f; ++x) {
        const int64_t w = level.weights[band_[x]];
        const int8_t sides[2] = {flow_.source_side(x), flow_.sink_side(x)};
        for (int c = 0; c < 2; ++c) {
            left[c] += sides[c] == 0 ? w : 0;
            right[c] += sides[c] == 2 ? w : 0;
        }
    }
    return std::abs(left[0] - right[0]) <= std::abs(left[1] - right[1]);
}

// Relabel. The separator joins `node`; a vertex that changes sides joins the lowest common
// ancestor of its neighbours' nodes on its new side (a part, or a separator refined later
// in this pass), which keeps every edge between a node and one of its descendants: the
// order stays a nested dissection.
void Dissection::relabel_band(size_t l, int32_t node, bool source_cut) {
    const int32_t a = nodes_[node].left, b = nodes_[node].right, end = nodes_[node].end;
    pending_.clear();
    for (int32_t x = 0; x < static_cast<int32_t>(band_.size()); ++x) {
        const int32_t v = band_[x];
        const int8_t s = source_cut ? flow_.source_side(x) : flow_.sink_side(x);
        if (s == 1) {
            label_[v] = node;
            continue;
        }
        const int32_t lo = s == 0 ? a : b, hi = s == 0 ? b : end;
        if (label_[v] >= lo && label_[v] < hi) continue;
        label_[v] = -1 - s;  // no node yet; the side is remembered
        pending_.push_back(v);
    }
    while (!pending_.empty() && place_pending(l, node)) {
    }
    for (int32_t v : pending_) {  // no neighbour on its side: the side's root takes it
        const int32_t root = label_[v] == -1 ? a : b;
        label_[v] = root;
        if (internal(root)) separators_[root].push_back(v);
    }
}

// One pass over the pending vertices: each with a neighbour on its side joins the lowest
// common ancestor of those neighbours' nodes. Returns whether any was placed.
bool Dissection::place_pending(size_t l, int32_t node) {
    const GraphLevel& level = levels_[l];
    const int32_t a = nodes_[node].left, b = nodes_[node].right, end = nodes_[node].end;
    bool placed = false;
    size_t kept = 0;
    for (int32_t v : pending_) {
        const int32_t s = -1 - label_[v];
        const int32_t lo = s == 0 ? a : b, hi = s == 0 ? b : end;
        int32_t found = -1;
        for (int32_t p = level.offsets[v]; p < level.offsets[v + 1]; ++p) {
            const int32_t lu = label_[level.neighbors[p]];
            if (lu < lo || lu >= hi) continue;
            if (found < 0) {
                found = lu;
            } else {
                while (lu < found || lu >= nodes_[found].end) found = tree_parent_[found];
            }
        }
        if (found >= 0) {
            label_[v] = found;
            if (internal(found)) separators_[found].push_back(v);
            placed = true;
        } else {
            pending_[kept++] = v;
        }
    }
    pending_.resize(kept);
    return placed;
}

}  // namespace dissection

}  // namespace raps
