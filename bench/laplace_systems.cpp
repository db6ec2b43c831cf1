#include "laplace_systems.h"

#include <cstring>
#include <map>
#include <stdexcept>

#include "atlas/atlas_pipeline.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"
#include "mesh_io.h"
#include "weights/laplacian_weights.h"

namespace raps_bench {
namespace {

raps::TriangleMesh to_mesh(const std::vector<double>& positions,
                           const std::vector<uint32_t>& triangles) {
    raps::TriangleMesh mesh;
    mesh.positions.resize(positions.size() / 3);
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        mesh.positions[v] =
            Eigen::Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    mesh.triangles.resize(triangles.size() / 3);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        mesh.triangles[t] = {static_cast<int32_t>(triangles[3 * t]),
                             static_cast<int32_t>(triangles[3 * t + 1]),
                             static_cast<int32_t>(triangles[3 * t + 2])};
    }
    return mesh;
}

// The largest chart of the default atlas of `mesh` (one thread), as a mesh of its own.
raps::TriangleMesh largest_chart(const raps::TriangleMesh& mesh) {
    raps::Settings settings;
    settings.domain = raps::Domain::kAtlas;
    settings.threads = 1;
    raps::Progress progress;
    raps::PhaseTimes times{};
    raps::ThreadPool pool(1);
    const raps::AtlasOutput atlas = raps::build_atlas(mesh, raps::single_part(mesh), settings, progress, times, pool);
    std::map<uint32_t, int64_t> size;
    for (uint32_t c : atlas.chart_of) ++size[c];
    uint32_t best = 0;
    int64_t best_size = -1;
    for (const auto& [chart, count] : size) {
        if (count > best_size) best = chart, best_size = count;
    }
    raps::TriangleMesh chart;
    std::vector<int32_t> local(atlas.remap.size(), -1);
    for (size_t t = 0; t < atlas.chart_of.size(); ++t) {
        if (atlas.chart_of[t] != best) continue;
        raps::Triangle triangle;
        for (int k = 0; k < 3; ++k) {
            const uint32_t o = atlas.indices[3 * t + k];
            if (local[o] < 0) {
                local[o] = chart.vertex_count();
                chart.positions.push_back(mesh.positions[atlas.remap[o]]);
            }
            triangle[k] = local[o];
        }
        chart.triangles.push_back(triangle);
    }
    return chart;
}

// The Laplace system of `mesh` on its interior vertices, the boundary held: mean value weights
// with rows scaled to a unit diagonal (the disk domain's initial map, two right-hand sides), or
// the cotangent Laplacian (the free-boundary map's Cholesky, one right-hand side).
System laplace_system(const raps::TriangleMesh& mesh, bool cotangent) {
    const raps::Halfedges halfedges = raps::build_halfedges(mesh);
    const raps::VertexAdjacency adjacency = raps::build_vertex_adjacency(mesh, halfedges);
    std::vector<char> on_boundary(mesh.positions.size(), 0);
    for (const auto& loop : raps::boundary_loops(mesh, halfedges)) {
        for (int32_t v : loop) on_boundary[v] = 1;
    }
    const std::vector<double> weights = raps::laplacian_weights(
        mesh, adjacency,
        cotangent ? raps::WeightScheme::kCotangent : raps::WeightScheme::kMeanValue);
    System system;
    system.symmetric = cotangent;
    system.rhs_count = cotangent ? 1 : 2;
    system.triangles = mesh.triangle_count();
    std::vector<int32_t> unknown(mesh.positions.size(), -1), vertex;
    for (int32_t v = 0; v < mesh.vertex_count(); ++v) {
        if (!on_boundary[v]) {
            unknown[v] = static_cast<int32_t>(vertex.size());
            vertex.push_back(v);
        }
    }
    const int32_t n = static_cast<int32_t>(vertex.size());
    raps::SparsePattern& pattern = system.pattern;
    pattern.size = n;
    system.rhs.assign(static_cast<size_t>(system.rhs_count) * n, 0.0);
    for (int32_t row = 0; row < n; ++row) {
        const int32_t v = vertex[row];
        system.coordinates.push_back(mesh.positions[v]);
        double diagonal = 0;
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s)
            diagonal += weights[s];
        const double scale = cotangent ? 1.0 : 1.0 / diagonal;
        bool diagonal_placed = false;
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            const int32_t u = adjacency.neighbors[s];
            const int32_t column = unknown[u];
            if (column < 0) {
                // Held boundary vertex: its position's x and y stand for its uv.
                if (cotangent) continue;
                system.rhs[row] += weights[s] * scale * mesh.positions[u].x();
                system.rhs[n + row] += weights[s] * scale * mesh.positions[u].y();
                continue;
            }
            if (!diagonal_placed && column > row) {
                pattern.columns.push_back(row);
                system.values.push_back(diagonal * scale);
                diagonal_placed = true;
            }
            pattern.columns.push_back(column);
            system.values.push_back(-weights[s] * scale);
        }
        if (!diagonal_placed) {
            pattern.columns.push_back(row);
            system.values.push_back(diagonal * scale);
        }
        pattern.row_offsets.push_back(static_cast<int32_t>(pattern.columns.size()));
        if (cotangent) system.rhs[row] = 1.0;  // stands for the angle defect
    }
    return system;
}

}  // namespace

System build_system(const std::string& data, const std::string& name, int subdivisions,
                    bool cotangent) {
    const bool disk = name.compare(0, 5, "disk:") == 0;
    if (!disk && name.compare(0, 6, "chart:") != 0)
        throw std::runtime_error("unknown system " + name + " (disk:FILE or chart:FILE)");
    const raps_samples::PolygonMesh polygons =
        raps_samples::read_mesh(data + "/meshes/" + name.substr(disk ? 5 : 6));
    std::vector<double> positions = polygons.positions;
    std::vector<uint32_t> triangles = polygons.triangles();
    if (!disk) return laplace_system(largest_chart(to_mesh(positions, triangles)), cotangent);
    for (int s = 0; s < subdivisions; ++s) raps_samples::subdivide_midpoint(positions, triangles);
    return laplace_system(to_mesh(positions, triangles), cotangent);
}

FactorSize cholesky_size(const raps::SparsePattern& pattern, const std::vector<int32_t>& order) {
    const int32_t n = pattern.size;
    std::vector<int32_t> position(n), parent(n, -1), mark(n, -1);
    std::vector<int64_t> column_count(n, 1);
    for (int32_t k = 0; k < n; ++k) position[order[k]] = k;
    for (int32_t k = 0; k < n; ++k) {
        mark[k] = k;
        const int32_t u = order[k];
        for (int32_t p = pattern.row_offsets[u]; p < pattern.row_offsets[u + 1]; ++p) {
            for (int32_t i = position[pattern.columns[p]]; i < k && mark[i] != k; i = parent[i]) {
                if (parent[i] < 0) parent[i] = k;
                mark[i] = k;
                ++column_count[i];
            }
        }
    }
    FactorSize size;
    for (int64_t c : column_count) {
        size.nonzeros += c;
        size.flops += static_cast<double>(c) * static_cast<double>(c);
    }
    return size;
}

uint64_t bits_hash(const std::vector<double>& x) {
    uint64_t h = 1469598103934665603ull;
    for (double value : x) {
        uint64_t bits;
        std::memcpy(&bits, &value, sizeof(bits));
        for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xff)) * 1099511628211ull;
    }
    return h;
}

}  // namespace raps_bench
