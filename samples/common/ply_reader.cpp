// PLY (Greg Turk's polygon file format, as the Stanford scans use it): ASCII and both binary
// byte orders. Only the vertex element's x, y, z and the face element's index list
// (vertex_indices or vertex_index) are kept; every other element and property is read past.
// Counts and list lengths come from the file, so each is checked against the bytes left
// before anything is reserved.
#include "ply_reader.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace raps_samples {
namespace {

enum class Format { kAscii, kLittle, kBig };

struct Property {
    std::string name;
    int type = 0;           // byte size of the value, negative for signed, 0 never
    bool floating = false;  // float or double
    bool list = false;
    int count_type = 0;  // for a list: the byte size (and sign) of its length
    bool count_floating = false;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error(path + ": " + what);
}

// A PLY scalar type: its byte size, signed as a negative size.
bool scalar_type(std::string_view name, int* type, bool* floating) {
    static const struct {
        const char* names[2];
        int type;
        bool floating;
    } kTypes[] = {{{"char", "int8"}, -1, false},   {{"uchar", "uint8"}, 1, false},
                  {{"short", "int16"}, -2, false}, {{"ushort", "uint16"}, 2, false},
                  {{"int", "int32"}, -4, false},   {{"uint", "uint32"}, 4, false},
                  {{"float", "float32"}, 4, true}, {{"double", "float64"}, 8, true}};
    for (const auto& t : kTypes) {
        if (name == t.names[0] || name == t.names[1]) {
            *type = t.type;
            *floating = t.floating;
            return true;
        }
    }
    return false;
}

std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    size_t at = 0;
    while (at < line.size()) {
        while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r')) ++at;
        const size_t start = at;
        while (at < line.size() && line[at] != ' ' && line[at] != '\t' && line[at] != '\r') ++at;
        if (at > start) out.push_back(line.substr(start, at - start));
    }
    return out;
}

// The header: format and elements; `body` is set to the first byte after end_header.
Format read_header(const std::string& path, const std::string& text, std::vector<Element>* elements,
                   size_t* body) {
    Format format = Format::kAscii;
    bool have_format = false;
    size_t at = 0;
    for (size_t line_number = 1;; ++line_number) {
        const size_t end = text.find('\n', at);
        if (end == std::string::npos) fail(path, "the header has no end_header line");
        const std::vector<std::string_view> w = words(std::string_view(text).substr(at, end - at));
        at = end + 1;
        const std::string where = "header line " + std::to_string(line_number) + ": ";
        if (line_number == 1) {
            if (w.size() != 1 || w[0] != "ply") fail(path, "does not start with 'ply'");
            continue;
        }
        if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "end_header") break;
        if (w[0] == "format" && w.size() == 3) {
            have_format = true;
            if (w[1] == "ascii")
                format = Format::kAscii;
            else if (w[1] == "binary_little_endian")
                format = Format::kLittle;
            else if (w[1] == "binary_big_endian")
                format = Format::kBig;
            else
                fail(path, where + "unknown format '" + std::string(w[1]) + "'");
        } else if (w[0] == "element" && w.size() == 3) {
            Element e;
            e.name = std::string(w[1]);
            const auto r = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
            if (r.ec != std::errc() || r.ptr != w[2].data() + w[2].size())
                fail(path, where + "element count '" + std::string(w[2]) + "'");
            elements->push_back(e);
        } else if (w[0] == "property" && !elements->empty()) {
            Property p;
            const bool ok = w.size() == 3 ? scalar_type(w[1], &p.type, &p.floating)
                            : w.size() == 5 && w[1] == "list"
                                ? scalar_type(w[2], &p.count_type, &p.count_floating) &&
                                      scalar_type(w[3], &p.type, &p.floating) && !p.count_floating
                                : false;
            if (!ok) fail(path, where + "cannot read this property");
            p.list = w.size() == 5;
            p.name = std::string(w.back());
            elements->back().properties.push_back(p);
        } else {
            fail(path, where + "cannot read it");
        }
    }
    if (!have_format) fail(path, "the header names no format");
    *body = at;
    return format;
}

// The values of the body, one at a time, in the file's format.
struct Values {
    const std::string& path;
    const std::string& text;
    Format format;
    size_t at;

    size_t left() const { return text.size() - at; }

    double next(int type, bool floating) {
        if (format == Format::kAscii) return next_word();
        const size_t size = static_cast<size_t>(type < 0 ? -type : type);
        if (left() < size) fail(path, "the file ends inside its data");
        unsigned char b[8];
        std::memcpy(b, text.data() + at, size);
        at += size;
        if (format == Format::kBig) {
            for (size_t i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
        }
        if (floating) {
            if (size == 4) {
                float f;
                std::memcpy(&f, b, 4);
                return f;
            }
            double d;
            std::memcpy(&d, b, 8);
            return d;
        }
        uint64_t u = 0;
        for (size_t i = size; i-- > 0;) u = (u << 8) | b[i];  // little-endian after the swap
        if (type < 0 && (u >> (8 * size - 1)))
            return static_cast<double>(u) - std::ldexp(1.0, 8 * size);
        return static_cast<double>(u);
    }

    double next_word() {
        while (at < text.size() && std::strchr(" \t\r\n", text[at])) ++at;
        const size_t start = at;
        while (at < text.size() && !std::strchr(" \t\r\n", text[at])) ++at;
        if (at == start) fail(path, "the file ends inside its data");
        double value = 0;
        const char* first = text.data() + start + (text[start] == '+');
        const auto r = std::from_chars(first, text.data() + at, value);
        if (r.ec != std::errc() || r.ptr != text.data() + at)
            fail(path, "cannot read number '" + text.substr(start, at - start) + "'");
        return value;
    }
};

// A list's length or an index: a whole number in [0, limit].
uint64_t whole(double value, double limit, const std::string& path, const std::string& what) {
    if (!(value >= 0 && value <= limit) ||
        value != static_cast<double>(static_cast<uint64_t>(value)))
        fail(path, what);
    return static_cast<uint64_t>(value);
}

void read_element(Values& v, const Element& e, PolygonMesh& mesh) {
    const bool vertex = e.name == "vertex", face = e.name == "face";
    // The fewest bytes an item can take: its scalars and list lengths in binary, a digit and a
    // separator each in ASCII. A count the file cannot hold is refused before any reserve.
    uint64_t least = 0;
    for (const Property& p : e.properties) {
        const int type = p.list ? p.count_type : p.type;
        least += v.format == Format::kAscii ? 2 : static_cast<uint64_t>(type < 0 ? -type : type);
    }
    if (least > 0 && e.count > v.left() / least) {
        fail(v.path, "element '" + e.name + "' count " + std::to_string(e.count) +
                         " is more than the file holds");
    }
    if (vertex) mesh.positions.reserve(3 * e.count);
    for (uint64_t i = 0; i < e.count; ++i) {
        double xyz[3] = {0, 0, 0};
        for (const Property& p : e.properties) {
            if (!p.list) {
                const double value = v.next(p.type, p.floating);
                for (int c = 0; c < 3; ++c) {
                    if (vertex && p.name == std::string(1, char('x' + c))) xyz[c] = value;
                }
                continue;
            }
            const uint64_t n = whole(v.next(p.count_type, false), double(v.left()), v.path,
                                     "element '" + e.name + "' " + std::to_string(i) +
                                         ": list length past the end of the file");
            const bool corners = face && (p.name == "vertex_indices" || p.name == "vertex_index");
            if (corners && n < 3) {
                fail(v.path, "face " + std::to_string(i) + " has fewer than 3 vertices");
            }
            for (uint64_t k = 0; k < n; ++k) {
                const double value = v.next(p.type, p.floating);
                if (corners) {
                    mesh.corners.push_back(static_cast<uint32_t>(
                        whole(value, 4294967295.0, v.path,
                              "face " + std::to_string(i) + ": invalid vertex index")));
                }
            }
            if (corners) mesh.polygon_offsets.push_back(static_cast<uint32_t>(mesh.corners.size()));
        }
        if (vertex) mesh.positions.insert(mesh.positions.end(), xyz, xyz + 3);
    }
}

}  // namespace

PolygonMesh read_ply(const std::string& path, const std::string& text) {
    std::vector<Element> elements;
    size_t body = 0;
    const Format format = read_header(path, text, &elements, &body);
    bool has_xyz = false, has_faces = false;
    for (const Element& e : elements) {
        for (const Property& p : e.properties) {
            has_xyz |= e.name == "vertex" && p.name == "z" && !p.list;
            has_faces |= e.name == "face" && p.list &&
                         (p.name == "vertex_indices" || p.name == "vertex_index");
        }
    }
    if (!has_xyz) fail(path, "no vertex element with x, y, z");
    if (!has_faces) fail(path, "no face element with vertex_indices (a point cloud?)");
    PolygonMesh mesh;
    mesh.polygon_offsets.push_back(0);
    Values values{path, text, format, body};
    for (const Element& e : elements) read_element(values, e, mesh);
    return mesh;
}

}  // namespace raps_samples
