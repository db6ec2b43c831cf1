// Instances in a scene, for stacking (RAPS_PARAM_ATLAS_STACK): a mesh given twice (or two
// meshes with the same triangles, the same artist's seams and congruent vertices) must come out
// with the same charts, or no chart of one could share the other's texels. The charts of a
// scene are not made part by part (merging works to one stretch budget for the whole atlas), so
// each instance's charts are replaced by copies of the charts of the part it copies: the same
// triangles over the same chart vertices and the same map, at the instance's own positions.
// Stacking (chart_stacking.h) then puts each copy on its original's place.
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/atlas_charts.h"
#include "atlas/atlas_pipeline.h"
#include "atlas/atlas_surface.h"
#include "atlas/corner_sources.h"
#include "core/triangle_mesh.h"

namespace raps {

// Per part, the earlier part it is an instance of (itself when none): the same vertex and
// triangle counts, the same triangles (indices relative to the part), the same groups and seam
// edges, and vertices that agree up to a rigid motion (or a mirror, when allowed) within
// tolerance times the part's extent. Parts with degenerate triangles that no chart holds are
// never sources (their point charts are not copied).
std::vector<int32_t> instance_sources(const TriangleMesh& mesh, const AtlasParts& parts,
                                      const CornerSources& sources, double tolerance,
                                      bool allow_mirror);

// Replaces the charts of every instance by copies of its source's charts, renumbering all
// charts by their first input triangle; `part` (per chart) and `sources` follow.
void copy_instance_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                          const AtlasSurface& surface, const std::vector<int32_t>& source,
                          std::vector<AtlasChart>& charts, CornerSources& sources,
                          std::vector<int32_t>& part);

}  // namespace raps
