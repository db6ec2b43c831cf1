#include "atlas/instanced_parts.h"

#include <algorithm>
#include <map>
#include <tuple>
#include <unordered_map>

#include "atlas/chart_stacking.h"
#include "core/hash_mix.h"
#include "core/union_find.h"

namespace raps {
namespace {

// The connected components of the triangles over welded vertices (welding stays within a
// part, so no component spans two), in the order of their first triangles.
std::vector<Instances::Piece> pieces_of(const TriangleMesh& mesh, const AtlasParts& parts,
                                        const std::vector<int32_t>& welded,
                                        std::vector<int32_t>& local_index) {
    std::vector<int32_t> parent(mesh.positions.size());
    for (size_t v = 0; v < parent.size(); ++v) parent[v] = static_cast<int32_t>(v);
    for (const Triangle& t : mesh.triangles) {
        for (int k = 1; k < 3; ++k) {
            const int32_t a = find_root(parent, welded[t[0]]), b = find_root(parent, welded[t[k]]);
            parent[std::max(a, b)] = std::min(a, b);
        }
    }
    std::vector<Instances::Piece> pieces;
    std::vector<int32_t> piece_of_root(mesh.positions.size(), -1);
    local_index.assign(mesh.positions.size(), -1);
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        int32_t& piece = piece_of_root[find_root(parent, welded[mesh.triangles[t][0]])];
        if (piece < 0) {
            piece = static_cast<int32_t>(pieces.size());
            pieces.emplace_back();
            pieces.back().part = parts.part_of_triangle(t);
        }
        Instances::Piece& p = pieces[piece];
        p.triangles.push_back(t);
        for (int32_t v : mesh.triangles[t]) {
            const int32_t w = welded[v];
            if (local_index[w] >= 0) continue;
            local_index[w] = static_cast<int32_t>(p.vertices.size());
            p.vertices.push_back(w);
        }
    }
    return pieces;
}

// What an instance must repeat exactly: its triangles over its vertices numbered by first use,
// its groups, its polygons (each triangle's polygon named by its first triangle's rank in the
// piece, as ids are only compared) and its seam edges (in that numbering, each pair sorted, the
// list sorted).
struct PieceLayout {
    std::vector<Triangle> triangles;
    std::vector<uint32_t> groups;
    std::vector<int32_t> polygons;
    std::vector<std::pair<int32_t, int32_t>> seams;
    bool operator==(const PieceLayout& o) const {
        return triangles == o.triangles && groups == o.groups && polygons == o.polygons &&
               seams == o.seams;
    }
};

PieceLayout layout_of(const TriangleMesh& mesh, const std::vector<int32_t>& welded,
                      const std::vector<int32_t>& local_index, const Instances::Piece& piece,
                      const std::vector<int32_t>& seams) {
    PieceLayout layout;
    std::unordered_map<uint32_t, int32_t> first_of_polygon;
    for (size_t k = 0; k < piece.triangles.size(); ++k) {
        const int32_t t = piece.triangles[k];
        const Triangle& v = mesh.triangles[t];
        layout.triangles.push_back(
            {local_index[welded[v[0]]], local_index[welded[v[1]]], local_index[welded[v[2]]]});
        if (!mesh.triangle_group.empty()) layout.groups.push_back(mesh.triangle_group[t]);
        if (!mesh.triangle_polygon.empty()) {
            layout.polygons.push_back(
                first_of_polygon.emplace(mesh.triangle_polygon[t], static_cast<int32_t>(k))
                    .first->second);
        }
    }
    for (int32_t e : seams) {
        const int32_t a = welded[mesh.seam_edges[e][0]], b = welded[mesh.seam_edges[e][1]];
        layout.seams.emplace_back(std::min(local_index[a], local_index[b]),
                                  std::max(local_index[a], local_index[b]));
    }
    std::sort(layout.seams.begin(), layout.seams.end());
    return layout;
}

// Originals kept per layout: a triangle soup (thousands of one-triangle pieces of as many
// shapes) would otherwise compare every piece with every earlier one.
constexpr size_t kCandidates = 16;

uint64_t hash_of(const PieceLayout& layout) {
    uint64_t hash = layout.triangles.size();
    for (const Triangle& t : layout.triangles) {
        for (int32_t v : t) hash = mix_bits(hash ^ static_cast<uint32_t>(v));
    }
    return hash;
}

std::vector<Eigen::Vector3d> positions_of(const TriangleMesh& mesh, const Instances::Piece& piece) {
    std::vector<Eigen::Vector3d> positions;
    positions.reserve(piece.vertices.size());
    for (int32_t w : piece.vertices) positions.push_back(mesh.positions[w]);
    return positions;
}

}  // namespace

bool Instances::any() const {
    for (size_t p = 0; p < source.size(); ++p) {
        if (source[p] != static_cast<int32_t>(p)) return true;
    }
    return false;
}

Instances find_instances(const TriangleMesh& mesh, const AtlasParts& parts,
                         const std::vector<int32_t>& welded, const CornerSources& sources,
                         size_t chart_count, double tolerance, bool allow_mirror,
                         bool across_parts) {
    Instances found;
    std::vector<int32_t> local_index;
    found.pieces = pieces_of(mesh, parts, welded, local_index);
    const int32_t count = static_cast<int32_t>(found.pieces.size());
    std::vector<int32_t> piece_of_vertex(mesh.positions.size(), -1);
    std::vector<char> has_points(count, 0);
    for (int32_t p = 0; p < count; ++p) {
        for (int32_t w : found.pieces[p].vertices) piece_of_vertex[w] = p;
        for (int32_t t : found.pieces[p].triangles)
            has_points[p] |= sources.chart[t] >= static_cast<int32_t>(chart_count);
    }
    std::vector<std::vector<int32_t>> seams(count);  // per piece, its seam edges
    for (size_t e = 0; e < mesh.seam_edges.size(); ++e) {
        const int32_t a = piece_of_vertex[welded[mesh.seam_edges[e][0]]];
        if (a >= 0 && a == piece_of_vertex[welded[mesh.seam_edges[e][1]]])
            seams[a].push_back(static_cast<int32_t>(e));
    }
    using PieceKey = std::tuple<int32_t, size_t, size_t, uint64_t>;
    std::map<PieceKey, std::vector<int32_t>> candidates;
    std::vector<PieceLayout> layouts(count);
    found.source.resize(count);
    for (int32_t p = 0; p < count; ++p) {
        found.source[p] = p;
        const Instances::Piece& piece = found.pieces[p];
        if (has_points[p]) continue;
        layouts[p] = layout_of(mesh, welded, local_index, piece, seams[p]);
        const PieceKey key{across_parts ? 0 : piece.part, piece.vertices.size(),
                           piece.triangles.size(), hash_of(layouts[p])};
        std::vector<int32_t>& earlier = candidates[key];
        const std::vector<Eigen::Vector3d> positions = positions_of(mesh, piece);
        for (int32_t q : earlier) {
            if (!(layouts[q] == layouts[p])) continue;
            const PointMatch match =
                match_points(positions_of(mesh, found.pieces[q]), positions, tolerance);
            if (match == PointMatch::kRigid || (allow_mirror && match == PointMatch::kMirror)) {
                found.source[p] = q;
                break;
            }
        }
        if (found.source[p] == p && earlier.size() < kCandidates) earlier.push_back(p);
    }
    return found;
}

void copy_instance_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                          const AtlasSurface& surface, const Instances& instances,
                          std::vector<AtlasChart>& charts, CornerSources& sources,
                          std::vector<int32_t>& part) {
    const int32_t old_count = static_cast<int32_t>(charts.size());
    // Each triangle's piece and place in it; each welded vertex's place in its piece.
    std::vector<int32_t> piece_of(mesh.triangle_count()), rank(mesh.triangle_count());
    std::vector<int32_t> vertex_rank(mesh.positions.size(), -1);
    for (size_t p = 0; p < instances.pieces.size(); ++p) {
        const Instances::Piece& piece = instances.pieces[p];
        for (size_t k = 0; k < piece.triangles.size(); ++k) {
            piece_of[piece.triangles[k]] = static_cast<int32_t>(p);
            rank[piece.triangles[k]] = static_cast<int32_t>(k);
        }
        for (size_t k = 0; k < piece.vertices.size(); ++k)
            vertex_rank[piece.vertices[k]] = static_cast<int32_t>(k);
    }
    // Triangle by triangle, in input order: an instance's triangle takes its source triangle's
    // chart (copied once per instance) and chart vertices; charts are numbered on first sight.
    std::vector<int32_t> kept(old_count, -1);                // old chart -> new, for non-instances
    std::map<std::pair<int32_t, int32_t>, int32_t> copy_of;  // (instance piece, old chart) -> new
    std::vector<AtlasChart> out;
    std::vector<int32_t> out_part;
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        const int32_t p = piece_of[t];
        const int32_t s = instances.source[p];
        const int32_t from = s == p ? t : instances.pieces[s].triangles[rank[t]];
        const int32_t old = sources.chart[from];
        if (old >= old_count) {  // a point chart (pieces that have one are never instances)
            sources.chart[t] = -1 - (old - old_count);  // numbered below, after the real ones
            continue;
        }
        // The original's chart, numbered when first seen (pieces of one mesh may interleave,
        // so an instance's triangle can come first).
        if (kept[old] < 0) {
            kept[old] = static_cast<int32_t>(out.size());
            out.push_back(std::move(charts[old]));
            out_part.push_back(part[old]);
        }
        if (s == p) {
            sources.chart[t] = kept[old];
            continue;
        }
        const auto [it, added] = copy_of.emplace(std::make_pair(p, old), 0);
        if (added) {
            it->second = static_cast<int32_t>(out.size());
            AtlasChart copy = out[kept[old]];
            const Instances::Piece& instance = instances.pieces[p];
            for (size_t v = 0; v < copy.disk.surface_vertex.size(); ++v) {
                const int32_t w = surface.welded_vertex[copy.disk.surface_vertex[v]];
                copy.disk.mesh.positions[v] = mesh.positions[instance.vertices[vertex_rank[w]]];
            }
            out.push_back(std::move(copy));
            out_part.push_back(parts.part_of_triangle(t));
        }
        sources.chart[t] = it->second;
        sources.vertex[t] = sources.vertex[from];
    }
    const int32_t count = static_cast<int32_t>(out.size());
    for (int32_t& chart : sources.chart) {
        if (chart < 0) chart = count - 1 - chart;
    }
    charts = std::move(out);
    part = std::move(out_part);
}

}  // namespace raps
