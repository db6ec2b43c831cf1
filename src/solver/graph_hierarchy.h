// The multilevel hierarchy of the nested dissection ordering (nested_dissection.h): a graph and
// successively coarser copies of it, each made by heavy-edge matching (Hendrickson & Leland
// 1995; Karypis & Kumar 1998), so that separators can be found on a small graph and refined on
// the way back to the full one.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "solver/sparse_pattern.h"

namespace raps {

// A graph of the hierarchy.
struct GraphLevel {
    // Adjacency in compressed rows. Level 0 points into the pattern itself, diagonal included
    // (the loops of the dissection skip a vertex's own entry where it matters); coarser levels
    // own their storage and have no diagonal.
    const int32_t* offsets = nullptr;
    const int32_t* neighbors = nullptr;
    int32_t count = 0;
    std::vector<int32_t> offset_store, neighbor_store;
    std::vector<int32_t> edge_weights;        // empty on level 0: all 1
    std::vector<int32_t> weights;             // fine vertices per vertex
    const Eigen::Vector3d* points = nullptr;  // level 0: the caller's coordinates
    std::vector<Eigen::Vector3d> point_store;
    std::vector<int32_t> parent;  // vertex of the next coarser level; empty on the coarsest
    // Scratch of the dissection, allocated (zeroed) here: the part being separated is stamped,
    // with local indices and the weight of the part's fine vertices under each vertex.
    std::vector<int32_t> stamp, local, part_weight;

    int32_t size() const { return count; }
    int32_t entries() const { return offsets[count]; }
};

// Level 0 is the pattern's graph with the given coordinates (both must outlive the levels);
// each further level is about half the one before, down to a few dozen vertices or until
// matching stops shrinking the graph.
std::vector<GraphLevel> build_graph_hierarchy(const SparsePattern& pattern,
                                              const std::vector<Eigen::Vector3d>& coordinates,
                                              const ProgressSpan& progress);

}  // namespace raps
