#include "atlas/uv_repack.h"

#include <algorithm>
#include <cmath>

#include "atlas/chart_packing.h"
#include "atlas/user_seams.h"
#include "core/error.h"
#include "metrics/distortion.h"
#include "core/union_find.h"

namespace raps {
namespace {

// One side of an edge as a triangle sees it: the welded vertex pair (smaller first) and the
// corner uvs at those two ends. Two sides with equal fields are one uv edge.
struct EdgeSide {
    int32_t hi;
    double lo_u, lo_v, hi_u, hi_v;
    int32_t triangle;
    int corner;    // the side runs from this corner of the triangle to the next
    int32_t next;  // the next side whose smaller vertex is the same, or -1
    bool same_edge(const EdgeSide& o) const {
        return hi == o.hi && lo_u == o.lo_u && lo_v == o.lo_v && hi_u == o.hi_u && hi_v == o.hi_v;
    }
};

// Islands by union-find over the triangles. Each side is looked up among the sides seen at its
// smaller vertex (a short list: the vertex's edges), so the work is linear; unions keep the
// smallest triangle as root, which makes the result independent of the order of the unions.
// An edge between two triangle groups or on a seam edge joins nothing (`seams`), as it
// separates charts when mapping: groups and closed or boundary-to-boundary seam paths then
// split an island whose uvs run across them.
std::vector<int32_t> island_roots(const TriangleMesh& mesh, const std::vector<int32_t>& welded,
                                  const UserSeams& seams) {
    const int32_t triangle_count = mesh.triangle_count();
    std::vector<int32_t> parent(triangle_count);
    for (int32_t t = 0; t < triangle_count; ++t) parent[t] = t;
    std::vector<int32_t> head(mesh.positions.size(), -1);
    std::vector<EdgeSide> sides;
    sides.reserve(3 * static_cast<size_t>(triangle_count));
    for (int32_t t = 0; t < triangle_count; ++t) {
        for (int k = 0; k < 3; ++k) {
            const int l = (k + 1) % 3;
            const int32_t a = welded[mesh.triangles[t][k]], b = welded[mesh.triangles[t][l]];
            if (a == b) continue;  // a collapsed edge joins nothing
            const Eigen::Vector2d& ua = mesh.corner_uv[3 * static_cast<size_t>(t) + k];
            const Eigen::Vector2d& ub = mesh.corner_uv[3 * static_cast<size_t>(t) + l];
            const int32_t lo = std::min(a, b);
            const EdgeSide side = a < b
                                      ? EdgeSide{b, ua.x(), ua.y(), ub.x(), ub.y(), t, k, head[lo]}
                                      : EdgeSide{a, ub.x(), ub.y(), ua.x(), ua.y(), t, k, head[lo]};
            int32_t found = head[lo];
            while (found >= 0 && !sides[found].same_edge(side)) found = sides[found].next;
            if (found >= 0 && seams.any() &&
                seams.cuts(t, k, sides[found].triangle, sides[found].corner))
                found = -1;
            if (found >= 0) {
                const int32_t x = find_root(parent, t),
                              y = find_root(parent, sides[found].triangle);
                parent[std::max(x, y)] = std::min(x, y);
            }
            sides.push_back(side);
            head[lo] = static_cast<int32_t>(sides.size() - 1);
        }
    }
    for (int32_t t = 0; t < triangle_count; ++t) parent[t] = find_root(parent, t);
    return parent;
}

double area_3d(const TriangleMesh& mesh, const Triangle& v) {
    return 0.5 * (mesh.positions[v[1]] - mesh.positions[v[0]])
                     .cross(mesh.positions[v[2]] - mesh.positions[v[0]])
                     .norm();
}

double area_uv(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const Eigen::Vector2d x = b - a, y = c - a;
    return 0.5 * std::abs(x.x() * y.y() - x.y() * y.x());
}

// "mesh 2: triangle 7" in a scene, "triangle 7" for one mesh.
std::string triangle_name(const AtlasParts& parts, int32_t t) {
    const int32_t p = parts.part_of_triangle(t);
    const std::string local = "triangle " + std::to_string(t - parts.first_triangle[p]);
    return parts.count() > 1 ? "mesh " + std::to_string(p) + ": " + local : local;
}

// The chart vertices: one per distinct (input vertex, uv) pair among the chart's corners,
// numbered in the order the triangles first use them. Each input vertex keeps the short list of
// (chart, uv) pairs seen at it.
void number_chart_vertices(const TriangleMesh& mesh, const std::vector<int32_t>& chart_of,
                           std::vector<std::array<int32_t, 3>>& corner_vertex,
                           std::vector<std::vector<int32_t>>& vertex_input,
                           std::vector<std::vector<Eigen::Vector2d>>& vertex_uv) {
    struct Seen {
        int32_t chart, local, next;
        Eigen::Vector2d uv;
    };
    std::vector<int32_t> head(mesh.positions.size(), -1);
    std::vector<Seen> seen;
    const int32_t charts = static_cast<int32_t>(vertex_input.size());
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        const int32_t c = chart_of[t];
        if (c >= charts) continue;  // a point chart
        for (int k = 0; k < 3; ++k) {
            const int32_t v = mesh.triangles[t][k];
            const Eigen::Vector2d& uv = mesh.corner_uv[3 * static_cast<size_t>(t) + k];
            int32_t found = head[v];
            while (found >= 0 && !(seen[found].chart == c && seen[found].uv == uv))
                found = seen[found].next;
            if (found < 0) {
                seen.push_back({c, static_cast<int32_t>(vertex_input[c].size()), head[v], uv});
                found = head[v] = static_cast<int32_t>(seen.size() - 1);
                vertex_input[c].push_back(v);
                vertex_uv[c].push_back(uv);
            }
            corner_vertex[t][k] = seen[found].local;
        }
    }
}

// The chart's own mesh and its uvs scaled uniformly to its 3D area (corner-relative, so that
// far-off islands lose no precision), with their stretch and smallest box.
AtlasChart make_chart(const TriangleMesh& mesh, const std::vector<int32_t>& input_of,
                      std::vector<Eigen::Vector2d> uv, std::vector<Triangle> triangles,
                      double surface_area, double uv_area) {
    AtlasChart chart;
    chart.disk.mesh.positions.reserve(input_of.size());
    for (int32_t v : input_of) chart.disk.mesh.positions.push_back(mesh.positions[v]);
    chart.disk.mesh.triangles = std::move(triangles);
    Eigen::Vector2d low = uv[0];
    for (const Eigen::Vector2d& p : uv) low = low.cwiseMin(p);
    const double scale = std::sqrt(surface_area / uv_area);
    for (Eigen::Vector2d& p : uv) p = (p - low) * scale;
    chart.map.uv = std::move(uv);
    const Stretch stretch =
        measure_stretch(chart.disk.mesh.positions, chart.map.uv, chart.disk.mesh.triangles);
    chart.map.stretch_l2 = stretch.l2;
    chart.map.stretch_linf = stretch.linf;
    chart.map.injective = false;  // not checked: the input's charts are kept as they are
    std::vector<int32_t> every(chart.map.uv.size());
    for (size_t v = 0; v < every.size(); ++v) every[v] = static_cast<int32_t>(v);
    chart.box = smallest_bounding_box(chart.map.uv, chart.disk.mesh.triangles, every);
    return chart;
}

}  // namespace

void check_corner_uvs(const TriangleMesh& mesh, const std::string& name) {
    const size_t corners = 3 * mesh.triangles.size();
    if (mesh.corner_uv.size() == corners) return;
    const std::string lead = name.empty() ? "the mesh" : name;
    throw Error(ErrorCode::kUvCount,
                mesh.corner_uv.empty()
                    ? lead +
                          " has no corner uvs to repack (set them with "
                          "raps_mesh_set_corner_uvs_f32/f64)"
                    : lead + " has " + std::to_string(mesh.corner_uv.size()) + " corner uvs but " +
                          std::to_string(mesh.triangles.size()) + " triangles (" +
                          std::to_string(corners) +
                          " corners): the indices changed since, or the count was wrong");
}

RepackedCharts repack_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                             const std::vector<int32_t>& welded) {
    const int32_t triangle_count = mesh.triangle_count();
    const std::vector<int32_t> root = island_roots(mesh, welded, UserSeams(mesh, false));
    // Islands numbered by first triangle; their areas and uv extents.
    std::vector<int32_t> island(triangle_count, -1), first_triangle;
    std::vector<double> surface, uv_area;
    std::vector<Eigen::Vector2d> low, high;
    std::vector<int64_t> size;
    double total = 0;
    for (int32_t t = 0; t < triangle_count; ++t) {
        if (island[root[t]] < 0) {
            island[root[t]] = static_cast<int32_t>(first_triangle.size());
            first_triangle.push_back(t);
            surface.push_back(0);
            uv_area.push_back(0);
            low.push_back(Eigen::Vector2d::Constant(1e300));
            high.push_back(Eigen::Vector2d::Constant(-1e300));
            size.push_back(0);
        }
        const int32_t i = island[t] = island[root[t]];
        const Eigen::Vector2d* uv = &mesh.corner_uv[3 * static_cast<size_t>(t)];
        const double a = area_3d(mesh, mesh.triangles[t]);
        surface[i] += a;
        total += a;
        uv_area[i] += area_uv(uv[0], uv[1], uv[2]);
        for (int k = 0; k < 3; ++k) {
            low[i] = low[i].cwiseMin(uv[k]);
            high[i] = high[i].cwiseMax(uv[k]);
        }
        ++size[i];
    }
    // Islands without surface (as the atlas calls a triangle degenerate: below 1e-12 of the
    // mean triangle's area) get no texels; one with surface but no uv area has no shape.
    const double degenerate = 1e-12 * total / triangle_count;
    RepackedCharts out;
    std::vector<int32_t> chart_of_island(first_triangle.size(), -1);
    std::vector<int32_t> point_of_part(parts.count(), -1);
    int32_t charts = 0;
    for (size_t i = 0; i < first_triangle.size(); ++i) {
        if (!(surface[i] > degenerate * static_cast<double>(size[i]))) continue;
        const double diagonal = (high[i] - low[i]).squaredNorm();
        if (!(uv_area[i] > 1e-12 * diagonal)) {
            throw Error(ErrorCode::kDegenerateUvChart,
                        "the uv chart of " + triangle_name(parts, first_triangle[i]) + " (" +
                            std::to_string(size[i]) +
                            " triangles) has zero uv area: it has no shape to repack");
        }
        chart_of_island[i] = charts++;
    }
    for (size_t i = 0; i < first_triangle.size(); ++i) {
        if (chart_of_island[i] >= 0) continue;
        int32_t& point = point_of_part[parts.part_of_triangle(first_triangle[i])];
        if (point < 0) {
            point = charts + static_cast<int32_t>(out.point_chart_part.size());
            out.point_chart_part.push_back(parts.part_of_triangle(first_triangle[i]));
        }
        chart_of_island[i] = point;
    }
    out.chart_of.resize(triangle_count);
    for (int32_t t = 0; t < triangle_count; ++t) out.chart_of[t] = chart_of_island[island[t]];

    out.corner_vertex.assign(triangle_count, {0, 0, 0});
    std::vector<std::vector<int32_t>> vertex_input(charts);
    std::vector<std::vector<Eigen::Vector2d>> vertex_uv(charts);
    number_chart_vertices(mesh, out.chart_of, out.corner_vertex, vertex_input, vertex_uv);
    std::vector<std::vector<Triangle>> triangles(charts);
    std::vector<double> chart_surface(charts, 0), chart_uv(charts, 0);
    for (int32_t t = 0; t < triangle_count; ++t) {
        const int32_t c = out.chart_of[t];
        if (c >= charts) continue;
        triangles[c].push_back(out.corner_vertex[t]);
        chart_surface[c] = surface[island[t]];
        chart_uv[c] = uv_area[island[t]];
    }
    out.charts.reserve(charts);
    for (int32_t c = 0; c < charts; ++c) {
        out.charts.push_back(make_chart(mesh, vertex_input[c], std::move(vertex_uv[c]),
                                        std::move(triangles[c]), chart_surface[c], chart_uv[c]));
    }
    return out;
}

}  // namespace raps
