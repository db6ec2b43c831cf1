#include "preview.h"

#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

#include "gltf_error.h"
#include "gltf_output.h"
#include "vec3.h"

namespace raps_gltf {

namespace {

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores matrices

Vec3 normalized(const Vec3& a) {
    const double n = std::sqrt(dot(a, a));
    return n > 0 ? Vec3{a[0] / n, a[1] / n, a[2] / n} : Vec3{0, 0, 0};
}

Mat4 identity() {
    return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row)
            for (int k = 0; k < 4; ++k) r[c * 4 + row] += a[k * 4 + row] * b[c * 4 + k];
    return r;
}

// node[key] when it is an array of n finite numbers, else empty (a malformed transform draws
// the node untransformed; the preview is a picture, not a validator).
std::vector<double> numbers(const Json& node, const char* key, size_t n) {
    std::vector<double> out;
    const auto it = node.find(key);
    if (it == node.end() || !it->is_array() || it->size() != n) return out;
    for (const Json& v : *it) {
        if (!v.is_number() || !std::isfinite(v.get<double>())) return {};
        out.push_back(v.get<double>());
    }
    return out;
}

Mat4 local_matrix(const Json& node) {
    const std::vector<double> matrix = numbers(node, "matrix", 16);
    if (!matrix.empty()) {
        Mat4 m;
        std::copy(matrix.begin(), matrix.end(), m.begin());
        return m;
    }
    const std::vector<double> translation = numbers(node, "translation", 3);
    const std::vector<double> rotation = numbers(node, "rotation", 4);
    const std::vector<double> scale = numbers(node, "scale", 3);
    Mat4 t = identity(), r = identity(), s = identity();
    if (!translation.empty()) {
        for (int k = 0; k < 3; ++k) t[12 + k] = translation[k];
    }
    if (!rotation.empty()) {
        const double x = rotation[0], y = rotation[1], z = rotation[2], w = rotation[3];
        r = {1 - 2 * (y * y + z * z),
             2 * (x * y + z * w),
             2 * (x * z - y * w),
             0,
             2 * (x * y - z * w),
             1 - 2 * (x * x + z * z),
             2 * (y * z + x * w),
             0,
             2 * (x * z + y * w),
             2 * (y * z - x * w),
             1 - 2 * (x * x + y * y),
             0,
             0,
             0,
             0,
             1};
    }
    if (!scale.empty()) {
        for (int k = 0; k < 3; ++k) s[k * 5] = scale[k];
    }
    return multiply(t, multiply(r, s));
}

Vec3 transform(const Mat4& m, const float* p) {
    Vec3 out;
    for (int row = 0; row < 3; ++row)
        out[row] = m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + m[12 + row];
    return out;
}

// A pastel colour per chart, by the golden-angle hue sequence, so neighbours differ.
std::array<double, 3> chart_colour(uint32_t chart) {
    const double h = std::fmod(chart * 0.618033988749895, 1.0) * 6.0;
    const double x = 1 - std::fabs(std::fmod(h, 2.0) - 1);
    std::array<double, 3> rgb{};
    const int sector = static_cast<int>(h);
    const double table[6][3] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
    for (int k = 0; k < 3; ++k) rgb[k] = 0.55 + 0.45 * table[sector % 6][k];
    return rgb;
}

class Canvas {
  public:
    Canvas(int w, int h)
        : w_(w), h_(h), rgb_(size_t(w) * h * 3, 1.0), depth_(size_t(w) * h, -1e300) {}
    int width() const { return w_; }
    int height() const { return h_; }

    void fill_rect(int x0, int y0, int x1, int y1, const std::array<double, 3>& c) {
        for (int y = std::max(0, y0); y < std::min(h_, y1); ++y)
            for (int x = std::max(0, x0); x < std::min(w_, x1); ++x) set(x, y, c);
    }

    // Triangle with per-pixel colour from `shade(b0, b1, b2)` (barycentrics) and optional depth.
    template <typename Shade>
    void triangle(const double* x, const double* y, const double* z, Shade shade) {
        const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (!(std::fabs(area) > 1e-12)) return;
        const int x0 = std::max(0, static_cast<int>(std::floor(std::min({x[0], x[1], x[2]}))));
        const int x1 = std::min(w_ - 1, static_cast<int>(std::ceil(std::max({x[0], x[1], x[2]}))));
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({y[0], y[1], y[2]}))));
        const int y1 = std::min(h_ - 1, static_cast<int>(std::ceil(std::max({y[0], y[1], y[2]}))));
        for (int py = y0; py <= y1; ++py) {
            for (int px = x0; px <= x1; ++px) {
                const double cx = px + 0.5, cy = py + 0.5;
                const double b0 = ((x[1] - cx) * (y[2] - cy) - (x[2] - cx) * (y[1] - cy)) / area;
                const double b1 = ((x[2] - cx) * (y[0] - cy) - (x[0] - cx) * (y[2] - cy)) / area;
                const double b2 = 1 - b0 - b1;
                if (b0 < 0 || b1 < 0 || b2 < 0) continue;
                if (z) {
                    const double d = b0 * z[0] + b1 * z[1] + b2 * z[2];
                    double& stored = depth_[size_t(py) * w_ + px];
                    if (d <= stored) continue;
                    stored = d;
                }
                set(px, py, shade(b0, b1, b2));
            }
        }
    }

    void line(double xa, double ya, double xb, double yb, const std::array<double, 3>& c) {
        const int steps = static_cast<int>(std::max(std::fabs(xb - xa), std::fabs(yb - ya))) + 1;
        for (int i = 0; i <= steps; ++i) {
            const double t = static_cast<double>(i) / steps;
            const int px = static_cast<int>(xa + t * (xb - xa)),
                      py = static_cast<int>(ya + t * (yb - ya));
            if (px >= 0 && py >= 0 && px < w_ && py < h_) set(px, py, c);
        }
    }

    // 2x2 box filter to 8-bit RGB.
    std::vector<uint8_t> downsampled() const {
        std::vector<uint8_t> out(size_t(w_ / 2) * (h_ / 2) * 3);
        for (int y = 0; y < h_ / 2; ++y)
            for (int x = 0; x < w_ / 2; ++x)
                for (int k = 0; k < 3; ++k) {
                    double sum = 0;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx)
                            sum += rgb_[(size_t(2 * y + dy) * w_ + 2 * x + dx) * 3 + k];
                    out[(size_t(y) * (w_ / 2) + x) * 3 + k] =
                        static_cast<uint8_t>(std::clamp(sum / 4, 0.0, 1.0) * 255 + 0.5);
                }
        return out;
    }

  private:
    void set(int x, int y, const std::array<double, 3>& c) {
        for (int k = 0; k < 3; ++k) rgb_[(size_t(y) * w_ + x) * 3 + k] = c[k];
    }
    int w_, h_;
    std::vector<double> rgb_;
    std::vector<double> depth_;
};

void draw_layouts(Canvas& canvas, int size, const BakeResult& bake) {
    const size_t n = bake.preview.size();
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const int rows = static_cast<int>((n + columns - 1) / columns);
    const int tile = size / std::max(columns, rows);
    const double top = (size - rows * tile) / 2.0;  // centre the tiles' rows vertically
    const std::array<double, 3> frame{0.6, 0.6, 0.6}, outline{0.1, 0.1, 0.15};
    for (size_t i = 0; i < n; ++i) {
        const PreviewGeometry& g = bake.preview[i];
        const double margin = tile * 0.04;
        const double aspect = g.atlas_height ? double(g.atlas_width) / g.atlas_height : 1.0;
        const double span = tile - 2 * margin;
        const double w = aspect >= 1 ? span : span * aspect, h = aspect >= 1 ? span / aspect : span;
        const double ox = (i % columns) * tile + margin, oy = top + (i / columns) * tile + margin;
        canvas.fill_rect(int(ox), int(oy), int(ox + w), int(oy + h), {0.97, 0.97, 0.97});
        canvas.line(ox, oy, ox + w, oy, frame);
        canvas.line(ox, oy + h, ox + w, oy + h, frame);
        canvas.line(ox, oy, ox, oy + h, frame);
        canvas.line(ox + w, oy, ox + w, oy + h, frame);
        // glTF uvs: v grows downwards, as image rows do.
        auto px = [&](uint32_t v) { return ox + g.uvs[2 * v] * w; };
        auto py = [&](uint32_t v) { return oy + g.uvs[2 * v + 1] * h; };
        std::map<std::pair<std::array<float, 2>, std::array<float, 2>>, int> edge_count;
        for (size_t t = 0; t < g.indices.size() / 3; ++t) {
            const uint32_t* v = &g.indices[3 * t];
            const double x[3] = {px(v[0]), px(v[1]), px(v[2])},
                         y[3] = {py(v[0]), py(v[1]), py(v[2])};
            const auto colour = chart_colour(g.chart_of_triangle[t]);
            canvas.triangle(x, y, nullptr, [&](double, double, double) { return colour; });
            for (int k = 0; k < 3; ++k) {
                std::array<float, 2> a{g.uvs[2 * v[k]], g.uvs[2 * v[k] + 1]};
                std::array<float, 2> b{g.uvs[2 * v[(k + 1) % 3]], g.uvs[2 * v[(k + 1) % 3] + 1]};
                if (b < a) std::swap(a, b);
                ++edge_count[{a, b}];
            }
        }
        // Chart outlines: uv edges only one triangle has.
        for (const auto& e : edge_count) {
            if (e.second != 1) continue;
            canvas.line(ox + e.first.first[0] * w, oy + e.first.first[1] * h,
                        ox + e.first.second[0] * w, oy + e.first.second[1] * h, outline);
        }
    }
}

void draw_model(Canvas& canvas, int x0, int size, const Asset& asset, const BakeResult& bake,
                const PreviewOptions& options) {
    // Instances: every node of the default scene that shows a baked mesh, with its world matrix.
    std::map<int, std::vector<int>> previews_of_mesh;
    for (size_t g = 0; g < bake.groups.size(); ++g) {
        auto& list = previews_of_mesh[bake.groups[g].mesh];
        const int p = bake.preview_of_group[g];
        if (std::find(list.begin(), list.end(), p) == list.end()) list.push_back(p);
    }
    std::vector<std::pair<int, Mat4>> instances;
    // load_asset checked that the nodes form a forest and that every index is in range. The
    // walk keeps its own stack (a hierarchy may be as deep as it has nodes) and draws each node
    // once, however often a scene lists it.
    const Json& nodes = array_of(asset.doc, "nodes");
    const Json& scenes = array_of(asset.doc, "scenes");
    std::vector<std::pair<size_t, Mat4>> stack;
    std::vector<bool> drawn(nodes.size(), false);
    if (!scenes.empty()) {
        const Json& scene = scenes[asset.doc.value("scene", size_t(0))];
        if (scene.contains("nodes")) {
            for (const Json& node : scene["nodes"])
                stack.emplace_back(node.get<size_t>(), identity());
        }
    }
    while (!stack.empty()) {
        const auto [node, parent] = stack.back();
        stack.pop_back();
        if (drawn[node]) continue;
        drawn[node] = true;
        const Json& n = nodes[node];
        const Mat4 world = multiply(parent, local_matrix(n));
        if (n.contains("mesh") && previews_of_mesh.count(n["mesh"].get<int>())) {
            for (int p : previews_of_mesh[n["mesh"].get<int>()]) instances.emplace_back(p, world);
        }
        if (n.contains("children")) {
            for (const Json& child : n["children"]) stack.emplace_back(child.get<size_t>(), world);
        }
    }
    if (instances.empty()) {  // no scene shows them: draw each atlas's geometry once
        for (size_t p = 0; p < bake.preview.size(); ++p) instances.emplace_back(int(p), identity());
    }

    const Vec3 toward_camera = normalized({0.55, 0.45, 0.7});
    const Vec3 right = normalized(cross({0, 1, 0}, toward_camera));
    const Vec3 up = cross(toward_camera, right);
    const Vec3 light = normalized({0.3, 0.8, 0.6});
    std::vector<std::vector<Vec3>> world(instances.size());
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (size_t i = 0; i < instances.size(); ++i) {
        const PreviewGeometry& g = bake.preview[instances[i].first];
        for (size_t v = 0; v < g.positions.size() / 3; ++v) {
            world[i].push_back(transform(instances[i].second, &g.positions[3 * v]));
            const double sx = dot(world[i].back(), right), sy = dot(world[i].back(), up);
            lo[0] = std::min(lo[0], sx), hi[0] = std::max(hi[0], sx);
            lo[1] = std::min(lo[1], sy), hi[1] = std::max(hi[1], sy);
        }
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-12});
    const double scale = size * 0.9 / extent;
    const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    for (size_t i = 0; i < instances.size(); ++i) {
        const PreviewGeometry& g = bake.preview[instances[i].first];
        const std::vector<Vec3>& p = world[i];
        for (size_t t = 0; t < g.indices.size() / 3; ++t) {
            const uint32_t* v = &g.indices[3 * t];
            double x[3], y[3], z[3];
            for (int k = 0; k < 3; ++k) {
                x[k] = x0 + size / 2.0 + (dot(p[v[k]], right) - cx) * scale;
                y[k] = size / 2.0 - (dot(p[v[k]], up) - cy) * scale;
                z[k] = dot(p[v[k]], toward_camera);
            }
            const Vec3 normal = normalized(cross(sub(p[v[1]], p[v[0]]), sub(p[v[2]], p[v[0]])));
            const double lit = 0.35 + 0.65 * std::fabs(dot(normal, light));
            const auto tint = chart_colour(g.chart_of_triangle[t]);
            canvas.triangle(x, y, z, [&](double b0, double b1, double b2) {
                const double u = b0 * g.uvs[2 * v[0]] + b1 * g.uvs[2 * v[1]] + b2 * g.uvs[2 * v[2]];
                const double w =
                    b0 * g.uvs[2 * v[0] + 1] + b1 * g.uvs[2 * v[1] + 1] + b2 * g.uvs[2 * v[2] + 1];
                const int check = (static_cast<int>(std::floor(u * options.checks)) +
                                   static_cast<int>(std::floor(w * options.checks))) &
                                  1;
                const double base = check ? 0.95 : 0.35;
                return std::array<double, 3>{base * tint[0] * lit, base * tint[1] * lit,
                                             base * tint[2] * lit};
            });
        }
    }
}

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const uint8_t* bytes = static_cast<const uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

void write_preview(const std::string& path, const Asset& asset, const BakeResult& bake,
                   const PreviewOptions& options) {
    const int size = 2 * options.height;  // supersampled
    Canvas canvas(2 * size, size);
    canvas.fill_rect(0, 0, size, size, {1, 1, 1});
    canvas.fill_rect(size, 0, 2 * size, size, {0.86, 0.88, 0.9});
    draw_layouts(canvas, size, bake);
    draw_model(canvas, size, size, asset, bake, options);
    canvas.fill_rect(size - 1, 0, size + 1, size, {0.5, 0.5, 0.5});
    const std::vector<uint8_t> pixels = canvas.downsampled();
    std::vector<uint8_t> png;
    if (!stbi_write_png_to_func(&append_bytes, &png, canvas.width() / 2, canvas.height() / 2, 3,
                                pixels.data(), canvas.width() / 2 * 3)) {
        throw GltfError("io", "cannot encode the preview PNG");
    }
    write_file_atomically(path, png);
}

}  // namespace raps_gltf
