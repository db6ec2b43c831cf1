// Reading OBJ, OFF and PLY meshes and writing OBJ with texture coordinates, for the command-line
// samples, the benchmarks and the tests. Not part of the library: raps itself never touches
// files. Polygons are kept as they are for writing back and cut into triangles for the library
// (PolygonMesh::polygon_triangles).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace raps_samples {

struct PolygonMesh {
    std::vector<double> positions;          // x, y, z per vertex
    std::vector<uint32_t> polygon_offsets;  // polygon p: corners [offsets[p], offsets[p + 1])
    std::vector<uint32_t> corners;          // vertex index per polygon corner
    // OBJ only (empty for OFF): per corner its `vt` index, 0-based (kNoTexcoord where the
    // corner names none, or one the file does not have), and per polygon its group: one id per
    // distinct (`g`, `usemtl`) pair, numbered from 0 in order of first use.
    static constexpr uint32_t kNoTexcoord = 0xffffffffu;
    std::vector<uint32_t> texcoord_corners;
    std::vector<uint32_t> polygon_groups;
    std::vector<double> texcoords;  // OBJ: u, v per `vt` line (v 0 where the line has none)

    size_t vertex_count() const { return positions.size() / 3; }
    size_t polygon_count() const { return polygon_offsets.size() - 1; }
    // Polygon f as size - 2 triangles of its corners (0 .. size - 1, counted from its first
    // corner): the fan from its first corner, unless that fan has a triangle of zero area
    // (corners in a straight line, as CAD n-gons have along straight edges); then ear clipping
    // in the polygon's plane, which never cuts off a straight corner, if it finds triangles that
    // all have area; else the fan.
    // Written into `out` (cleared first), which callers reuse: no allocation per polygon.
    void polygon_triangles(size_t f, std::vector<std::array<uint32_t, 3>>& out) const;
    // Triangle indices, polygon_triangles of each polygon in polygon order.
    std::vector<uint32_t> triangles() const;
    // Per triangle of triangles(), its polygon's group (empty without groups).
    std::vector<uint32_t> triangle_groups() const;
    // Per corner of triangles(), its texcoord's u, v (needs texcoord_corners without
    // kNoTexcoord): the file's own uvs, as raps_mesh_set_corner_uvs takes them.
    std::vector<double> triangle_texcoords() const;
    // The mesh with one vertex per distinct (vertex, texcoord) pair of its corners, in order of
    // first use: the input's uv seams become vertex splits. Needs texcoord_corners.
    PolygonMesh split_at_texcoord_seams() const;
};

// Reads .obj, .off or .ply (chosen by extension, case-insensitive; PLY: ply_reader.h). Throws
// std::runtime_error with the file, line and problem on anything it cannot read (a malformed
// number, an index 0 or one that resolves below 1, a face with fewer than 3 corners, a truncated
// OFF).
PolygonMesh read_mesh(const std::string& path);

// Writes OBJ: `v` for every vertex, `vt` for every uv pair, and each polygon as
// `f v/vt ...` with uv_corners[i] the vt index of corner i (0-based); with no uvs, `f v ...`.
// Written to a temporary
// file in the same folder and renamed, so `path` never holds a partial file. Throws
// std::runtime_error on failure.
void write_obj(const std::string& path, const PolygonMesh& mesh, const std::vector<double>& uvs,
               const std::vector<uint32_t>& uv_corners, const std::string& header_comment);

// One object of a multi-object OBJ: its name, mesh, uvs and uv corners as write_obj takes them.
struct ObjObject {
    std::string name;
    PolygonMesh mesh;
    std::vector<double> uvs;
    std::vector<uint32_t> uv_corners;
};

// Writes the objects into one OBJ, each as an `o` line followed by its `v`, `vt` and `f` lines
// (indices counted across the file), atomically like write_obj.
void write_obj_objects(const std::string& path, const std::vector<ObjObject>& objects,
                       const std::string& header_comment);

// 1-to-4 midpoint subdivision of a triangle mesh (x, y, z per vertex; 3 indices per triangle),
// each edge's midpoint created once: how the benchmarks build large meshes from the shared ones.
void subdivide_midpoint(std::vector<double>& positions, std::vector<uint32_t>& triangles);

// Writes `text` to `path` whole or not at all, or into a device or pipe (output_file.h).
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace raps_samples
