#include "atlas/instanced_parts.h"

#include <algorithm>
#include <map>
#include <tuple>
#include <unordered_map>

#include "atlas/chart_stacking.h"
#include "core/hash_mix.h"

namespace raps {
namespace {

// A part's triangles relative to its first vertex, its groups, its polygons (each triangle's
// polygon named by its first triangle in the part, as ids are only compared) and its seam
// edges (relative too): what an instance must repeat exactly.
struct PartLayout {
    std::vector<Triangle> triangles;
    std::vector<uint32_t> groups;
    std::vector<int32_t> polygons;
    std::vector<std::array<uint32_t, 2>> seams;
    bool operator==(const PartLayout& o) const {
        return triangles == o.triangles && groups == o.groups && polygons == o.polygons &&
               seams == o.seams;
    }
};

PartLayout layout_of(const TriangleMesh& mesh, const AtlasParts& parts, int32_t p) {
    PartLayout layout;
    const int32_t first = parts.first_vertex[p], last = parts.first_vertex[p + 1];
    std::unordered_map<uint32_t, int32_t> first_of_polygon;
    for (int32_t t = parts.first_triangle[p]; t < parts.first_triangle[p + 1]; ++t) {
        const Triangle& v = mesh.triangles[t];
        layout.triangles.push_back({v[0] - first, v[1] - first, v[2] - first});
        if (!mesh.triangle_group.empty()) layout.groups.push_back(mesh.triangle_group[t]);
        if (!mesh.triangle_polygon.empty()) {
            layout.polygons.push_back(
                first_of_polygon.emplace(mesh.triangle_polygon[t], t - parts.first_triangle[p])
                    .first->second);
        }
    }
    for (const std::array<uint32_t, 2>& pair : mesh.seam_edges) {
        const int64_t a = pair[0];
        if (a >= first && a < last)
            layout.seams.push_back(
                {pair[0] - static_cast<uint32_t>(first), pair[1] - static_cast<uint32_t>(first)});
    }
    return layout;
}

uint64_t hash_of(const PartLayout& layout) {
    uint64_t hash = layout.triangles.size();
    for (const Triangle& t : layout.triangles) {
        for (int32_t v : t) hash = mix_bits(hash ^ static_cast<uint32_t>(v));
    }
    return hash;
}

std::vector<Eigen::Vector3d> positions_of(const TriangleMesh& mesh, const AtlasParts& parts,
                                          int32_t p) {
    return std::vector<Eigen::Vector3d>(mesh.positions.begin() + parts.first_vertex[p],
                                        mesh.positions.begin() + parts.first_vertex[p + 1]);
}

}  // namespace

std::vector<int32_t> instance_sources(const TriangleMesh& mesh, const AtlasParts& parts,
                                      const CornerSources& sources, double tolerance,
                                      bool allow_mirror) {
    std::vector<int32_t> source(parts.count());
    std::vector<char> has_points(parts.count(), 0);
    for (int32_t p : sources.point_chart_part) has_points[p] = 1;
    using Key = std::tuple<int32_t, int32_t, uint64_t>;
    std::map<Key, std::vector<int32_t>> candidates;
    std::vector<PartLayout> layouts(parts.count());
    for (int32_t p = 0; p < parts.count(); ++p) {
        source[p] = p;
        if (has_points[p]) continue;
        layouts[p] = layout_of(mesh, parts, p);
        const Key key{parts.first_vertex[p + 1] - parts.first_vertex[p],
                      parts.first_triangle[p + 1] - parts.first_triangle[p], hash_of(layouts[p])};
        std::vector<int32_t>& earlier = candidates[key];
        const std::vector<Eigen::Vector3d> positions = positions_of(mesh, parts, p);
        for (int32_t q : earlier) {
            if (!(layouts[q] == layouts[p])) continue;
            const PointMatch match =
                match_points(positions_of(mesh, parts, q), positions, tolerance);
            if (match == PointMatch::kRigid || (allow_mirror && match == PointMatch::kMirror)) {
                source[p] = q;
                break;
            }
        }
        if (source[p] == p) earlier.push_back(p);
    }
    return source;
}

void copy_instance_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                          const AtlasSurface& surface, const std::vector<int32_t>& source,
                          std::vector<AtlasChart>& charts, CornerSources& sources,
                          std::vector<int32_t>& part) {
    const int32_t old_count = static_cast<int32_t>(charts.size());
    // Triangle by triangle, in input order: an instance's triangle takes its source triangle's
    // chart (copied once per instance) and chart vertices; charts are numbered on first sight.
    std::vector<int32_t> kept(old_count, -1);                // old chart -> new, for non-instances
    std::map<std::pair<int32_t, int32_t>, int32_t> copy_of;  // (instance part, old chart) -> new
    std::vector<AtlasChart> out;
    std::vector<int32_t> out_part;
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        const int32_t p = parts.part_of_triangle(t);
        const int32_t s = source[p];
        const int32_t from = t - parts.first_triangle[p] + parts.first_triangle[s];
        const int32_t old = sources.chart[from];
        if (old >= old_count) {  // a point chart (parts that have one are never instances)
            sources.chart[t] = -1 - (old - old_count);  // numbered below, after the real ones
            continue;
        }
        if (s == p) {
            if (kept[old] < 0) {
                kept[old] = static_cast<int32_t>(out.size());
                out.push_back(std::move(charts[old]));
                out_part.push_back(part[old]);
            }
            sources.chart[t] = kept[old];
            continue;
        }
        const auto [it, added] = copy_of.emplace(std::make_pair(p, old), 0);
        if (added) {
            it->second = static_cast<int32_t>(out.size());
            // The source part's triangles come first: its chart has moved into `out`.
            AtlasChart copy = out[kept[old]];
            const int32_t offset = parts.first_vertex[p] - parts.first_vertex[s];
            for (size_t v = 0; v < copy.disk.surface_vertex.size(); ++v) {
                const int32_t input = surface.welded_vertex[copy.disk.surface_vertex[v]];
                copy.disk.mesh.positions[v] = mesh.positions[input + offset];
            }
            out.push_back(std::move(copy));
            out_part.push_back(p);
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
