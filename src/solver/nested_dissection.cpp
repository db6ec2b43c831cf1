#include "solver/nested_dissection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include <Eigen/Eigenvalues>

#include "solver/vertex_cut.h"

namespace raps {
namespace {

// Tuning, measured on face.obj subdivided twice, face.obj, a 400x400 grid and the disk meshes of
// the test data (see the header comment for the resulting numbers).

// Parts whose vertex weight is at most the leaf size are ordered by recursive coordinate
// bisection instead of flow-based dissection: below a few thousand vertices the separators are
// short and cheap geometric cuts lose little, while flows would dominate the running time. Small
// graphs afford flows further down.
constexpr double kLeafDivisor = 200;
constexpr int32_t kMinLeafSize = 256;
constexpr int32_t kMaxLeafSize = 2048;
// Pieces of at most this many vertices keep their order: bisecting them down to three vertices
// saved 0.3% of the fill on face.obj x16 for 5% more ordering work. Bisection down to here
// leaves less fill than minimum degree on pieces of up to 32 vertices, which the leaves had
// before (docs/bench-solver.md).
constexpr int32_t kKeepOrderSize = 8;
// The tree is first built on the coarsest level that still has 1/8 of the vertices, then
// projected down and refined level by level.
constexpr double kBaseRatio = 8;
// Inertial flow runs on the coarsest level where the part has at most weight / 16 vertices,
// clamped to [64, 1500]: enough resolution for a good cut, few enough vertices for the flows.
constexpr double kFlowRatio = 16;
constexpr int32_t kFlowMinVertices = 64;
constexpr int32_t kFlowMaxVertices = 1500;
// Source and sink of inertial flow: the first and last 30% of the part along a direction, so
// both sides of the cut keep at least 30% of it.
constexpr double kAlpha = 0.3;
// Refinement bands: the projected separator plus two layers of vertices on each side, taking
// at most (1 - kKeepFraction) of the part (phase A) or half of a subtree (phase B) so that the
// source and the sink never vanish.
constexpr int kBandLayers = 2;
constexpr double kKeepFraction = 0.2;
// Heavy-edge matching visits large levels in index order (mesh numberings are local, which
// keeps the first, most expensive contractions cache friendly) and small ones in a fixed
// pseudo-random order (index order there leaves stars unmatched and stalls the coarsening).
constexpr int32_t kShuffleBelow = 50000;
constexpr int32_t kCoarsestSize = 64;

// A graph of the multilevel hierarchy (Hendrickson & Leland 1995; Karypis & Kumar 1998).
struct Level {
    // Adjacency in compressed rows. Level 0 points into the pattern itself, diagonal included
    // (the loops below skip a vertex's own entry where it matters); coarser levels own their
    // storage and have no diagonal.
    const int32_t* offsets = nullptr;
    const int32_t* neighbors = nullptr;
    int32_t count = 0;
    std::vector<int32_t> offset_store, neighbor_store;
    std::vector<int32_t> edge_weights;        // empty on level 0: all 1
    std::vector<int32_t> weights;             // fine vertices per vertex
    const Eigen::Vector3d* points = nullptr;  // level 0: the caller's coordinates
    std::vector<Eigen::Vector3d> point_store;
    std::vector<int32_t> parent;  // vertex of the next coarser level
    // Scratch of phase A: the part being separated is stamped, with local indices and the
    // weight of the part's fine vertices under each vertex.
    std::vector<int32_t> stamp, local, part_weight;

    int32_t size() const { return count; }
    int32_t entries() const { return offsets[count]; }
};

// Dissection tree nodes are numbered in preorder, so a subtree is an id range: a node is a leaf
// or has a separator and two children, `left` = id + 1 and `right`.
struct TreeNode {
    int32_t left = -1, right = -1;
    int32_t end = 0;  // the subtree is [id, end)
};

class Dissection {
  public:
    Dissection(const SparsePattern& pattern, const std::vector<Eigen::Vector3d>& coordinates,
               const ProgressSpan& progress)
        : pattern_(pattern),
          progress_(progress),
          leaf_size_(static_cast<int32_t>(std::clamp(pattern.size / kLeafDivisor,
                                                     double{kMinLeafSize}, double{kMaxLeafSize}))) {
        build_hierarchy(coordinates);
    }

    std::vector<int32_t> run() {
        const int32_t n = pattern_.size;
        order_.reserve(n);
        if (n == 0) return std::move(order_);
        // Phase A: recursive bisection of the base level.
        while (base_ + 1 < levels_.size() &&
               levels_[base_ + 1].size() * kBaseRatio >= static_cast<double>(n)) {
            ++base_;
        }
        lists_.resize(levels_.size());
        sides_.resize(levels_.size());
        {
            std::vector<int32_t> ids(levels_[base_].size());
            std::iota(ids.begin(), ids.end(), 0);
            label_.assign(ids.size(), 0);
            base_weight_ = static_cast<double>(n);
            dissect(ids);
        }
        progress_.report(kDissected);
        // Phase B: project the tree to the finer levels, refining every separator on every
        // second level (refining on the others too measured no better).
        for (size_t l = base_; l-- > 0;) {
            project_labels(l);
            if (l % 2 == 0) refine_all(l);
            progress_.report(kDissected + (kRefined - kDissected) * (base_ - l) / base_);
        }
        // Phase C: the order.
        emit();
        return std::move(order_);
    }

  private:
    // ---------------------------------------------------------------------------------------
    // The hierarchy.

    void build_hierarchy(const std::vector<Eigen::Vector3d>& coordinates) {
        const int32_t n = pattern_.size;
        levels_.emplace_back();
        Level& fine = levels_.back();
        fine.offsets = pattern_.row_offsets.data();
        fine.neighbors = pattern_.columns.data();
        fine.count = n;
        fine.weights.assign(n, 1);
        progress_.report(0.0);
        fine.points = coordinates.data();
        while (levels_.back().size() > kCoarsestSize) {
            Level coarse;
            // Each level is about half the one before: the finest takes half the work.
            const double done = 1.0 - static_cast<double>(levels_.back().size()) / n;
            coarsen(levels_.back(), coarse,
                    progress_.part(kBuilt * done, kBuilt * (done + 0.5 * (1.0 - done))));
            if (coarse.size() > 0.9 * levels_.back().size()) break;  // no longer shrinking
            levels_.push_back(std::move(coarse));
        }
        levels_.back().parent.clear();
        // Scratch of every level: tens of megabytes of fresh pages at millions of vertices, a
        // report per level and array.
        for (Level& l : levels_) {
            l.stamp.assign(l.size(), 0);
            progress_.report(kBuilt);
            l.local.assign(l.size(), 0);
            progress_.report(kBuilt);
            l.part_weight.assign(l.size(), 0);
            progress_.report(kBuilt);
        }
    }

    // Heavy-edge matching (Karypis & Kumar 1998): each vertex is merged with the unmatched
    // neighbour it shares the heaviest edge with, the lightest such neighbour on ties.
    void coarsen(Level& fine, Level& coarse, const ProgressSpan& progress) {
        const int32_t n = fine.size();
        std::vector<int32_t> visit(n), match(n, -1);
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
        fine.parent.assign(n, -1);
        std::vector<int32_t> representative;
        representative.reserve(n / 2 + 1);
        for (int32_t v = 0; v < n; ++v) {
            if (fine.parent[v] >= 0) continue;
            fine.parent[v] = fine.parent[match[v]] = static_cast<int32_t>(representative.size());
            representative.push_back(v);
        }
        const int32_t m = static_cast<int32_t>(representative.size());
        coarse.weights.resize(m);
        coarse.point_store.resize(m);
        coarse.offset_store.resize(m + 1);
        // Reserved, not resized: only the pages written are ever touched.
        std::vector<int32_t>& out_neighbors = coarse.neighbor_store;
        std::vector<int32_t>& out_weights = coarse.edge_weights;
        out_neighbors.reserve(fine.entries());
        out_weights.reserve(fine.entries());
        int32_t* out_offsets = coarse.offset_store.data();
        const int32_t* parent = fine.parent.data();
        // Merging the two rows: short rows are searched linearly (in cache); rows longer than
        // kShortRow switch to slot[d], the position of coarse neighbour d in the row being
        // built (valid if >= the row's start), which costs a cache miss per entry.
        constexpr int32_t kShortRow = 16;
        std::vector<int32_t> slot(m, -1);
        int32_t entries = 0;
        out_offsets[0] = 0;
        for (int32_t c = 0; c < m; ++c) {
            progress.at(m + c, 2 * static_cast<int64_t>(m));
            const int32_t a = representative[c], b = match[a];
            const int32_t row_start = entries;
            bool long_row = false;
            for (int q = 0; q < (a == b ? 1 : 2); ++q) {
                const int32_t v = q == 0 ? a : b;
                for (int32_t p = fine.offsets[v]; p < fine.offsets[v + 1]; ++p) {
                    const int32_t d = parent[fine.neighbors[p]];
                    if (d == c) continue;
                    const int32_t w = unit ? 1 : fine.edge_weights[p];
                    int32_t at = -1;
                    if (long_row) {
                        if (slot[d] >= row_start) at = slot[d];
                    } else {
                        for (int32_t i = row_start; i < entries; ++i) {
                            if (out_neighbors[i] == d) at = i;
                        }
                    }
                    if (at >= 0) {
                        out_weights[at] += w;
                        continue;
                    }
                    out_neighbors.push_back(d);
                    out_weights.push_back(w);
                    if (long_row) slot[d] = entries;
                    ++entries;
                    if (!long_row && entries - row_start > kShortRow) {
                        long_row = true;
                        for (int32_t i = row_start; i < entries; ++i) slot[out_neighbors[i]] = i;
                    }
                }
            }
            out_offsets[c + 1] = entries;
            const int32_t wa = fine.weights[a], wb = a == b ? 0 : fine.weights[b];
            coarse.weights[c] = wa + wb;
            coarse.point_store[c] = (wa * fine.points[a] + wb * fine.points[b]) / (wa + wb);
        }
        coarse.points = coarse.point_store.data();
        coarse.offsets = coarse.offset_store.data();
        coarse.neighbors = coarse.neighbor_store.data();
        coarse.count = m;
    }

    // ---------------------------------------------------------------------------------------
    // Phase A: recursive bisection of the base level, each cut found multilevel: inertial flow
    // on a coarse level, then minimum cuts in a band around the projected separator on every
    // level down to the base (the V-cycle of METIS, with flows in place of Fiduccia-Mattheyses).

    int32_t new_node() {
        nodes_.emplace_back();
        tree_parent_.push_back(-1);
        return static_cast<int32_t>(nodes_.size()) - 1;
    }

    // Builds the subtree of the part `ids` (base-level vertices); returns its root.
    int32_t dissect(std::vector<int32_t>& ids) {
        const int32_t node = new_node();
        const Level& base = levels_[base_];
        int64_t weight = 0;
        for (int32_t v : ids) weight += base.weights[v];
        bool split = weight > leaf_size_ && ids.size() >= 3;
        std::vector<int32_t> left_ids, right_ids;
        if (split) {
            separate(ids);
            const std::vector<int8_t>& side = sides_[base_];
            for (size_t k = 0; k < ids.size(); ++k) {
                if (side[k] == 0) left_ids.push_back(ids[k]);
                if (side[k] == 2) right_ids.push_back(ids[k]);
                if (side[k] == 1) label_[ids[k]] = node;
            }
            // A cut with an empty side does not help (a degenerate part): keep it whole.
            split = !left_ids.empty() && !right_ids.empty();
        }
        if (!split) {
            // A leaf: its weight is done; one report per separator or leaf (a few hundred
            // vertices each at least).
            leaf_weight_ += static_cast<double>(weight);
            report_dissected();
            for (int32_t v : ids) label_[v] = node;
            nodes_[node].end = node + 1;
            return node;
        }
        std::vector<int32_t>().swap(ids);  // release before recursing
        const int32_t left = dissect(left_ids);
        const int32_t right = dissect(right_ids);
        nodes_[node].left = left;
        nodes_[node].right = right;
        nodes_[node].end = static_cast<int32_t>(nodes_.size());
        tree_parent_[left] = tree_parent_[right] = node;
        return node;
    }

    // Fills sides_[base_] for ids: 0 left, 1 separator, 2 right.
    void separate(const std::vector<int32_t>& ids) {
        const int32_t part = ++stamp_;
        lists_[base_] = ids;
        int64_t weight = 0;
        {
            Level& l = levels_[base_];
            for (size_t k = 0; k < ids.size(); ++k) {
                l.stamp[ids[k]] = part;
                l.local[ids[k]] = static_cast<int32_t>(k);
                l.part_weight[ids[k]] = l.weights[ids[k]];
                weight += l.weights[ids[k]];
            }
        }
        // The part on the coarser levels: the vertices with fine vertices in it.
        const int32_t target = std::clamp(static_cast<int32_t>(weight / kFlowRatio),
                                          kFlowMinVertices, kFlowMaxVertices);
        size_t top = base_;
        while (top + 1 < levels_.size() && static_cast<int32_t>(lists_[top].size()) > target) {
            const Level& l = levels_[top];
            Level& c = levels_[top + 1];
            std::vector<int32_t>& up = lists_[top + 1];
            up.clear();
            for (int32_t a : lists_[top]) {
                const int32_t p = l.parent[a];
                if (c.stamp[p] != part) {
                    c.stamp[p] = part;
                    c.local[p] = static_cast<int32_t>(up.size());
                    c.part_weight[p] = 0;
                    up.push_back(p);
                }
                c.part_weight[p] += l.part_weight[a];
            }
            ++top;
        }
        report_dissected();
        inertial_flow(top, part);
        // The largest parts' bands hold tens of thousands of vertices: a report per level.
        for (size_t l = top; l-- > base_;) {
            report_dissected();
            refine(l, part);
        }
    }

    // Phase A's fraction: the weight of the leaves done.
    void report_dissected() const {
        progress_.report(kBuilt + (kDissected - kBuilt) * leaf_weight_ / base_weight_);
    }

    // Inertial flow (Schild & Sommer 2015): along each of a few directions, the minimum vertex
    // cut between the first and the last kAlpha of the part. The cut may bend anywhere in the
    // middle 40%, so it goes around dense regions of the mesh that any plane would cross.
    void inertial_flow(size_t l, int32_t part) {
        const Level& level = levels_[l];
        const std::vector<int32_t>& list = lists_[l];
        const int32_t n = static_cast<int32_t>(list.size());
        double total = 0;
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (int32_t a : list) {
            total += level.part_weight[a];
            centroid += level.part_weight[a] * level.points[a];
        }
        centroid /= total;
        Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
        for (int32_t a : list) {
            const Eigen::Vector3d d = level.points[a] - centroid;
            covariance += level.part_weight[a] * d * d.transpose();
        }
        // The principal axes in the part's plane and the two diagonals between them; the
        // normal axis never helped.
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
        const Eigen::Vector3d major = eigen.eigenvectors().col(2);
        const Eigen::Vector3d middle = eigen.eigenvectors().col(1);
        const Eigen::Vector3d directions[] = {major, middle, (major + middle).normalized(),
                                              (major - middle).normalized()};
        std::vector<int8_t>& best = sides_[l];
        std::vector<int8_t> side(n);
        std::vector<double> key(n);
        std::vector<int32_t> rank(n);
        int64_t best_cut = std::numeric_limits<int64_t>::max(), best_imbalance = 0;
        for (const Eigen::Vector3d& direction : directions) {
            for (int32_t k = 0; k < n; ++k) key[k] = direction.dot(level.points[list[k]]);
            // Ties broken by index, so that coincident points still split.
            std::iota(rank.begin(), rank.end(), 0);
            auto less = [&](int32_t a, int32_t b) {
                return key[a] < key[b] || (key[a] == key[b] && a < b);
            };
            const int32_t lo = std::max<int32_t>(1, static_cast<int32_t>(kAlpha * n));
            const int32_t hi = std::max(lo + 1, n - lo);
            std::nth_element(rank.begin(), rank.begin() + lo, rank.end(), less);
            std::nth_element(rank.begin() + lo, rank.begin() + hi, rank.end(), less);
            band_.clear();
            int64_t fixed_left = 0, fixed_right = 0;
            for (int32_t k = 0; k < lo; ++k) {
                side[rank[k]] = 0;
                fixed_left += level.part_weight[list[rank[k]]];
            }
            for (int32_t k = lo; k < hi; ++k) {
                side[rank[k]] = 1;
                band_.push_back(rank[k]);
            }
            for (int32_t k = hi; k < n; ++k) side[rank[k]] = 2;
            // A sink vertex next to a source vertex (a long edge) would make every cut
            // infinite: let it join the band.
            for (int32_t k = hi; k < n; ++k) {
                const int32_t a = list[rank[k]];
                bool touches = false;
                for (int32_t p = level.offsets[a]; p < level.offsets[a + 1] && !touches; ++p) {
                    const int32_t b = level.neighbors[p];
                    touches = level.stamp[b] == part && side[level.local[b]] == 0;
                }
                if (touches) {
                    side[rank[k]] = 1;
                    band_.push_back(rank[k]);
                } else {
                    fixed_right += level.part_weight[a];
                }
            }
            // Directions whose flow reaches the best cut so far are abandoned early.
            int64_t cut = 0, imbalance = 0;
            if (!band_cut(l, part, side, best_cut, fixed_left, fixed_right, cut, imbalance)) {
                continue;
            }
            if (cut < best_cut || (cut == best_cut && imbalance < best_imbalance)) {
                best_cut = cut;
                best_imbalance = imbalance;
                best = side;
            }
        }
    }

    // Projects the sides of the next coarser level to level l and moves the separator to the
    // minimum cut of a band around it.
    void refine(size_t l, int32_t part) {
        const Level& level = levels_[l];
        const Level& coarse = levels_[l + 1];
        const std::vector<int32_t>& list = lists_[l];
        const std::vector<int8_t>& coarse_side = sides_[l + 1];
        const int32_t n = static_cast<int32_t>(list.size());
        std::vector<int8_t>& side = sides_[l];
        side.resize(n);
        band_.clear();
        int64_t fixed[3] = {0, 0, 0}, total = 0;
        for (int32_t k = 0; k < n; ++k) {
            side[k] = coarse_side[coarse.local[level.parent[list[k]]]];
            if (side[k] == 1) band_.push_back(k);
            fixed[side[k]] += level.part_weight[list[k]];
            total += level.part_weight[list[k]];
        }
        const int64_t keep = static_cast<int64_t>(kKeepFraction * total);
        size_t layer_start = 0;
        for (int layer = 0; layer < kBandLayers; ++layer) {
            const size_t layer_end = band_.size();
            for (size_t i = layer_start; i < layer_end; ++i) {
                const int32_t a = list[band_[i]];
                for (int32_t p = level.offsets[a]; p < level.offsets[a + 1]; ++p) {
                    const int32_t b = level.neighbors[p];
                    if (level.stamp[b] != part) continue;
                    const int32_t kb = level.local[b];
                    if (side[kb] != 1 && fixed[side[kb]] - level.part_weight[b] >= keep) {
                        fixed[side[kb]] -= level.part_weight[b];
                        side[kb] = 1;
                        band_.push_back(kb);
                    }
                }
            }
            layer_start = layer_end;
        }
        int64_t cut = 0, imbalance = 0;
        band_cut(l, part, side, std::numeric_limits<int64_t>::max(), fixed[0], fixed[2], cut,
                 imbalance);
    }

    // Minimum vertex cut through band_ (local indices of side 1) between the vertices of side 0
    // and side 2 of the part on level l; of the two extreme minimum cuts, the more balanced.
    // Rewrites the band's sides; returns false (sides undefined) once the flow reaches limit.
    bool band_cut(size_t l, int32_t part, std::vector<int8_t>& side, int64_t limit,
                  int64_t fixed_left, int64_t fixed_right, int64_t& cut, int64_t& imbalance) {
        const Level& level = levels_[l];
        const std::vector<int32_t>& list = lists_[l];
        const int32_t f = static_cast<int32_t>(band_.size());
        if (band_index_.size() < list.size()) band_index_.resize(list.size());
        for (int32_t x = 0; x < f; ++x) band_index_[band_[x]] = x;
        flow_.begin(f);
        for (int32_t x = 0; x < f; ++x) {
            const int32_t a = list[band_[x]];
            for (int32_t p = level.offsets[a]; p < level.offsets[a + 1]; ++p) {
                const int32_t b = level.neighbors[p];
                if (level.stamp[b] != part || b == a) continue;
                const int8_t sb = side[level.local[b]];
                if (sb == 1) {
                    flow_.add_neighbor(band_index_[level.local[b]]);
                } else if (sb == 0) {
                    flow_.touch_source();
                } else {
                    flow_.touch_sink();
                }
            }
            flow_.end_vertex();
        }
        if (!flow_.solve(limit)) return false;
        const int64_t imbalance_a = imbalance_of(level, list, fixed_left, fixed_right, true);
        const int64_t imbalance_b = imbalance_of(level, list, fixed_left, fixed_right, false);
        const bool source_cut = imbalance_a <= imbalance_b;
        for (int32_t x = 0; x < f; ++x) {
            side[band_[x]] = source_cut ? flow_.source_side(x) : flow_.sink_side(x);
        }
        cut = flow_.cut_size();
        imbalance = source_cut ? imbalance_a : imbalance_b;
        return true;
    }

    int64_t imbalance_of(const Level& level, const std::vector<int32_t>& list, int64_t left,
                         int64_t right, bool source_cut) const {
        for (int32_t x = 0; x < static_cast<int32_t>(band_.size()); ++x) {
            const int8_t s = source_cut ? flow_.source_side(x) : flow_.sink_side(x);
            const int64_t w = level.part_weight[list[band_[x]]];
            left += s == 0 ? w : 0;
            right += s == 2 ? w : 0;
        }
        return std::abs(left - right);
    }

    // ---------------------------------------------------------------------------------------
    // Phase B: every vertex of a level carries the tree node it belongs to (a leaf part or the
    // separator of an inner node). Labels are projected to the next finer level, where every
    // separator, top down, moves to the minimum cut of a band around it.

    bool internal(int32_t node) const { return nodes_[node].left >= 0; }

    void project_labels(size_t l) {
        const Level& level = levels_[l];
        std::vector<int32_t> fine_label(level.size());
        // Phase B's share of this level (run() reports its end).
        const double step = (kRefined - kDissected) / static_cast<double>(base_);
        const double from = kDissected + step * static_cast<double>(base_ - l - 1);
        for (int32_t v = 0; v < level.size(); ++v) {
            progress_.at(v, level.size(), from, from + step);
            fine_label[v] = label_[level.parent[v]];
        }
        label_.swap(fine_label);
    }

    void refine_all(size_t l) {
        const Level& level = levels_[l];
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

    void refine_separator(size_t l, int32_t node, const std::vector<int64_t>& prefix) {
        Level& level = levels_[l];
        const int32_t a = nodes_[node].left, b = nodes_[node].right, end = nodes_[node].end;
        // The band: the separator (its list may hold stale or repeated entries) and layers of
        // the subtrees on both sides, each side keeping at least half of its weight outside.
        const int32_t mark = ++stamp_;
        band_.clear();
        for (int32_t v : separators_[node]) {
            if (label_[v] == node && level.stamp[v] != mark) {
                level.stamp[v] = mark;
                band_.push_back(v);
            }
        }
        if (band_.empty()) return;
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
        const int32_t f = static_cast<int32_t>(band_.size());
        int64_t band_left = 0, band_right = 0;
        for (int32_t x = 0; x < f; ++x) {
            const int32_t v = band_[x];
            level.local[v] = x;
            if (label_[v] != node) (label_[v] < b ? band_left : band_right) += level.weights[v];
        }
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
        flow_.solve(std::numeric_limits<int64_t>::max());
        int64_t left[2] = {prefix[b] - prefix[a] - band_left, prefix[b] - prefix[a] - band_left};
        int64_t right[2] = {prefix[end] - prefix[b] - band_right,
                            prefix[end] - prefix[b] - band_right};
        for (int32_t x = 0; x < f; ++x) {
            const int64_t w = level.weights[band_[x]];
            const int8_t sides[2] = {flow_.source_side(x), flow_.sink_side(x)};
            for (int c = 0; c < 2; ++c) {
                left[c] += sides[c] == 0 ? w : 0;
                right[c] += sides[c] == 2 ? w : 0;
            }
        }
        const bool source_cut = std::abs(left[0] - right[0]) <= std::abs(left[1] - right[1]);
        // Relabel. The separator joins `node`; a vertex that changes sides joins the lowest
        // common ancestor of its neighbours' nodes on its new side (a part, or a separator
        // refined later in this pass), which keeps every edge between a node and one of its
        // descendants: the order stays a nested dissection.
        pending_.clear();
        for (int32_t x = 0; x < f; ++x) {
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
        bool progress = true;
        while (!pending_.empty() && progress) {
            progress = false;
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
                    progress = true;
                } else {
                    pending_[kept++] = v;
                }
            }
            pending_.resize(kept);
        }
        for (int32_t v : pending_) {  // no neighbour on its side: the side's root takes it
            const int32_t root = label_[v] == -1 ? a : b;
            label_[v] = root;
            if (internal(root)) separators_[root].push_back(v);
        }
    }

    // ---------------------------------------------------------------------------------------
    // Phase C: postorder of the tree, every separator after both of its subtrees.

    void emit() {
        const Level& fine = levels_[0];
        const int32_t count = static_cast<int32_t>(nodes_.size());
        std::vector<int32_t> offsets(count + 1, 0), members(fine.size());
        for (int32_t v = 0; v < fine.size(); ++v) ++offsets[label_[v] + 1];
        for (int32_t i = 0; i < count; ++i) offsets[i + 1] += offsets[i];
        {
            std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
            for (int32_t v = 0; v < fine.size(); ++v) members[fill[label_[v]]++] = v;
        }
        std::vector<std::pair<int32_t, bool>> stack{{0, false}};  // (node, children done)
        while (!stack.empty()) {
            const auto [node, done] = stack.back();
            stack.pop_back();
            const int32_t* first = members.data() + offsets[node];
            const int32_t size = offsets[node + 1] - offsets[node];
            if (!internal(node)) {
                order_leaf(first, size);
                progress_.report(kRefined + (1.0 - kRefined) * static_cast<double>(order_.size()) /
                                                fine.size());
            } else if (done) {
                order_.insert(order_.end(), first, first + size);
            } else {
                stack.push_back({node, true});
                stack.push_back({nodes_[node].right, false});
                stack.push_back({nodes_[node].left, false});
            }
        }
    }

    // A leaf: its induced subgraph is copied into compact local arrays, which stay in cache
    // while recursive coordinate bisection passes over them.
    void order_leaf(const int32_t* ids, int32_t m) {
        if (m == 0) return;
        Level& fine = levels_[0];
        const int32_t mark = ++stamp_;
        for (int32_t k = 0; k < m; ++k) {
            fine.stamp[ids[k]] = mark;
            fine.local[ids[k]] = k;
        }
        leaf_offsets_.resize(m + 1);
        leaf_adjacency_.clear();
        leaf_points_.resize(m);
        leaf_offsets_[0] = 0;
        for (int32_t k = 0; k < m; ++k) {
            const int32_t v = ids[k];
            for (int32_t p = fine.offsets[v]; p < fine.offsets[v + 1]; ++p) {
                const int32_t u = fine.neighbors[p];
                if (fine.stamp[u] == mark && u != v) leaf_adjacency_.push_back(fine.local[u]);
            }
            leaf_offsets_[k + 1] = static_cast<int32_t>(leaf_adjacency_.size());
            leaf_points_[k] = fine.points[v];
        }
        leaf_piece_.assign(m, 0);
        leaf_position_.resize(m);
        leaf_side_.resize(m);
        leaf_copy_.resize(m);
        leaf_order_.clear();
        std::vector<int32_t> local_ids(m);
        std::iota(local_ids.begin(), local_ids.end(), 0);
        bisect_leaf(local_ids.data(), m);
        for (int32_t k : leaf_order_) order_.push_back(ids[k]);
    }

    // Recursive coordinate bisection: the best axis-aligned cut over the three axes and 32
    // positions each, within 35-65% balance, scored by the smaller one-sided boundary; a single
    // pass over the edges scores all 96 candidates (for each vertex, the lowest and highest bin
    // among its neighbours tell which cuts it touches). Works in place on local ids.
    void bisect_leaf(int32_t* ids, int32_t m) {
        if (m <= kKeepOrderSize) {
            leaf_order_.insert(leaf_order_.end(), ids, ids + m);
            return;
        }
        constexpr int kBins = 32;
        const int32_t piece = ++leaf_piece_count_;
        Eigen::Vector3d lo = leaf_points_[ids[0]], hi = lo;
        for (int32_t k = 0; k < m; ++k) {
            leaf_piece_[ids[k]] = piece;
            leaf_position_[ids[k]] = k;
            lo = lo.cwiseMin(leaf_points_[ids[k]]);
            hi = hi.cwiseMax(leaf_points_[ids[k]]);
        }
        const size_t size3 = 3 * static_cast<size_t>(m);
        if (bins_.size() < 3 * size3) bins_.resize(3 * size3);
        int* bin = bins_.data();  // three per vertex, one per axis
        int* low = bin + size3;   // lowest neighbour bin
        int* high = low + size3;  // highest neighbour bin
        double scale[3];
        for (int ax = 0; ax < 3; ++ax) {
            scale[ax] = hi[ax] > lo[ax] ? kBins / (hi[ax] - lo[ax]) : 0.0;
        }
        for (int32_t k = 0; k < m; ++k) {
            const Eigen::Vector3d& x = leaf_points_[ids[k]];
            for (int ax = 0; ax < 3; ++ax) {
                bin[3 * k + ax] =
                    std::min(kBins - 1, static_cast<int>((x[ax] - lo[ax]) * scale[ax]));
            }
        }
        // count[b]: vertices in bin b; lt / rt: difference arrays of the sizes of the left and
        // right one-sided boundaries for the cut between bins b - 1 and b.
        int32_t count[3][kBins + 1] = {}, lt[3][kBins + 2] = {}, rt[3][kBins + 2] = {};
        for (int32_t k = 0; k < m; ++k) {
            const int32_t v = ids[k];
            const int own[3] = {bin[3 * k], bin[3 * k + 1], bin[3 * k + 2]};
            int l0 = own[0], l1 = own[1], l2 = own[2], h0 = own[0], h1 = own[1], h2 = own[2];
            for (int32_t p = leaf_offsets_[v]; p < leaf_offsets_[v + 1]; ++p) {
                const int32_t u = leaf_adjacency_[p];
                if (leaf_piece_[u] != piece) continue;
                const int* bu = bin + 3 * leaf_position_[u];
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
                ++count[ax][own[ax]];
                ++lt[ax][own[ax] + 1];
                --lt[ax][highs[ax] + 1];
                ++rt[ax][lows[ax] + 1];
                --rt[ax][own[ax] + 1];
            }
        }
        int64_t best = std::numeric_limits<int64_t>::max();
        int best_axis = 0, best_bin = 0;
        bool left_boundary = true;  // the separator is the left side's boundary
        for (int ax = 0; ax < 3; ++ax) {
            if (scale[ax] == 0.0) continue;
            int64_t below = count[ax][0], ls = lt[ax][0] + lt[ax][1], rs = rt[ax][0] + rt[ax][1];
            for (int b = 1; b < kBins; ++b) {
                if (below >= 0.35 * m && below <= 0.65 * m && std::min(ls, rs) < best) {
                    best = std::min(ls, rs);
                    best_axis = ax;
                    best_bin = b;
                    left_boundary = ls <= rs;
                }
                below += count[ax][b];
                ls += lt[ax][b + 1];
                rs += rt[ax][b + 1];
            }
        }
        // Scratch shared by the recursion: each call is done with it before it recurses.
        int8_t* side = leaf_side_.data();  // 0 left, 1 separator, 2 right
        if (best == std::numeric_limits<int64_t>::max()) {
            // No axis splits it (coincident points): halve by position, one-sided boundary.
            for (int32_t k = 0; k < m; ++k) {
                side[k] = k < m / 2 ? 0 : 2;
                if (k >= m / 2) continue;
                const int32_t v = ids[k];
                for (int32_t p = leaf_offsets_[v]; p < leaf_offsets_[v + 1]; ++p) {
                    const int32_t u = leaf_adjacency_[p];
                    if (leaf_piece_[u] == piece && leaf_position_[u] >= m / 2) side[k] = 1;
                }
            }
        } else {
            const int ax = best_axis;
            for (int32_t k = 0; k < m; ++k) {
                if (bin[3 * k + ax] < best_bin) {
                    side[k] = left_boundary && high[3 * k + ax] >= best_bin ? 1 : 0;
                } else {
                    side[k] = !left_boundary && low[3 * k + ax] < best_bin ? 1 : 2;
                }
            }
        }
        // In place: left, right, separator; order both halves, then the separator.
        int32_t* copy = leaf_copy_.data();
        std::copy(ids, ids + m, copy);
        int32_t at = 0, sizes[2] = {0, 0};
        for (int8_t which : {0, 2, 1}) {
            for (int32_t k = 0; k < m; ++k) {
                if (side[k] == which) ids[at++] = copy[k];
            }
            if (which != 1) sizes[which / 2] = at - (which == 0 ? 0 : sizes[0]);
        }
        bisect_leaf(ids, sizes[0]);
        bisect_leaf(ids + sizes[0], sizes[1]);
        leaf_order_.insert(leaf_order_.end(), ids + sizes[0] + sizes[1], ids + m);
    }

    const SparsePattern& pattern_;
    ProgressSpan progress_;
    const int32_t leaf_size_;
    std::vector<Level> levels_;
    size_t base_ = 0;
    std::vector<TreeNode> nodes_;
    std::vector<int32_t> tree_parent_;
    std::vector<int32_t> label_;                    // tree node of each vertex (phase B)
    std::vector<std::vector<int32_t>> separators_;  // vertices of each separator (phase B)
    std::vector<std::vector<int32_t>> lists_;       // the part on each level (phase A)
    std::vector<std::vector<int8_t>> sides_;        // its sides on each level (phase A)
    // Progress: the hierarchy to kBuilt, the base level's dissection to kDissected, the
    // refinements to kRefined, the leaves' orders to 1.
    static constexpr double kBuilt = 0.3, kDissected = 0.5, kRefined = 0.8;
    double base_weight_ = 1, leaf_weight_ = 0;
    std::vector<int32_t> order_;
    int32_t stamp_ = 0;
    VertexCut flow_;
    std::vector<int32_t> band_, band_index_, pending_;
    std::vector<int32_t> leaf_offsets_, leaf_adjacency_, leaf_piece_, leaf_position_, leaf_order_;
    std::vector<int32_t> leaf_copy_;
    std::vector<int8_t> leaf_side_;
    std::vector<Eigen::Vector3d> leaf_points_;
    int32_t leaf_piece_count_ = 0;
    std::vector<int> bins_;
};

}  // namespace

std::vector<int32_t> nested_dissection_order(const SparsePattern& pattern,
                                             const std::vector<Eigen::Vector3d>& coordinates,
                                             const ProgressSpan& progress) {
    return Dissection(pattern, coordinates, progress).run();
}

}  // namespace raps
