#include "solver/vertex_cut.h"

#include <algorithm>

namespace raps {
namespace {

// pred_ / succ_ values besides a band index.
constexpr int32_t kNone = -1;      // the vertex carries no flow
constexpr int32_t kTerminal = -2;  // the flow comes from the source / goes to the sink
constexpr int32_t kDead = -3;      // distance of a state from which no shortest path continues

}  // namespace

void VertexCut::begin(int32_t size) {
    offsets_.clear();
    offsets_.reserve(size + 1);
    offsets_.push_back(0);
    adjacency_.clear();
    touch_.clear();
    touch_.reserve(size);
    touch_.push_back(0);
}

void VertexCut::end_vertex() {
    offsets_.push_back(static_cast<int32_t>(adjacency_.size()));
    touch_.push_back(0);
}

// States of the split network: 2x is x_in, 2x + 1 is x_out. Residual arcs: s -> x_in when x
// touches the source; x_in -> x_out when x carries no flow, else x_in -> pred(x)_out (undoing the
// flow into x); x_out -> y_in for every band neighbour y (uncapacitated); x_out -> x_in when x
// carries flow; x_out -> t when x touches the sink.
bool VertexCut::solve(int64_t limit) {
    const int32_t size = static_cast<int32_t>(offsets_.size()) - 1;
    touch_.resize(size);
    sources_.clear();
    for (int32_t x = 0; x < size; ++x) {
        if (touch_[x] & 1) sources_.push_back(x);
    }
    pred_.assign(size, kNone);
    succ_.assign(size, kNone);
    dist_.resize(2 * static_cast<size_t>(size));
    next_arc_.resize(size);
    queue_.resize(2 * static_cast<size_t>(size) + 1);
    const int32_t* offsets = offsets_.data();
    const int32_t* adjacency = adjacency_.data();
    int32_t* dist = dist_.data();
    int32_t* pred = pred_.data();
    int32_t* queue = queue_.data();
    flow_ = 0;
    while (true) {
        // Breadth-first distances from s (at distance 0), up to the distance of t.
        std::fill(dist_.begin(), dist_.end(), -1);
        int32_t head = 0, tail = 0, dist_t = -1;
        for (int32_t x : sources_) {
            dist[2 * x] = 1;
            queue[tail++] = 2 * x;
        }
        while (head < tail) {
            const int32_t state = queue[head++], x = state >> 1, d = dist[state];
            if (dist_t >= 0 && d + 1 >= dist_t) break;
            if (!(state & 1)) {
                const int32_t y = pred[x] == kNone ? x : pred[x];
                if (y >= 0 && dist[2 * y + 1] < 0) {
                    dist[2 * y + 1] = d + 1;
                    queue[tail++] = 2 * y + 1;
                }
                continue;
            }
            if ((touch_[x] & 2) && dist_t < 0) dist_t = d + 1;
            if (pred[x] != kNone && dist[2 * x] < 0) {
                dist[2 * x] = d + 1;
                queue[tail++] = 2 * x;
            }
            for (int32_t p = offsets[x]; p < offsets[x + 1]; ++p) {
                const int32_t y = adjacency[p];
                if (dist[2 * y] < 0) {
                    dist[2 * y] = d + 1;
                    queue[tail++] = 2 * y;
                }
            }
        }
        if (dist_t < 0) break;  // the last search marked what the source side reaches

        // Blocking flow: depth-first searches along arcs that increase the distance by one.
        // next_arc_ walks x_out's arcs: offsets[x] - 2 is the arc to t, offsets[x] - 1 the arc
        // back to x_in, then the band neighbours. x_in has a single candidate arc.
        for (int32_t x = 0; x < size; ++x) next_arc_[x] = offsets[x] - 2;
        for (int32_t source : sources_) {
            while (dist[2 * source] == 1) {
                path_.clear();
                path_.push_back(2 * source);
                bool augmented = false;
                while (!path_.empty()) {
                    const int32_t state = path_.back(), x = state >> 1, d = dist[state];
                    int32_t next = -1;
                    if (!(state & 1)) {
                        const int32_t y = pred[x] == kNone ? x : pred[x];
                        if (y >= 0 && dist[2 * y + 1] == d + 1) next = 2 * y + 1;
                    } else {
                        int32_t& arc = next_arc_[x];
                        for (; arc < offsets[x + 1]; ++arc) {
                            if (arc == offsets[x] - 2) {
                                if ((touch_[x] & 2) && d + 1 == dist_t) {
                                    next = kTerminal;
                                    break;
                                }
                            } else if (arc == offsets[x] - 1) {
                                if (pred[x] != kNone && dist[2 * x] == d + 1) {
                                    next = 2 * x;
                                    break;
                                }
                            } else if (dist[2 * adjacency[arc]] == d + 1) {
                                next = 2 * adjacency[arc];
                                break;
                            }
                        }
                    }
                    if (next == kTerminal) {
                        augment();
                        augmented = true;
                        break;
                    }
                    if (next >= 0) {
                        path_.push_back(next);
                        continue;
                    }
                    dist[state] = kDead;
                    path_.pop_back();
                    if (!path_.empty() && (path_.back() & 1)) ++next_arc_[path_.back() >> 1];
                }
                if (!augmented) break;
                if (++flow_ >= limit) return false;
            }
        }
    }

    // What reaches t in the residual network, searched backwards from t: the arcs into x_in
    // come from every band neighbour's out and, when x carries flow, from x_out; the arcs into
    // x_out come from x_in when x carries no flow, else from the in of x's successor.
    reach_.assign(2 * static_cast<size_t>(size), 0);
    int32_t head = 0, tail = 0;
    for (int32_t x = 0; x < size; ++x) {
        if (touch_[x] & 2) {
            reach_[2 * x + 1] = 1;
            queue[tail++] = 2 * x + 1;
        }
    }
    while (head < tail) {
        const int32_t state = queue[head++], x = state >> 1;
        if (!(state & 1)) {
            if (pred[x] != kNone && !reach_[2 * x + 1]) {
                reach_[2 * x + 1] = 1;
                queue[tail++] = 2 * x + 1;
            }
            for (int32_t p = offsets[x]; p < offsets[x + 1]; ++p) {
                const int32_t y = adjacency[p];
                if (!reach_[2 * y + 1]) {
                    reach_[2 * y + 1] = 1;
                    queue[tail++] = 2 * y + 1;
                }
            }
        } else {
            const int32_t y = pred[x] == kNone ? x : succ_[x];
            if (y >= 0 && !reach_[2 * y]) {
                reach_[2 * y] = 1;
                queue[tail++] = 2 * y;
            }
        }
    }
    return true;
}

int8_t VertexCut::source_side(int32_t x) const {
    if (dist_[2 * x] < 0) return 2;
    return dist_[2 * x + 1] >= 0 ? 0 : 1;
}

int8_t VertexCut::sink_side(int32_t x) const {
    if (!reach_[2 * x + 1]) return 0;
    return reach_[2 * x] ? 2 : 1;
}

// Sends one more unit along path_, which alternates in and out states from a vertex touching
// the source to one touching the sink, by rewriting the predecessors and successors on it.
void VertexCut::augment() {
    int32_t pending = kTerminal;  // the vertex whose out feeds the next in state
    bool undone = false;          // the next in state is entered from its own out
    const size_t length = path_.size();
    for (size_t i = 0; i < length; ++i) {
        const int32_t state = path_[i], x = state >> 1;
        if (!(state & 1)) {
            pred_[x] = undone ? kNone : pending;
            undone = false;
        } else if (i + 1 == length) {
            succ_[x] = kTerminal;
        } else if (path_[i + 1] == 2 * x) {
            succ_[x] = kNone;
            undone = true;
        } else {
            succ_[x] = path_[i + 1] >> 1;
            pending = x;
        }
    }
}

}  // namespace raps
