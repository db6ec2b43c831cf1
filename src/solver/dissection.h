// The nested dissection of nested_dissection.h (George 1973; the method and its measurements
// are described there), shared by its two files:
// nested_dissection.cpp (the dissection of the base level and the order) and
// separator_refinement.cpp (the tree's separators refined on the finer levels).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "solver/graph_hierarchy.h"
#include "solver/leaf_bisection.h"
#include "solver/sparse_pattern.h"
#include "solver/vertex_cut.h"

namespace raps {
namespace dissection {

// Tuning, measured on face.obj subdivided twice, face.obj, a 400x400 grid and the disk meshes of
// the test data (see the header comment for the resulting numbers).

// Parts whose vertex weight is at most the leaf size are ordered by recursive coordinate
// bisection instead of flow-based dissection: below a few thousand vertices the separators are
// short and cheap geometric cuts lose little, while flows would dominate the running time. Small
// graphs afford flows further down.
constexpr double kLeafDivisor = 200;
constexpr int32_t kMinLeafSize = 256;
constexpr int32_t kMaxLeafSize = 2048;
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
          leaf_size_(static_cast<int32_t>(
              std::clamp(pattern.size / kLeafDivisor, double{kMinLeafSize}, double{kMaxLeafSize}))),
          levels_(build_graph_hierarchy(pattern, coordinates, progress.part(0.0, kBuilt))) {}

    std::vector<int32_t> run();

  private:
    // ---------------------------------------------------------------------------------------
    // Phase A: recursive bisection of the base level, each cut found multilevel: inertial flow
    // on a coarse level, then minimum cuts in a band around the projected separator on every
    // level down to the base (the V-cycle of METIS, with flows in place of Fiduccia-Mattheyses).

    int32_t new_node();

    // Builds the subtree of the part `ids` (base-level vertices); returns its root.
    int32_t dissect(std::vector<int32_t>& ids);

    // Fills sides_[base_] for ids: 0 left, 1 separator, 2 right.
    void separate(const std::vector<int32_t>& ids);

    // Phase A's fraction: the weight of the leaves done.
    void report_dissected() const;

    // Inertial flow (Schild & Sommer 2015): along each of a few directions, the minimum vertex
    // cut between the first and the last kAlpha of the part. The cut may bend anywhere in the
    // middle 40%, so it goes around dense regions of the mesh that any plane would cross.
    void inertial_flow(size_t l, int32_t part);

    // The directions of inertial flow on level l's part: its two principal axes in the part's
    // plane and the two diagonals between them.
    std::array<Eigen::Vector3d, 4> principal_directions(size_t l) const;

    // Sides of level l's part along `direction`: the first kAlpha of it on the source side
    // (0), the last on the sink side (2), the middle in band_ (1); adds the fixed sides'
    // weights. key and rank: scratch of the part's size.
    void slab_sides(size_t l, int32_t part, const Eigen::Vector3d& direction,
                    std::vector<int8_t>& side, std::vector<double>& key, std::vector<int32_t>& rank,
                    int64_t& fixed_left, int64_t& fixed_right);

    // Projects the sides of the next coarser level to level l and moves the separator to the
    // minimum cut of a band around it.
    void refine(size_t l, int32_t part);

    // Minimum vertex cut through band_ (local indices of side 1) between the vertices of side 0
    // and side 2 of the part on level l; of the two extreme minimum cuts, the more balanced.
    // Rewrites the band's sides; returns false (sides undefined) once the flow reaches limit.
    bool band_cut(size_t l, int32_t part, std::vector<int8_t>& side, int64_t limit,
                  int64_t fixed_left, int64_t fixed_right, int64_t& cut, int64_t& imbalance);

    int64_t imbalance_of(const GraphLevel& level, const std::vector<int32_t>& list, int64_t left,
                         int64_t right, bool source_cut) const;

    // ---------------------------------------------------------------------------------------
    // Phase B: every vertex of a level carries the tree node it belongs to (a leaf part or the
    // separator of an inner node). Labels are projected to the next finer level, where every
    // separator, top down, moves to the minimum cut of a band around it.

    bool internal(int32_t node) const { return nodes_[node].left >= 0; }

    void project_labels(size_t l);

    void refine_all(size_t l);

    void refine_separator(size_t l, int32_t node, const std::vector<int64_t>& prefix);

    // The band: the separator (its list may hold stale or repeated entries) and layers of the
    // subtrees on both sides, each side keeping at least half of its weight outside. Stamps
    // the band with `mark`; returns false if the separator is empty.
    bool grow_separator_band(size_t l, int32_t node, const std::vector<int64_t>& prefix,
                             int32_t mark);

    // The flow network of the band: its vertices (local indices in level.local) are free, the
    // left subtree's vertices around it are the source, the right subtree's the sink.
    void build_separator_flow(size_t l, int32_t node, int32_t mark);

    // Of the two extreme minimum cuts, whether the one closest to the source is the more
    // balanced (weights of the two subtrees after the cut).
    bool more_balanced_cut(size_t l, int32_t node, const std::vector<int64_t>& prefix) const;

    // Relabel. The separator joins `node`; a vertex that changes sides joins the lowest common
    // ancestor of its neighbours' nodes on its new side (a part, or a separator refined later
    // in this pass), which keeps every edge between a node and one of its descendants: the
    // order stays a nested dissection.
    void relabel_band(size_t l, int32_t node, bool source_cut);

    // One pass over the pending vertices: each with a neighbour on its side joins the lowest
    // common ancestor of those neighbours' nodes. Returns whether any was placed.
    bool place_pending(size_t l, int32_t node);

    // ---------------------------------------------------------------------------------------
    // Phase C: postorder of the tree, every separator after both of its subtrees.

    void emit();

    const SparsePattern& pattern_;
    ProgressSpan progress_;
    const int32_t leaf_size_;
    std::vector<GraphLevel> levels_;
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
    LeafBisection leaves_;
};

}  // namespace dissection
}  // namespace raps
