#include "mesh_io.h"

#include "output_file.h"
#include "ply_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <unistd.h>

namespace raps_samples {
namespace {

std::string lower_extension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

std::string read_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw std::runtime_error(path + ": read error");
    return buffer.str();
}

// A cursor over one line of text. A token that starts with '#' starts a comment, which runs to
// the end of the line (exporters write them after faces; a '#' inside a name is kept).
struct Tokens {
    const char* p;
    const char* end;
    bool next(std::string_view& token) {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
        if (p >= end || *p == '#') return false;
        const char* start = p;
        while (p < end && *p != ' ' && *p != '\t' && *p != '\r') ++p;
        token = std::string_view(start, static_cast<size_t>(p - start));
        return true;
    }
};

[[noreturn]] void fail(const std::string& path, size_t line, const std::string& what) {
    throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

double parse_double(std::string_view token, const std::string& path, size_t line) {
    double value = 0;
    const char* first = token.data();
    if (!token.empty() && token[0] == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
        fail(path, line, "cannot read number '" + std::string(token) + "'");
    }
    return value;
}

// A texcoord's coordinate; NaN when it is not a number. Only --repack reads them (and the
// library refuses NaN there, naming the corner), so a file whose vt lines nothing uses still
// reads as before.
double lenient_double(std::string_view token) {
    double value = 0;
    const char* first = token.data();
    if (!token.empty() && token[0] == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
    return ec != std::errc() || ptr != token.data() + token.size() ? NAN : value;
}

long long parse_integer(std::string_view token, const std::string& path, size_t line) {
    long long value = 0;
    const char* first = token.data();
    if (!token.empty() && token[0] == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
        fail(path, line, "cannot read index '" + std::string(token) + "'");
    }
    return value;
}

// A corner's `vt` index, 0-based, from "v/vt/vn"; kNoTexcoord when it has none or names one the
// file does not have. Not an error here: most callers never read texcoords, and the one that
// does (raps-param --keep-uv-seams) refuses such a file itself.
uint32_t texcoord_of(std::string_view corner, size_t texcoord_count) {
    const size_t slash = corner.find('/');
    if (slash == std::string_view::npos) return PolygonMesh::kNoTexcoord;
    std::string_view text = corner.substr(slash + 1);
    text = text.substr(0, text.find('/'));
    long long index = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
    if (ec != std::errc() || ptr != text.data() + text.size() || index == 0)
        return PolygonMesh::kNoTexcoord;
    const long long resolved =
        index > 0 ? index - 1 : static_cast<long long>(texcoord_count) + index;
    if (resolved < 0 || resolved >= static_cast<long long>(texcoord_count))
        return PolygonMesh::kNoTexcoord;
    return static_cast<uint32_t>(resolved);
}

// The next logical line of an OBJ file at p: physical lines that end in a backslash are joined
// with the next (the format's line continuation). Advances p and counts physical lines.
std::string_view next_obj_line(const char*& p, const char* end, size_t& line_number,
                               std::string& joined) {
    joined.clear();
    for (;;) {
        const char* line_end = static_cast<const char*>(std::memchr(p, '\n', end - p));
        if (!line_end) line_end = end;
        ++line_number;
        const char* last = line_end;
        while (last > p && (last[-1] == '\r' || last[-1] == ' ' || last[-1] == '\t')) --last;
        const bool continues = last > p && last[-1] == '\\' && line_end < end;
        const char* start = p;
        p = line_end < end ? line_end + 1 : end;
        if (!continues && joined.empty()) return std::string_view(start, line_end - start);
        joined.append(start, continues ? last - 1 : line_end);
        joined += ' ';
        if (!continues) return joined;
    }
}

PolygonMesh read_obj(const std::string& path, const std::string& text) {
    PolygonMesh mesh;
    mesh.polygon_offsets.push_back(0);
    size_t texcoord_count = 0;
    std::string group_name, material;
    std::map<std::pair<std::string, std::string>, uint32_t> group_ids;
    size_t line_number = 0;
    std::string joined;
    const char* p = text.data();
    const char* end = p + text.size();
    while (p < end) {
        const size_t first_line = line_number + 1;
        const std::string_view line = next_obj_line(p, end, line_number, joined);
        Tokens tokens{line.data(), line.data() + line.size()};
        std::string_view keyword;
        if (!tokens.next(keyword)) continue;
        if (keyword == "v") {
            std::string_view coordinate;
            for (int c = 0; c < 3; ++c) {
                if (!tokens.next(coordinate))
                    fail(path, first_line, "vertex with fewer than 3 coordinates");
                mesh.positions.push_back(parse_double(coordinate, path, first_line));
            }
        } else if (keyword == "f") {
            std::string_view corner;
            size_t corners = 0;
            while (tokens.next(corner)) {
                const std::string_view vertex = corner.substr(0, corner.find('/'));
                const long long index = parse_integer(vertex, path, first_line);
                const long long resolved =
                    index > 0 ? index - 1 : static_cast<long long>(mesh.vertex_count()) + index;
                if (index == 0 || resolved < 0 || resolved > 0xffffffffLL) {
                    fail(path, first_line, "vertex index " + std::to_string(index) + " is invalid");
                }
                mesh.corners.push_back(static_cast<uint32_t>(resolved));
                mesh.texcoord_corners.push_back(texcoord_of(corner, texcoord_count));
                ++corners;
            }
            if (corners < 3) fail(path, first_line, "face with fewer than 3 vertices");
            mesh.polygon_offsets.push_back(static_cast<uint32_t>(mesh.corners.size()));
            mesh.polygon_groups.push_back(group_ids
                                              .emplace(std::make_pair(group_name, material),
                                                       static_cast<uint32_t>(group_ids.size()))
                                              .first->second);
        } else if (keyword == "vt") {
            ++texcoord_count;
            std::string_view coordinate;
            mesh.texcoords.push_back(tokens.next(coordinate) ? lenient_double(coordinate) : NAN);
            mesh.texcoords.push_back(tokens.next(coordinate) ? lenient_double(coordinate) : 0.0);
        } else if (keyword == "g" || keyword == "usemtl") {
            std::string name;
            for (std::string_view part; tokens.next(part);) name += std::string(part) + ' ';
            (keyword == "g" ? group_name : material) = name;
        }
        // vn, o, s, mtllib, l, p and comments carry nothing raps uses.
    }
    return mesh;
}

// The OFF header, tokens[0]: "OFF", or Geomview's variants with numbers after x y z on every
// vertex line (ST texture coordinates, C colour, N normal: "STCNOFF" at most), and with the
// vertex count run into it ("OFF1234 5678 0", as ModelNet writes it: the count becomes a token
// of its own). Returns whether vertex lines carry such extras (skipped).
bool read_off_header(const std::string& path,
                     std::vector<std::pair<std::string_view, size_t>>& tokens) {
    if (tokens.empty()) fail(path, 1, "file ends before the OFF header");
    std::string_view header = tokens[0].first;
    const size_t line = tokens[0].second;
    const size_t off = header.find("OFF");
    if (off == std::string_view::npos) fail(path, line, "does not start with OFF");
    const std::string_view prefix = header.substr(0, off);
    if (prefix.find_first_of("4n") != std::string_view::npos) {
        fail(path, line, "'" + std::string(header) + "': only 3D OFF is read (not 4OFF or nOFF)");
    }
    if (prefix != "" && prefix != "ST" && prefix != "C" && prefix != "N" && prefix != "STC" &&
        prefix != "STN" && prefix != "CN" && prefix != "STCN") {
        fail(path, line, "does not start with OFF");
    }
    const std::string_view rest = header.substr(off + 3);
    if (!rest.empty()) {
        if (rest.find_first_not_of("0123456789") != std::string_view::npos)
            fail(path, line, "does not start with OFF");
        tokens[0].first = header.substr(0, off + 3);
        tokens.insert(tokens.begin() + 1, std::make_pair(rest, line));
    }
    if (tokens.size() > 1 && tokens[1].first == "BINARY") {
        fail(path, line, "binary OFF is not read (only the text form)");
    }
    return !prefix.empty();
}

PolygonMesh read_off(const std::string& path, const std::string& text) {
    // OFF: a header line "OFF" (optionally followed by the counts), then "V F E", then V points
    // and F faces "k i0 .. ik-1" (possibly followed by a colour). '#' starts a comment.
    std::vector<std::pair<std::string_view, size_t>> tokens;
    size_t line_number = 0;
    const char* p = text.data();
    const char* end = p + text.size();
    while (p < end) {
        const char* line_end = static_cast<const char*>(std::memchr(p, '\n', end - p));
        if (!line_end) line_end = end;
        ++line_number;
        const char* hash = static_cast<const char*>(std::memchr(p, '#', line_end - p));
        Tokens line{p, hash ? hash : line_end};
        p = line_end + 1;
        std::string_view token;
        while (line.next(token)) tokens.emplace_back(token, line_number);
    }
    size_t at = 0;
    auto next = [&](const char* what) -> std::pair<std::string_view, size_t> {
        if (at >= tokens.size()) fail(path, line_number, std::string("file ends before ") + what);
        return tokens[at++];
    };
    const bool vertex_extras = read_off_header(path, tokens);
    ++at;
    auto count = [&](const char* what) {
        const auto token = next(what);
        const long long value = parse_integer(token.first, path, token.second);
        if (value < 0) fail(path, token.second, what + std::string(" is negative"));
        return static_cast<size_t>(value);
    };
    const size_t vertex_count = count("the vertex count");
    const size_t face_count = count("the face count");
    count("the edge count");
    PolygonMesh mesh;
    mesh.positions.reserve(3 * std::min<size_t>(vertex_count, tokens.size()));
    for (size_t i = 0; i < 3 * vertex_count; ++i) {
        const auto token = next("all vertices are read");
        mesh.positions.push_back(parse_double(token.first, path, token.second));
        if (vertex_extras && i % 3 == 2) {  // texcoords, colour, normal
            while (at < tokens.size() && tokens[at].second == token.second) ++at;
        }
    }
    mesh.polygon_offsets.push_back(0);
    for (size_t f = 0; f < face_count; ++f) {
        const auto size_token = next("all faces are read");
        const long long corners = parse_integer(size_token.first, path, size_token.second);
        if (corners < 3) fail(path, size_token.second, "face with fewer than 3 vertices");
        const size_t face_line = size_token.second;
        for (long long c = 0; c < corners; ++c) {
            const auto token = next("all faces are read");
            if (token.second != face_line) fail(path, face_line, "face line ends early");
            const long long index = parse_integer(token.first, path, token.second);
            if (index < 0 || index > 0xffffffffLL) fail(path, token.second, "invalid vertex index");
            mesh.corners.push_back(static_cast<uint32_t>(index));
        }
        mesh.polygon_offsets.push_back(static_cast<uint32_t>(mesh.corners.size()));
        while (at < tokens.size() && tokens[at].second == face_line) ++at;  // colour
    }
    return mesh;
}

void append_number(std::string& out, double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out.append(buffer, result.ptr);
}

}  // namespace

void PolygonMesh::polygon_triangles(size_t f, std::vector<std::array<uint32_t, 3>>& fan) const {
    const uint32_t begin = polygon_offsets[f], size = polygon_offsets[f + 1] - begin;
    fan.clear();
    for (uint32_t i = 0; i + 2 < size; ++i) fan.push_back({0, i + 1, i + 2});
    if (size <= 3) return;
    auto point = [&](uint32_t k) {
        const double* p = &positions[3 * static_cast<size_t>(corners[begin + k])];
        return std::array<double, 3>{p[0], p[1], p[2]};
    };
    auto sub = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
        return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    };
    auto cross = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
        return std::array<double, 3>{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                     u[0] * v[1] - u[1] * v[0]};
    };
    auto dot = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
        return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    };
    // The polygon's normal (Newell) and its longest edge, squared: "zero area" is below 1e-12
    // of that edge's square, whatever the units.
    std::array<double, 3> normal = {0, 0, 0};
    double longest = 0;
    for (uint32_t k = 0; k < size; ++k) {
        const std::array<double, 3> p = point(k), q = point((k + 1) % size);
        const std::array<double, 3> n = cross(p, q);
        for (int d = 0; d < 3; ++d) normal[d] += n[d];
        longest = std::max(longest, dot(sub(q, p), sub(q, p)));
    }
    const double flat = 1e-12 * longest;
    auto signed_area = [&](uint32_t a, uint32_t b, uint32_t c) {  // twice, along the normal
        const double length = std::sqrt(dot(normal, normal));
        return length > 0
                   ? dot(cross(sub(point(b), point(a)), sub(point(c), point(a))), normal) / length
                   : 0.0;
    };
    bool fan_is_flat = false;
    for (const auto& t : fan) fan_is_flat |= !(std::abs(signed_area(t[0], t[1], t[2])) > flat);
    if (!fan_is_flat) return;
    // Ear clipping: each time the ear (a corner whose triangle with its neighbours turns the
    // polygon's way with area and holds no other corner) of the roundest triangle, the first of
    // equals. Corners in a straight line are never ears, and clipping the roundest ear first
    // leaves no straight run for last (the first ear each time, along a rectangle's bottom,
    // left its top as a flat remainder).
    std::vector<uint32_t> left(size);
    for (uint32_t k = 0; k < size; ++k) left[k] = k;
    auto roundness = [&](uint32_t a, uint32_t b, uint32_t c) {
        const std::array<double, 3> u = sub(point(b), point(a)), v = sub(point(c), point(b)),
                                    w = sub(point(a), point(c));
        return signed_area(a, b, c) / (dot(u, u) + dot(v, v) + dot(w, w));
    };
    std::vector<std::array<uint32_t, 3>> ears;
    while (left.size() > 3) {
        const size_t n = left.size();
        size_t best = n;
        double best_roundness = 0;
        for (size_t k = 0; k < n; ++k) {
            const uint32_t a = left[(k + n - 1) % n], b = left[k], c = left[(k + 1) % n];
            if (!(signed_area(a, b, c) > flat)) continue;
            bool holds_corner = false;
            for (size_t j = 0; j < n && !holds_corner; ++j) {
                const uint32_t p = left[j];
                if (p == a || p == b || p == c) continue;
                holds_corner = signed_area(a, b, p) >= -flat && signed_area(b, c, p) >= -flat &&
                               signed_area(c, a, p) >= -flat;
            }
            const double r = roundness(a, b, c);
            if (!holds_corner && (best == n || r > best_roundness)) {
                best = k;
                best_roundness = r;
            }
        }
        if (best == n) return;  // the fan, as it is
        ears.push_back({left[(best + n - 1) % n], left[best], left[(best + 1) % n]});
        left.erase(left.begin() + static_cast<std::ptrdiff_t>(best));
    }
    if (!(signed_area(left[0], left[1], left[2]) > flat)) return;
    ears.push_back({left[0], left[1], left[2]});
    fan = std::move(ears);
}

std::vector<uint32_t> PolygonMesh::triangles() const {
    std::vector<uint32_t> out;
    out.reserve(3 * (corners.size() - 2 * polygon_count()));
    std::vector<std::array<uint32_t, 3>> parts;
    for (size_t f = 0; f < polygon_count(); ++f) {
        polygon_triangles(f, parts);
        for (const std::array<uint32_t, 3>& t : parts) {
            for (uint32_t k : t) out.push_back(corners[polygon_offsets[f] + k]);
        }
    }
    return out;
}

std::vector<double> PolygonMesh::triangle_texcoords() const {
    std::vector<double> out;
    auto add = [&](uint32_t corner) {
        out.push_back(texcoords[2 * static_cast<size_t>(texcoord_corners[corner])]);
        out.push_back(texcoords[2 * static_cast<size_t>(texcoord_corners[corner]) + 1]);
    };
    std::vector<std::array<uint32_t, 3>> parts;
    for (size_t f = 0; f < polygon_count(); ++f) {
        polygon_triangles(f, parts);
        for (const std::array<uint32_t, 3>& t : parts) {
            for (uint32_t k : t) add(polygon_offsets[f] + k);
        }
    }
    return out;
}

std::vector<uint32_t> PolygonMesh::triangle_groups() const {
    std::vector<uint32_t> out;
    if (polygon_groups.empty()) return out;
    for (size_t f = 0; f < polygon_count(); ++f)
        out.insert(out.end(), polygon_offsets[f + 1] - polygon_offsets[f] - 2, polygon_groups[f]);
    return out;
}

PolygonMesh PolygonMesh::split_at_texcoord_seams() const {
    PolygonMesh split = *this;
    split.positions.clear();
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> vertex_of;
    for (size_t c = 0; c < corners.size(); ++c) {
        const auto [it, added] = vertex_of.emplace(std::make_pair(corners[c], texcoord_corners[c]),
                                                   static_cast<uint32_t>(vertex_of.size()));
        if (added) {
            split.positions.insert(split.positions.end(), positions.begin() + 3 * corners[c],
                                   positions.begin() + 3 * corners[c] + 3);
        }
        split.corners[c] = it->second;
    }
    return split;
}

PolygonMesh read_mesh(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext != "obj" && ext != "off" && ext != "ply") {
        throw std::runtime_error(path + ": unknown mesh format (expected .obj, .off or .ply)");
    }
    std::string text = read_all(path);
    if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // a UTF-8 byte order mark
    // Lines ended by a carriage return alone (classic Mac OS exporters): one line otherwise.
    if (ext != "ply" && text.find('\n') == std::string::npos)
        std::replace(text.begin(), text.end(), '\r', '\n');
    if (ext == "ply") return read_ply(path, text);
    return ext == "obj" ? read_obj(path, text) : read_off(path, text);
}

void write_file_atomically(const std::string& path, const std::string& text) {
    const OutputFile target = output_file(path);
    if (target.direct) return write_into(target.path, text.data(), text.size());
    const std::string temporary = target.path + ".tmp." + std::to_string(getpid());
    FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) {
        throw std::runtime_error(path + ": cannot write (" + std::strerror(errno) + ")");
    }
    const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    const bool flushed = std::fflush(file) == 0 && fsync(fileno(file)) == 0;
    const bool closed = std::fclose(file) == 0;
    if (!written || !flushed || !closed ||
        std::rename(temporary.c_str(), target.path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::remove(temporary.c_str());
        throw std::runtime_error(path + ": cannot write (" + reason + ")");
    }
}

namespace {

// The `v`, `vt` and `f` lines of one mesh, its indices after the `v_offset` vertices and
// `vt_offset` uv pairs written before it.
void append_obj_body(std::string& out, const PolygonMesh& mesh, const std::vector<double>& uvs,
                     const std::vector<uint32_t>& uv_corners, size_t v_offset, size_t vt_offset) {
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        out += "v ";
        append_number(out, mesh.positions[3 * v]);
        out += ' ';
        append_number(out, mesh.positions[3 * v + 1]);
        out += ' ';
        append_number(out, mesh.positions[3 * v + 2]);
        out += '\n';
    }
    for (size_t t = 0; t < uvs.size() / 2; ++t) {
        out += "vt ";
        append_number(out, uvs[2 * t]);
        out += ' ';
        append_number(out, uvs[2 * t + 1]);
        out += '\n';
    }
    for (size_t f = 0; f < mesh.polygon_count(); ++f) {
        out += 'f';
        for (uint32_t c = mesh.polygon_offsets[f]; c < mesh.polygon_offsets[f + 1]; ++c) {
            out += ' ';
            out += std::to_string(mesh.corners[c] + v_offset + 1);
            if (!uv_corners.empty()) {
                out += '/';
                out += std::to_string(uv_corners[c] + vt_offset + 1);
            }
        }
        out += '\n';
    }
}

}  // namespace

void write_obj(const std::string& path, const PolygonMesh& mesh, const std::vector<double>& uvs,
               const std::vector<uint32_t>& uv_corners, const std::string& header_comment) {
    std::string out;
    out.reserve(64 * (mesh.vertex_count() + uvs.size() / 2) + 24 * mesh.corners.size());
    out += "# " + header_comment + "\n";
    append_obj_body(out, mesh, uvs, uv_corners, 0, 0);
    write_file_atomically(path, out);
}

void write_obj_objects(const std::string& path, const std::vector<ObjObject>& objects,
                       const std::string& header_comment) {
    std::string out = "# " + header_comment + "\n";
    size_t v_offset = 0, vt_offset = 0;
    for (const ObjObject& object : objects) {
        out += "o " + object.name + "\n";
        append_obj_body(out, object.mesh, object.uvs, object.uv_corners, v_offset, vt_offset);
        v_offset += object.mesh.vertex_count();
        vt_offset += object.uvs.size() / 2;
    }
    write_file_atomically(path, out);
}

void subdivide_midpoint(std::vector<double>& positions, std::vector<uint32_t>& triangles) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
    auto middle = [&](uint32_t a, uint32_t b) {
        const auto key = std::make_pair(std::min(a, b), std::max(a, b));
        const auto it = midpoint.find(key);
        if (it != midpoint.end()) return it->second;
        const uint32_t id = static_cast<uint32_t>(positions.size() / 3);
        for (int c = 0; c < 3; ++c)
            positions.push_back(0.5 * (positions[3 * a + c] + positions[3 * b + c]));
        midpoint.emplace(key, id);
        return id;
    };
    std::vector<uint32_t> next;
    next.reserve(4 * triangles.size());
    for (size_t t = 0; t < triangles.size(); t += 3) {
        const uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
        const uint32_t ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
        const uint32_t children[] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
        next.insert(next.end(), children, children + 12);
    }
    triangles.swap(next);
}

}  // namespace raps_samples
