// A chart's smallest bounding box, which has a side along one of the convex hull's edges
// (Freeman and Shapira, "Determining the minimum-area encasing rectangle for an arbitrary
// closed curve", Communications of the ACM, 1975): each edge is tried. The rotation packing
// turns a chart by, and how well the chart fills its box, which merging weighs.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/triangle_mesh.h"

namespace raps {

// The counter-clockwise turn, in degrees in [0, 360), of a chart turned by `rotation` (cos,
// sin: its points p go to (r.x p.x + r.y p.y, -r.y p.x + r.x p.y), a clockwise turn) and then by
// `quarters` quarter turns counter-clockwise.
double turn_degrees(const Eigen::Vector2d& rotation, int quarters);

// A chart's smallest bounding box: the rotation (cos, sin) that aligns it with the axes, and how
// well the chart fills it, uv area / box area, in (0, 1]. Arches, rings and L-shapes fill it
// badly and waste packing space around them.
struct ChartBox {
    Eigen::Vector2d rotation = Eigen::Vector2d(1, 0);
    double fill = 1;
};
// boundary: the chart's boundary vertices, whose hull is the chart's when the map is injective
// (the hull is searched over them alone; a map that is not gets a box that is still valid, if
// not the smallest).
ChartBox smallest_bounding_box(const std::vector<Eigen::Vector2d>& uv,
                               const std::vector<Triangle>& triangles,
                               const std::vector<int32_t>& boundary);

// The axis-aligned box of the points `uv` turned by `rotation` (turned(), chart_raster.h): its
// lower corner and its size.
struct TurnedBox {
    Eigen::Vector2d origin, extent;
};
TurnedBox turned_box(const std::vector<Eigen::Vector2d>& uv, const Eigen::Vector2d& rotation);

// The area of the triangles in uv (each triangle's, unsigned).
double uv_area(const std::vector<Eigen::Vector2d>& uv, const std::vector<Triangle>& triangles);

}  // namespace raps
