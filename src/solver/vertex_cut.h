// Minimum vertex cut in a band of a graph, for the nested dissection ordering: the band's
// vertices are free to join the separator, the vertices around the band are fixed on the
// source side or the sink side, and the cut is the fewest band vertices whose removal
// disconnects the two sides. By Menger's theorem it is as large as the most vertex-disjoint
// source-sink paths, which are found by Dinic's blocking flows (Dinic 1970) on the
// vertex-split network; with unit vertex capacities that takes O(E sqrt(V)) (Even & Tarjan
// 1975). The split network is kept implicit: a path uses a vertex at most once, so each vertex
// stores only its predecessor and successor on its path.
#pragma once

#include <cstdint>
#include <vector>

namespace raps {

class VertexCut {
  public:
    // Describes the band vertex by vertex, 0 .. size - 1: neighbours in the band by band index,
    // and whether the vertex also touches the fixed source side or sink side.
    void begin(int32_t size);
    void add_neighbor(int32_t band_index) { adjacency_.push_back(band_index); }
    void touch_source() { touch_.back() |= 1; }
    void touch_sink() { touch_.back() |= 2; }
    void end_vertex();

    // Computes the maximum flow. Returns false, leaving the cut undefined, as soon as the flow
    // reaches `limit` (a cut that large is of no use to the caller).
    bool solve(int64_t limit);

    int64_t cut_size() const { return flow_; }

    // The two extreme minimum cuts: the one closest to the source (every vertex the residual
    // network reaches from the source is on the left) and the one closest to the sink.
    // Returns 0 (left), 1 (separator) or 2 (right) for band vertex x.
    int8_t source_side(int32_t x) const;
    int8_t sink_side(int32_t x) const;

  private:
    void augment();

    std::vector<int32_t> offsets_{0}, adjacency_;
    std::vector<int8_t> touch_;
    std::vector<int32_t> sources_;
    std::vector<int32_t> pred_, succ_;  // neighbours on the vertex's path, or kNone / kTerminal
    std::vector<int32_t> dist_;         // per state: distance from s in the residual network
    std::vector<int32_t> next_arc_, queue_, path_;
    std::vector<int8_t> reach_;  // per state: reaches t in the residual network
    int64_t flow_ = 0;
};

}  // namespace raps
