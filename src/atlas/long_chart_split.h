// Step 4b: charts too long for the square atlas. At a resolution the atlas is a square; a chart
// whose longer side, at the density the charts' area would allow, is longer than the square's
// side sets the atlas's density alone, and the square is then partly empty (alligator, one chart
// 5.7 times as long as wide, covered 0.086 of it; a 1000:1 strip, 0.001). Such a chart is cut
// across its length into pieces that each keep their part of its map: the uvs, and so the stretch
// of every triangle, stay as they were; only seams are added, and the pieces pack side by side.
#pragma once

#include <utility>
#include <vector>

#include "atlas/atlas_surface.h"
#include "atlas/chart_mapping.h"
#include "core/settings.h"

namespace raps {

// Charts worth packing both whole and cut (between once and 1.25 times the side, under half
// the area): each one's index in the charts split_long_charts leaves, and its pieces.
struct LongChartCuts {
    std::vector<std::pair<size_t, std::vector<AtlasChart>>> pieces;  // ascending indices
};

// Cuts the charts of `charts` that are too long (above) into pieces, in place: a chart's pieces
// follow it in order. Triangles of one input polygon stay in one piece. Returns the charts that
// may or may not be too long, left whole, with their pieces. Does nothing with a density (pages
// are cropped to their charts, and a chart larger than a page is shrunk and reported) or when
// repacking (the input's islands are kept as they are). `beat` is told its start fraction as
// the charts are measured and cut.
LongChartCuts split_long_charts(const AtlasSurface& surface, const Settings& settings,
                                std::vector<AtlasChart>& charts, const ProgressSpan& beat);

// The atlas with them cut is kept when it packs at a density this much higher: the density
// search ends within 1%, so less is the search's own spread, not worth a seam.
constexpr double kCutPacksDenser = 1.01;

// `charts` with the charts of `cuts` replaced by their pieces (in their place, in order).
std::vector<AtlasChart> with_cuts(const std::vector<AtlasChart>& charts, const LongChartCuts& cuts);

}  // namespace raps
