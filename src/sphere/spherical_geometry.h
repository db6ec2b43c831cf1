// Geometry of points on the unit sphere, for the sphere domain (paper section 7): orientation,
// exact areas of geodesic triangles, great-circle lengths and the angles between great-circle
// arcs. A spherical map puts one unit vector per vertex; its triangles are the geodesic triangles
// of their corners.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/portable_math.h"
#include "metrics/map_geometry.h"

namespace raps {

// det[a, b, c]: positive when the triangle is counter-clockwise seen from outside the sphere
// (the origin on its inner side). A map's triangle is flipped when this is negative.
// Evaluated as a . ((b - a) x (c - a)), the same determinant: its rounding error is a few units
// of 2^-52 times |b - a| |c - a|, so the sign is that of the exact determinant of the stored
// points for every triangle but slivers, however small. a . (b x c) rounds by about 1e-16
// whatever the triangle's size, which is noise for the triangles of a squeezed limb (edges of
// 1e-9, det of 1e-17): measured on cow.off subdivided to 88K triangles, every centring boost
// then "turned over" some of them by rounding alone and was refused in 642 of 850 sweeps, so
// that the map drifted off-centre and continuation steps were taken back
// (docs/sphere-status.md).
inline double orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
    return a.dot((b - a).cross(c - a));
}

// Signed area (spherical excess) of the geodesic triangle abc, by Van Oosterom and Strackee
// (1983): tan(E / 2) = det[a, b, c] / (1 + a.b + b.c + c.a). Exact, stable for small triangles,
// negative for a flipped one; the areas of a bijective map add up to 4 pi.
inline double spherical_triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c) {
    return 2.0 * portable::atan2(orientation(a, b, c), 1.0 + a.dot(b) + b.dot(c) + c.dot(a));
}

// Great-circle distance between two unit vectors.
inline double arc_length(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return portable::atan2(a.cross(b).norm(), a.dot(b));
}

// The angle at a between the great-circle arcs to b and to c, as sine and cosine times the same
// positive factor: the arcs' tangents at a are b - (a.b) a and c - (a.c) a, whose cross product
// is det[a, b, c] a and whose dot product is b.c - (a.b)(a.c). The sine is negative when the
// triangle is flipped.
inline void spherical_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c, double* sine, double* cosine) {
    *sine = orientation(a, b, c);
    *cosine = b.dot(c) - a.dot(b) * a.dot(c);
}

// A spherical map: one unit vector per vertex.
class SphericalMapGeometry final : public MapGeometry {
  public:
    explicit SphericalMapGeometry(const std::vector<Eigen::Vector3d>& points) : u_(points) {}
    double area(int32_t a, int32_t b, int32_t c) const override {
        return spherical_triangle_area(u_[a], u_[b], u_[c]);
    }
    double length(int32_t a, int32_t b) const override { return arc_length(u_[a], u_[b]); }
    void angle(int32_t a, int32_t b, int32_t c, double* sine, double* cosine) const override {
        spherical_angle(u_[a], u_[b], u_[c], sine, cosine);
    }
    // The flat triangle of the three points, in an orthonormal frame of its plane oriented by
    // the outward direction, scaled so that its area is the spherical one.
    void edges(int32_t a, int32_t b, int32_t c, Eigen::Vector2d* ab,
               Eigen::Vector2d* ac) const override;

  private:
    const std::vector<Eigen::Vector3d>& u_;
};

}  // namespace raps
