#include "solver/nested_dissection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include <Eigen/Eigenvalues>

#include "core/fill_in_runs.h"
#include "solver/dissection.h"

namespace raps {
namespace dissection {

std::vector<int32_t> Dissection::run() {
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

// ---------------------------------------------------------------------------------------
// Phase A: recursive bisection of the base level, each cut found multilevel: inertial flow
// on a coarse level, then minimum cuts in a band around the projected separator on every
// level down to the base (the V-cycle of METIS, with flows in place of Fiduccia-Mattheyses).

int32_t Dissection::new_node() {
    nodes_.emplace_back();
    tree_parent_.push_back(-1);
    return static_cast<int32_t>(nodes_.size()) - 1;
}

// Builds the subtree of the part `ids` (base-level vertices); returns its root.
int32_t Dissection::dissect(std::vector<int32_t>& ids) {
    const int32_t node = new_node();
    const GraphLevel& base = levels_[base_];
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
void Dissection::separate(const std::vector<int32_t>& ids) {
    const int32_t part = ++stamp_;
    lists_[base_] = ids;
    int64_t weight = 0;
    {
        GraphLevel& l = levels_[base_];
        for (size_t k = 0; k < ids.size(); ++k) {
            l.stamp[ids[k]] = part;
            l.local[ids[k]] = static_cast<int32_t>(k);
            l.part_weight[ids[k]] = l.weights[ids[k]];
            weight += l.weights[ids[k]];
        }
    }
    // The part on the coarser levels: the vertices with fine vertices in it.
    const int32_t target =
        std::clamp(static_cast<int32_t>(weight / kFlowRatio), kFlowMinVertices, kFlowMaxVertices);
    size_t top = base_;
    while (top + 1 < levels_.size() && static_cast<int32_t>(lists_[top].size()) > target) {
        const GraphLevel& l = levels_[top];
        GraphLevel& c = levels_[top + 1];
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
void Dissection::report_dissected() const {
    progress_.report(kBuilt + (kDissected - kBuilt) * leaf_weight_ / base_weight_);
}

// Inertial flow (Schild & Sommer 2015): along each of a few directions, the minimum vertex
// cut between the first and the last kAlpha of the part. The cut may bend anywhere in the
// middle 40%, so it goes around dense regions of the mesh that any plane would cross.
void Dissection::inertial_flow(size_t l, int32_t part) {
    const int32_t n = static_cast<int32_t>(lists_[l].size());
    std::vector<int8_t>& best = sides_[l];
    std::vector<int8_t> side(n);
    std::vector<double> key(n);
    std::vector<int32_t> rank(n);
    int64_t best_cut = std::numeric_limits<int64_t>::max(), best_imbalance = 0;
    for (const Eigen::Vector3d& direction : principal_directions(l)) {
        int64_t fixed_left = 0, fixed_right = 0;
        slab_sides(l, part, direction, side, key, rank, fixed_left, fixed_right);
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

std::array<Eigen::Vector3d, 4> Dissection::principal_directions(size_t l) const {
    const GraphLevel& level = levels_[l];
    const std::vector<int32_t>& list = lists_[l];
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
    return {major, middle, (major + middle).normalized(), (major - middle).normalized()};
}

void Dissection::slab_sides(size_t l, int32_t part, const Eigen::Vector3d& direction,
                            std::vector<int8_t>& side, std::vector<double>& key,
                            std::vector<int32_t>& rank, int64_t& fixed_left, int64_t& fixed_right) {
    const GraphLevel& level = levels_[l];
    const std::vector<int32_t>& list = lists_[l];
    const int32_t n = static_cast<int32_t>(list.size());
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
    for (int32_t k = 0; k < lo; ++k) {
        side[rank[k]] = 0;
        fixed_left += level.part_weight[list[rank[k]]];
    }
    for (int32_t k = lo; k < hi; ++k) {
        side[rank[k]] = 1;
        band_.push_back(rank[k]);
    }
    for (int32_t k = hi; k < n; ++k) side[rank[k]] = 2;
    // A sink vertex next to a source vertex (a long edge) would make every cut infinite: let
    // it join the band.
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
}

// Projects the sides of the next coarser level to level l and moves the separator to the
// minimum cut of a band around it.
void Dissection::refine(size_t l, int32_t part) {
    const GraphLevel& level = levels_[l];
    const GraphLevel& coarse = levels_[l + 1];
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
bool Dissection::band_cut(size_t l, int32_t part, std::vector<int8_t>& side, int64_t limit,
                          int64_t fixed_left, int64_t fixed_right, int64_t& cut,
                          int64_t& imbalance) {
    const GraphLevel& level = levels_[l];
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

int64_t Dissection::imbalance_of(const GraphLevel& level, const std::vector<int32_t>& list,
                                 int64_t left, int64_t right, bool source_cut) const {
    for (int32_t x = 0; x < static_cast<int32_t>(band_.size()); ++x) {
        const int8_t s = source_cut ? flow_.source_side(x) : flow_.sink_side(x);
        const int64_t w = level.part_weight[list[band_[x]]];
        left += s == 0 ? w : 0;
        right += s == 2 ? w : 0;
    }
    return std::abs(left - right);
}

// ---------------------------------------------------------------------------------------
// Phase C: postorder of the tree, every separator after both of its subtrees.

void Dissection::emit() {
    const GraphLevel& fine = levels_[0];
    const int32_t count = static_cast<int32_t>(nodes_.size());
    // The passes over every vertex report as they go (70 ms without a call at 2.8M vertices).
    const ProgressSpan beat = progress_.part(kRefined, kRefined);
    std::vector<int32_t> offsets(count + 1, 0);
    std::vector<int32_t> members = filled_in_runs(static_cast<size_t>(fine.size()), 0, beat);
    for (int32_t v = 0; v < fine.size(); ++v) {
        beat.at(v, fine.size());
        ++offsets[label_[v] + 1];
    }
    for (int32_t i = 0; i < count; ++i) offsets[i + 1] += offsets[i];
    {
        std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
        for (int32_t v = 0; v < fine.size(); ++v) {
            beat.at(v, fine.size());
            members[fill[label_[v]]++] = v;
        }
    }
    std::vector<std::pair<int32_t, bool>> stack{{0, false}};  // (node, children done)
    while (!stack.empty()) {
        const auto [node, done] = stack.back();
        stack.pop_back();
        const int32_t* first = members.data() + offsets[node];
        const int32_t size = offsets[node + 1] - offsets[node];
        if (!internal(node)) {
            leaves_.order(levels_[0], ++stamp_, first, size, order_);
            progress_.report(kRefined +
                             (1.0 - kRefined) * static_cast<double>(order_.size()) / fine.size());
        } else if (done) {
            order_.insert(order_.end(), first, first + size);
        } else {
            stack.push_back({node, true});
            stack.push_back({nodes_[node].right, false});
            stack.push_back({nodes_[node].left, false});
        }
    }
}

}  // namespace dissection

std::vector<int32_t> nested_dissection_order(const SparsePattern& pattern,
                                             const std::vector<Eigen::Vector3d>& coordinates,
                                             const ProgressSpan& progress) {
    return dissection::Dissection(pattern, coordinates, progress).run();
}

}  // namespace raps
