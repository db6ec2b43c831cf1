// Instances, for stacking (RAPS_PARAM_ATLAS_STACK): a piece of geometry repeated (a mesh given
// twice to a scene, or a connected piece of a mesh copied within it, moved, turned by any angle
// or, when allowed, mirrored) must come out with the same charts, or no chart of one copy could
// share the other's texels. Segmentation is not invariant under a turn (a quarter-turned copy
// of Duck was cut into 18 charts against 17) and a scene's charts are not made piece by piece
// (merging works to one stretch budget for the whole atlas), so each instance's charts are
// replaced by copies of the charts of the piece it repeats: the same triangles over the same
// chart vertices and the same map, at the instance's own positions. Stacking
// (chart_stacking.h) then puts each copy on its original's place.
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/atlas_charts.h"
#include "atlas/atlas_pipeline.h"
#include "atlas/atlas_surface.h"
#include "atlas/corner_sources.h"
#include "core/triangle_mesh.h"

namespace raps {

// The pieces instances are found among: the connected components of each part (triangles
// joined by welded vertices), each with its triangles in input order and its welded vertices
// in the order the triangles first use them; and per piece, the earlier piece it repeats
// (itself when none).
struct Instances {
    struct Piece {
        int32_t part = 0;
        std::vector<int32_t> triangles;  // input triangles, in order
        std::vector<int32_t> vertices;   // welded input vertices, by first use
    };
    std::vector<Piece> pieces;
    std::vector<int32_t> source;  // per piece
    bool any() const;
};

// welded[v]: input vertex v's representative, welded within its part. A piece repeats an earlier
// one when both have the same triangles over their vertices numbered by first use (corner for
// corner), the same groups, polygons and seam edges, and vertices that agree up to a rigid motion
// (or a mirror, when allowed) within tolerance times the piece's extent; with across_parts false,
// only pieces of one part. Pieces with degenerate triangles that no chart holds are never
// sources or instances (their point charts are not copied). Each piece is compared with the
// first 16 originals of its layout at most.
Instances find_instances(const TriangleMesh& mesh, const AtlasParts& parts,
                         const std::vector<int32_t>& welded, const CornerSources& sources,
                         size_t chart_count, double tolerance, bool allow_mirror,
                         bool across_parts);

// Replaces the charts of every instance by copies of its source's charts, renumbering all
// charts by their first input triangle; `part` (per chart) and `sources` follow.
void copy_instance_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                          const AtlasSurface& surface, const Instances& instances,
                          std::vector<AtlasChart>& charts, CornerSources& sources,
                          std::vector<int32_t>& part);

}  // namespace raps
