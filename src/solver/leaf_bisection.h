// The order of a leaf of the nested dissection (nested_dissection.h): recursive coordinate
// bisection of the leaf's induced subgraph down to pieces of eight vertices, each piece's
// separator after its two halves. Below a few thousand vertices the separators are short and
// these cheap geometric cuts lose little to flows; they left less fill than minimum degree on
// such pieces (docs/bench-solver.md).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "solver/graph_hierarchy.h"

namespace raps {

class LeafBisection {
  public:
    // Appends the elimination order of the m vertices ids of level `fine` to `order`. Uses
    // fine.stamp (marked with `mark`, which no vertex may carry yet) and fine.local as scratch.
    void order(GraphLevel& fine, int32_t mark, const int32_t* ids, int32_t m,
               std::vector<int32_t>& order);

  private:
    static constexpr int kBins = 32;
    // Per axis: count[b] vertices in bin b; lt / rt: difference arrays of the sizes of the left
    // and right one-sided boundaries for the cut between bins b - 1 and b.
    struct Histogram {
        int32_t count[3][kBins + 1] = {}, lt[3][kBins + 2] = {}, rt[3][kBins + 2] = {};
    };
    // The best axis-aligned cut of a piece.
    struct Cut {
        int axis = 0, bin = 0;
        bool left_boundary = true;  // the separator is the left side's boundary
        bool found = false;
    };

    void copy_subgraph(const GraphLevel& fine, int32_t mark, const int32_t* ids, int32_t m);
    void bisect(int32_t* ids, int32_t m);
    void bin_points(const int32_t* ids, int32_t m, int32_t piece, Histogram& histogram);
    Cut best_cut(const Histogram& histogram, int32_t m) const;
    void assign_sides(const int32_t* ids, int32_t m, int32_t piece, const Cut& cut);
    void split(int32_t* ids, int32_t m);

    // The leaf's induced subgraph in local indices, with its points.
    std::vector<int32_t> offsets_, adjacency_;
    std::vector<Eigen::Vector3d> points_;
    // Scratch of the recursion: each call is done with it before it recurses.
    std::vector<int32_t> piece_, position_, copy_, order_;
    std::vector<int8_t> side_;     // 0 left, 1 separator, 2 right
    std::vector<int> bins_;        // per vertex and axis: its bin, lowest and highest neighbour bin
    double scale_[3] = {0, 0, 0};  // bins per unit length on each axis, 0 if the piece is flat
    int32_t piece_count_ = 0;
};

}  // namespace raps
