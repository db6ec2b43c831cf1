// Reading PLY meshes (ASCII and binary, either byte order) for the samples: the vertex
// element's x, y, z and the face element's vertex_indices (or vertex_index) lists; other
// elements and properties are read past.
#pragma once

#include <string>

#include "mesh_io.h"

namespace raps_samples {

// `text` is the whole file. Throws std::runtime_error naming the file and the problem (a header
// it cannot read, no faces, a count or list longer than the file, an index that is negative or
// not whole, a face with fewer than 3 vertices, data cut short).
PolygonMesh read_ply(const std::string& path, const std::string& text);

}  // namespace raps_samples
