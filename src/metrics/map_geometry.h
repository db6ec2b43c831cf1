// The geometry of a map's image, whatever its domain: the plane (a uv map) or the unit sphere.
// The error monitors (paper section 6) and the distortion statistics are written once against
// this interface, so that the sphere domain (section 7: "the error monitor functions we derived
// are not specific to the planar case") measures its triangles with the same code: exact
// spherical areas, great-circle lengths and the angles between great-circle arcs.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace raps {

class MapGeometry {
  public:
    virtual ~MapGeometry() = default;
    // Signed area of the image of triangle (a, b, c): positive when the map keeps its
    // orientation, negative for a flipped triangle.
    virtual double area(int32_t a, int32_t b, int32_t c) const = 0;
    // Length of the image of edge (a, b).
    virtual double length(int32_t a, int32_t b) const = 0;
    // The image's angle at a in triangle (a, b, c), as its sine (negative for a flipped
    // triangle) and cosine, both times the same positive factor (for atan2).
    virtual void angle(int32_t a, int32_t b, int32_t c, double* sine, double* cosine) const = 0;
    // The image's edges b - a and c - a in an orthonormal frame in which it is a flat triangle
    // of the triangle's signed area (for the stretch of Sander et al.).
    virtual void edges(int32_t a, int32_t b, int32_t c, Eigen::Vector2d* ab,
                       Eigen::Vector2d* ac) const = 0;
};

// A uv map: one point of the plane per vertex.
class PlanarMapGeometry final : public MapGeometry {
  public:
    explicit PlanarMapGeometry(const std::vector<Eigen::Vector2d>& uv) : uv_(uv) {}
    double area(int32_t a, int32_t b, int32_t c) const override {
        return 0.5 * cross(uv_[b] - uv_[a], uv_[c] - uv_[a]);
    }
    double length(int32_t a, int32_t b) const override { return (uv_[a] - uv_[b]).norm(); }
    void angle(int32_t a, int32_t b, int32_t c, double* sine, double* cosine) const override {
        const Eigen::Vector2d p = uv_[b] - uv_[a], q = uv_[c] - uv_[a];
        *sine = cross(p, q);
        *cosine = p.dot(q);
    }
    void edges(int32_t a, int32_t b, int32_t c, Eigen::Vector2d* ab,
               Eigen::Vector2d* ac) const override {
        *ab = uv_[b] - uv_[a];
        *ac = uv_[c] - uv_[a];
    }

  private:
    static double cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
        return p.x() * q.y() - p.y() * q.x();
    }
    const std::vector<Eigen::Vector2d>& uv_;
};

}  // namespace raps
