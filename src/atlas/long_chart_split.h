// Step 4b: charts too long for the square atlas. At a resolution the atlas is a square; a chart
// whose longer side, at the density the charts' area would allow, is more than twice the
// square's side sets the atlas's density alone, and the square is then mostly empty (alligator, one chart 5.7
// times as long as wide, covered 0.086 of it; a 1000:1 strip, 0.001). Such a chart is cut across
// its length into pieces that each keep their part of its map: the uvs, and so the stretch of
// every triangle, stay as they were; only seams are added, and the pieces pack side by side.
#pragma once

#include <vector>

#include "atlas/atlas_surface.h"
#include "atlas/chart_mapping.h"
#include "core/settings.h"

namespace raps {

// Cuts the charts of `charts` that are too long (above) into pieces, in place: a chart's pieces
// follow it in order. Triangles of one input polygon stay in one piece. Does nothing with a
// density (pages are cropped to their charts, and a chart larger than a page is shrunk and
// reported) or when repacking (the input's islands are kept as they are).
void split_long_charts(const AtlasSurface& surface, const Settings& settings,
                       std::vector<AtlasChart>& charts);

}  // namespace raps
