#include "atlas/chart_disk.h"

#include <algorithm>
#include <numeric>

#include "atlas/local_index.h"
#include "core/fill_in_runs.h"
#include "mesh/mesh_topology.h"
#include "planar/laplace_system.h"

namespace raps {
namespace {

// Local twins of the chart's triangles: the surface's, kept inside the chart and off seams.
std::vector<int32_t> local_twins(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                                 const std::vector<char>& seam, const ProgressSpan& beat) {
    const LocalIndex local_of(triangles, surface.mesh.triangles.size());
    beat.report(0.0);
    std::vector<int32_t> twin = filled_in_runs(3 * triangles.size(), -1, beat);
    beat.in_runs(static_cast<int64_t>(triangles.size()), [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) {
            for (int k = 0; k < 3; ++k) {
                const int32_t h = 3 * triangles[i] + k, o = surface.twin[h];
                if (o < 0 || seam[h]) continue;
                const int32_t other = local_of(o / 3);
                if (other >= 0) twin[3 * i + k] = 3 * other + o % 3;
            }
        }
    });
    return twin;
}

// Chart vertices: corners joined across uncut edges, one vertex per class.
void build_vertices(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                    const std::vector<int32_t>& twin, ChartDisk& disk, const ProgressSpan& beat) {
    const std::vector<int32_t> classes = corner_vertex_classes(twin, beat);
    disk.mesh.positions.clear();
    disk.surface_vertex.clear();
    assign_in_runs(disk.mesh.triangles, triangles.size(), Triangle{}, beat);
    // Classes are numbered in order of first sight; reserved exactly, a kept chart holds no
    // doubling's slack in its positions while merging maps the others.
    const size_t vertex_count =
        classes.empty()
            ? 0
            : static_cast<size_t>(*std::max_element(classes.begin(), classes.end())) + 1;
    disk.mesh.positions.reserve(vertex_count);
    disk.surface_vertex.reserve(vertex_count);
    beat.in_runs(static_cast<int64_t>(classes.size()), [&](int64_t begin, int64_t end) {
        for (int64_t c = begin; c < end; ++c) {
            if (classes[c] == static_cast<int32_t>(disk.surface_vertex.size())) {  // a new vertex
                const int32_t v = surface.mesh.triangles[triangles[c / 3]][c % 3];
                disk.surface_vertex.push_back(v);
                disk.mesh.positions.push_back(surface.mesh.positions[v]);
            }
            disk.mesh.triangles[c / 3][c % 3] = classes[c];
        }
    });
}

// Whether the chart is a topological disk; `loops` receives its boundary loops.
bool is_disk(const ChartDisk& disk, const Halfedges& halfedges,
             std::vector<std::vector<int32_t>>& loops, const ProgressSpan& beat) {
    loops = boundary_loops(disk.mesh, halfedges, beat);
    const int64_t euler = static_cast<int64_t>(disk.mesh.vertex_count()) - edge_count(halfedges) +
                          disk.mesh.triangle_count();
    return loops.size() == 1 && euler == 1;
}

// Marks the edges a spanning tree of the triangles (breadth first from triangle 0) crosses;
// false when the triangles are not connected.
bool spanning_tree_crossings(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                             const std::vector<int32_t>& twin, std::vector<char>& crossed,
                             const ProgressSpan& beat) {
    const size_t triangle_count = twin.size() / 3;
    crossed.assign(twin.size(), 0);
    std::vector<char> visited(triangle_count, 0);
    std::vector<int32_t> frontier;
    // Enters `first` and the rest of its input polygon, across the polygon's own edges, so
    // that no cut runs through a polygon.
    auto enter = [&](int32_t first) {
        visited[first] = 1;
        const size_t begin = frontier.size();
        frontier.push_back(first);
        for (size_t j = begin; j < frontier.size(); ++j) {
            for (int k = 0; k < 3; ++k) {
                const int32_t h = 3 * frontier[j] + k, o = twin[h];
                if (o < 0 || visited[o / 3] ||
                    !joins_polygon(surface, 3 * triangles[frontier[j]] + k))
                    continue;
                visited[o / 3] = 1;
                crossed[h] = crossed[o] = 1;
                frontier.push_back(o / 3);
            }
        }
    };
    enter(0);
    for (size_t i = 0; i < frontier.size(); ++i) {
        beat.at(static_cast<int64_t>(i), static_cast<int64_t>(triangle_count));
        for (int k = 0; k < 3; ++k) {
            const int32_t h = 3 * frontier[i] + k, o = twin[h];
            if (o < 0 || visited[o / 3]) continue;
            crossed[h] = crossed[o] = 1;
            enter(o / 3);
        }
    }
    return frontier.size() == triangle_count;
}

// Cuts the chart open along every uncut edge the spanning tree does not cross, pruned of
// dangling branches: candidate edges with an end that is neither on the boundary nor touched by
// another candidate are dropped until none is left.
void cut_along_tree_complement(const TriangleMesh& mesh, const std::vector<char>& crossed,
                               std::vector<int32_t>& twin, const ProgressSpan& beat) {
    const int32_t corners = static_cast<int32_t>(twin.size());
    const int32_t n = mesh.vertex_count();
    std::vector<int32_t> degree(n, 0);
    std::vector<char> boundary(n, 0), cut(corners, 0);
    for (int32_t h = 0; h < corners; ++h) {
        beat.at(h, corners);
        const int32_t a = halfedge_origin(mesh, h), b = halfedge_target(mesh, h);
        if (twin[h] < 0) {
            boundary[a] = boundary[b] = 1;
        } else if (!crossed[h] && h < twin[h]) {
            cut[h] = 1;
            ++degree[a];
            ++degree[b];
        }
    }
    // The candidate edges at each vertex, in one array (offsets per vertex).
    std::vector<int32_t> offset(n + 1, 0), incident;
    for (int32_t v = 0; v < n; ++v) offset[v + 1] = offset[v] + degree[v];
    incident.resize(offset[n]);
    std::vector<int32_t> filled(offset.begin(), offset.end() - 1);
    for (int32_t h = 0; h < corners; ++h) {
        beat.at(h, corners);
        if (!cut[h]) continue;
        incident[filled[halfedge_origin(mesh, h)]++] = h;
        incident[filled[halfedge_target(mesh, h)]++] = h;
    }
    std::vector<int32_t> dangling;
    for (int32_t v = 0; v < n; ++v) {
        if (degree[v] == 1 && !boundary[v]) dangling.push_back(v);
    }
    for (int64_t step = 0; !dangling.empty(); ++step) {
        beat.at(step, corners);
        const int32_t v = dangling.back();
        dangling.pop_back();
        if (degree[v] != 1 || boundary[v]) continue;
        for (int32_t s = offset[v]; s < offset[v + 1]; ++s) {
            const int32_t h = incident[s];
            if (!cut[h]) continue;
            cut[h] = 0;
            const int32_t a = halfedge_origin(mesh, h), b = halfedge_target(mesh, h);
            --degree[a];
            --degree[b];
            const int32_t other = a == v ? b : a;
            if (degree[other] == 1 && !boundary[other]) dangling.push_back(other);
        }
    }
    for (int32_t h = 0; h < corners; ++h) {
        if (cut[h]) {
            const int32_t o = twin[h];
            twin[h] = twin[o] = -1;
        }
    }
}

// The chart's topology (everything but its vertex order), or false when it is no disk.
// Every step reports to `beat` as it goes: a union of a million triangles took up to 230 ms here
// without a progress call.
bool build_chart_disk(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                      const std::vector<char>& seam, ChartDisk& disk, const ProgressSpan& beat) {
    disk.surface_triangle = triangles;
    Halfedges halfedges;
    halfedges.twin = local_twins(surface, triangles, seam, beat);
    build_vertices(surface, triangles, halfedges.twin, disk, beat);
    std::vector<std::vector<int32_t>> loops;
    if (!is_disk(disk, halfedges, loops, beat)) {
        std::vector<char> crossed;
        if (!spanning_tree_crossings(surface, triangles, halfedges.twin, crossed, beat))
            return false;  // not connected
        cut_along_tree_complement(disk.mesh, crossed, halfedges.twin, beat);
        build_vertices(surface, triangles, halfedges.twin, disk, beat);
        if (!is_disk(disk, halfedges, loops, beat)) return false;
    }
    disk.boundary_loop = std::move(loops[0]);
    // Summed here, corner by corner in order, from the surface's angles: a per-vertex sum is a
    // sixth of a per-corner copy, and charts being mapped are where the atlas peaks.
    assign_in_runs(disk.angle_sum, disk.mesh.positions.size(), 0.0, beat);
    beat.in_runs(static_cast<int64_t>(triangles.size()), [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) {
            for (int k = 0; k < 3; ++k) {
                disk.angle_sum[disk.mesh.triangles[i][k]] +=
                    surface.corner_angle[3 * static_cast<size_t>(triangles[i]) + k];
            }
        }
    });
    // The chart's own twins are the chart mesh's half-edges: every pair joins the same two
    // chart vertices (they are classes of corners joined across exactly these pairs).
    disk.adjacency = build_vertex_adjacency(disk.mesh, halfedges, beat);
    return true;
}

}  // namespace

bool make_chart_disk(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                     const std::vector<char>& seam, ChartDisk& disk, const ProgressSpan& progress) {
    if (!build_chart_disk(surface, triangles, seam, disk, progress)) return false;
    progress.report(0.0);
    disk.vertex_order = vertex_elimination_order(disk.mesh, disk.adjacency, progress);
    return true;
}

bool make_union_chart_disk(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                           const std::vector<char>& seam, const ChartDisk& a, const ChartDisk& b,
                           ChartDisk& disk, const ProgressSpan& progress) {
    if (!build_chart_disk(surface, triangles, seam, disk, progress)) return false;
    progress.report(0.0);
    // One level of nested dissection with the parts' own minimum degree orders inside: a's
    // vertices in a's order, then b's in b's, then the vertices they share (the seam between
    // them, which separates the two) in a's order. Measured by callgrind on one thread, the
    // whole atlas, against ordering the unions by minimum degree: fandisk 543.2M -> 524.4M
    // instructions, cheburashka 875.7M -> 852.5M, lion 1071.6M -> 1040.4M; the factorizations
    // did not grow (fandisk's Cholesky and LU kernels 40.1M -> 39.1M).
    // Per part, the surface vertex at each position of its order (the first position wins).
    auto ordered_vertices = [](const ChartDisk& part) {
        std::vector<int32_t> vertex(part.vertex_order.size());
        for (size_t k = 0; k < vertex.size(); ++k)
            vertex[k] = part.surface_vertex[part.vertex_order[k]];
        return vertex;
    };
    const size_t surface_vertices = surface.mesh.positions.size();
    const LocalIndex position_in_a(ordered_vertices(a), surface_vertices);
    const LocalIndex position_in_b(ordered_vertices(b), surface_vertices);
    progress.report(0.0);
    // A counting sort by (group, position in its part's order), ties in vertex order.
    const int32_t n = disk.mesh.vertex_count();
    const int32_t size_a = static_cast<int32_t>(a.vertex_order.size());
    const int32_t size_b = static_cast<int32_t>(b.vertex_order.size());
    std::vector<int32_t> key(n), start(2 * static_cast<size_t>(size_a) + size_b + 1, 0);
    for (int32_t v = 0; v < n; ++v) {
        const int32_t in_a = position_in_a(disk.surface_vertex[v]);
        const int32_t in_b = position_in_b(disk.surface_vertex[v]);
        key[v] = in_a < 0 ? size_a + in_b : in_b < 0 ? in_a : size_a + size_b + in_a;
        ++start[key[v] + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    progress.report(0.0);
    disk.vertex_order.resize(n);
    for (int32_t v = 0; v < n; ++v) disk.vertex_order[start[key[v]]++] = v;
    return true;
}

}  // namespace raps
