#include "solver/graph_hierarchy.h"

#include <numeric>
#include <utility>

#include "core/fill_in_runs.h"

namespace raps {
namespace {

// Heavy-edge matching visits large levels in index order (mesh numberings are local, which
// keeps the first, most expensive contractions cache friendly) and small ones in a fixed
// pseudo-random order (index order there leaves stars unmatched and stalls the coarsening).
constexpr int32_t kShuffleBelow = 50000;
constexpr int32_t kCoarsestSize = 64;

// Heavy-edge matching (Karypis & Kumar 1998): each vertex is merged with the unmatched
// neighbour it shares the heaviest edge with, the lightest such neighbour on ties. Returns each
// vertex's partner (itself when unmatched).
std::vector<int32_t> heavy_edge_matching(const GraphLevel& fine, const ProgressSpan& progress) {
    const int32_t n = fine.size();
    // Fresh pages filled in runs: at 2.8M vertices these two arrays were 106 ms in one go.
    std::vector<int32_t> visit = filled_in_runs(static_cast<size_t>(n), 0, progress.part(0.0, 0.0));
    std::vector<int32_t> match =
        filled_in_runs(static_cast<size_t>(n), -1, progress.part(0.0, 0.0));
    progress.report(0.0);
    std::iota(visit.begin(), visit.end(), 0);
    if (n < kShuffleBelow) {
        uint64_t state = 0x9E3779B97F4A7C15ull;  // fixed seed: the order is deterministic
        for (int32_t i = n - 1; i > 0; --i) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            std::swap(visit[i], visit[static_cast<int32_t>((state >> 33) % (i + 1))]);
        }
    }
    const bool unit = fine.edge_weights.empty();
    for (int32_t i = 0; i < n; ++i) {
        progress.at(i, 2 * static_cast<int64_t>(n));
        const int32_t v = visit[i];
        if (match[v] >= 0) continue;
        int32_t best = -1, best_weight = -1;
        for (int32_t p = fine.offsets[v]; p < fine.offsets[v + 1]; ++p) {
            const int32_t u = fine.neighbors[p];
            if (match[u] >= 0 || u == v) continue;
            const int32_t w = unit ? 1 : fine.edge_weights[p];
            if (w > best_weight || (w == best_weight && fine.weights[u] < fine.weights[best])) {
                best = u;
                best_weight = w;
            }
        }
        match[v] = best >= 0 ? best : v;
        if (best >= 0) match[best] = v;
    }
    return match;
}

// Numbers the pairs of a matching in the order of their lower vertex: fine.parent[v] is the
// coarse vertex of v's pair; returns each coarse vertex's lower fine vertex.
std::vector<int32_t> number_pairs(GraphLevel& fine, const std::vector<int32_t>& match,
                                  const ProgressSpan& beat) {
    const int32_t n = fine.size();
    assign_in_runs(fine.parent, static_cast<size_t>(n), -1, beat);
    std::vector<int32_t> representative;
    representative.reserve(n / 2 + 1);
    for (int32_t v = 0; v < n; ++v) {
        beat.at(v, n);
        if (fine.parent[v] >= 0) continue;
        fine.parent[v] = fine.parent[match[v]] = static_cast<int32_t>(representative.size());
        representative.push_back(v);
    }
    return representative;
}

// The coarse rows being built, merged from the two fine rows of each pair. Short rows are
// searched linearly (in cache); rows longer than kShortRow switch to slot[d], the position of
// coarse neighbour d in the row being built (valid if >= the row's start), which costs a cache
// miss per entry.
class RowMerger {
  public:
    RowMerger(const GraphLevel& fine, GraphLevel& coarse, int32_t coarse_count,
              const ProgressSpan& beat)
        : fine_(fine),
          neighbors_(coarse.neighbor_store),
          weights_(coarse.edge_weights),
          slot_(filled_in_runs(static_cast<size_t>(coarse_count), -1, beat)) {
        // Reserved, not resized: only the pages written are ever touched.
        neighbors_.reserve(fine.entries());
        weights_.reserve(fine.entries());
    }

    // Appends the fine row of v, less the edges inside coarse vertex c, to row c (begun at
    // `row_start`).
    void add_row(int32_t v, int32_t c, int32_t row_start) {
        const bool unit = fine_.edge_weights.empty();
        for (int32_t p = fine_.offsets[v]; p < fine_.offsets[v + 1]; ++p) {
            const int32_t d = fine_.parent[fine_.neighbors[p]];
            if (d == c) continue;
            const int32_t w = unit ? 1 : fine_.edge_weights[p];
            const int32_t at = find(d, row_start);
            if (at >= 0) {
                weights_[at] += w;
                continue;
            }
            neighbors_.push_back(d);
            weights_.push_back(w);
            if (long_row_) slot_[d] = entries_;
            ++entries_;
            if (!long_row_ && entries_ - row_start > kShortRow) {
                long_row_ = true;
                for (int32_t i = row_start; i < entries_; ++i) slot_[neighbors_[i]] = i;
            }
        }
    }

    // Ends the current row; returns the entries so far (the next row's start).
    int32_t end_row() {
        long_row_ = false;
        return entries_;
    }

  private:
    static constexpr int32_t kShortRow = 16;

    int32_t find(int32_t d, int32_t row_start) const {
        if (long_row_) return slot_[d] >= row_start ? slot_[d] : -1;
        int32_t at = -1;
        for (int32_t i = row_start; i < entries_; ++i) {
            if (neighbors_[i] == d) at = i;
        }
        return at;
    }

    const GraphLevel& fine_;
    std::vector<int32_t>& neighbors_;
    std::vector<int32_t>& weights_;
    std::vector<int32_t> slot_;
    int32_t entries_ = 0;
    bool long_row_ = false;
};

// Contracts each matched pair of `fine` into one vertex of `coarse` (fine.parent: the pair's
// coarse vertex), summing the weights of merged edges; the coarse point is the pair's weighted
// centroid.
void contract(GraphLevel& fine, const std::vector<int32_t>& match, GraphLevel& coarse,
              const ProgressSpan& progress) {
    const ProgressSpan beat = progress.part(0.5, 0.5);
    const std::vector<int32_t> representative = number_pairs(fine, match, beat);
    const int32_t m = static_cast<int32_t>(representative.size());
    assign_in_runs(coarse.weights, static_cast<size_t>(m), 0, beat);
    assign_in_runs(coarse.point_store, static_cast<size_t>(m), Eigen::Vector3d::Zero().eval(),
                   beat);
    assign_in_runs(coarse.offset_store, static_cast<size_t>(m) + 1, 0, beat);
    int32_t* out_offsets = coarse.offset_store.data();
    out_offsets[0] = 0;
    RowMerger rows(fine, coarse, m, beat);
    for (int32_t c = 0; c < m; ++c) {
        progress.at(m + c, 2 * static_cast<int64_t>(m));
        const int32_t a = representative[c], b = match[a];
        rows.add_row(a, c, out_offsets[c]);
        if (b != a) rows.add_row(b, c, out_offsets[c]);
        out_offsets[c + 1] = rows.end_row();
        const int32_t wa = fine.weights[a], wb = a == b ? 0 : fine.weights[b];
        coarse.weights[c] = wa + wb;
        coarse.point_store[c] = (wa * fine.points[a] + wb * fine.points[b]) / (wa + wb);
    }
    coarse.points = coarse.point_store.data();
    coarse.offsets = coarse.offset_store.data();
    coarse.neighbors = coarse.neighbor_store.data();
    coarse.count = m;
}

}  // namespace

std::vector<GraphLevel> build_graph_hierarchy(const SparsePattern& pattern,
                                              const std::vector<Eigen::Vector3d>& coordinates,
                                              const ProgressSpan& progress) {
    std::vector<GraphLevel> levels;
    const int32_t n = pattern.size;
    levels.emplace_back();
    GraphLevel& fine = levels.back();
    fine.offsets = pattern.row_offsets.data();
    fine.neighbors = pattern.columns.data();
    fine.count = n;
    assign_in_runs(fine.weights, static_cast<size_t>(n), 1, progress.part(0.0, 0.0));
    fine.points = coordinates.data();
    while (levels.back().size() > kCoarsestSize) {
        GraphLevel coarse;
        // Each level is about half the one before: the finest takes half the work.
        const double done = 1.0 - static_cast<double>(levels.back().size()) / n;
        const ProgressSpan span = progress.part(done, done + 0.5 * (1.0 - done));
        const std::vector<int32_t> match = heavy_edge_matching(levels.back(), span);
        contract(levels.back(), match, coarse, span);
        if (coarse.size() > 0.9 * levels.back().size()) break;  // no longer shrinking
        levels.push_back(std::move(coarse));
    }
    levels.back().parent.clear();
    // Scratch of every level: tens of megabytes of fresh pages at millions of vertices (an
    // array of the finest level was 40 to 50 ms at 2.8M vertices), filled in runs.
    const ProgressSpan beat = progress.part(1.0, 1.0);
    for (GraphLevel& l : levels) {
        assign_in_runs(l.stamp, static_cast<size_t>(l.size()), 0, beat);
        assign_in_runs(l.local, static_cast<size_t>(l.size()), 0, beat);
        assign_in_runs(l.part_weight, static_cast<size_t>(l.size()), 0, beat);
    }
    return levels;
}

}  // namespace raps
