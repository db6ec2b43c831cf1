#include "gltf_safety.h"

#include <sys/stat.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>

#include "gltf_error.h"

namespace raps_gltf {

namespace {

uint32_t read_u32(const std::vector<uint8_t>& b, size_t at) {
    return uint32_t(b[at]) | (uint32_t(b[at + 1]) << 8) | (uint32_t(b[at + 2]) << 16) |
           (uint32_t(b[at + 3]) << 24);
}

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

std::string real_path(const std::string& path) {
    std::unique_ptr<char, decltype(&std::free)> resolved(realpath(path.c_str(), nullptr),
                                                         &std::free);
    return resolved ? std::string(resolved.get()) : std::string();
}

bool inside(const std::string& folder, const std::string& real) {
    if (real.empty()) return false;
    const std::string prefix = folder == "/" ? folder : folder + "/";
    return real.size() > prefix.size() && real.compare(0, prefix.size(), prefix) == 0;
}

bool is_regular_file(const std::string& path) {
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

int base64_value(unsigned char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

// RFC 2045 token characters, for the media type and its parameters.
bool is_token(const std::string& s) {
    if (s.empty()) return false;
    for (unsigned char c : s) {
        if (c <= 0x20 || c >= 0x7f || std::strchr("()<>@,;:\\\"/[]?=", c)) return false;
    }
    return true;
}

}  // namespace

bool looks_like_glb(const std::vector<uint8_t>& bytes) {
    return bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic;
}

GlbParts split_glb(const std::vector<uint8_t>& bytes) {
    auto fail = [](const std::string& what) { throw GltfError("glb", "invalid GLB: " + what); };
    if (bytes.size() < 12) fail("the file is shorter than the 12-byte header");
    if (read_u32(bytes, 0) != kGlbMagic) fail("no 'glTF' magic");
    if (read_u32(bytes, 4) != 2)
        fail("container version " + std::to_string(read_u32(bytes, 4)) + " (only 2 is glTF 2.0)");
    // Bytes after the declared length are not part of the GLB (the validator ignores them too).
    const uint64_t declared = read_u32(bytes, 8);
    if (declared > bytes.size()) {
        fail("the header declares " + std::to_string(declared) + " bytes but the file has " +
             std::to_string(bytes.size()) + " (truncated)");
    }
    GlbParts parts;
    parts.trailing = bytes.size() - declared;
    const size_t size = declared;
    size_t at = 12;
    int index = 0;
    while (at < size) {
        if (size - at < 8) fail("chunk " + std::to_string(index) + " header is cut off");
        const uint64_t length = read_u32(bytes, at);
        const uint32_t type = read_u32(bytes, at + 4);
        at += 8;
        if (length > size - at) {
            fail("chunk " + std::to_string(index) + " declares " + std::to_string(length) +
                 " bytes but only " + std::to_string(size - at) +
                 " remain in the GLB (chunk length too big or data truncated)");
        }
        if (index == 0) {
            if (type != kChunkJson) fail("the first chunk is not JSON");
            if (length == 0) fail("the JSON chunk is empty");
            parts.json_offset = at;
            parts.json_size = length;
        } else if (type == kChunkJson) {
            fail("a second JSON chunk");
        } else if (type == kChunkBin) {
            if (index != 1) fail("the BIN chunk is not the second chunk");
            parts.has_bin = true;
            parts.bin_offset = at;
            parts.bin_size = length;
        }  // other chunk types are skipped, as the GLB specification asks
        at += length;
        ++index;
    }
    if (index == 0) fail("no JSON chunk");
    return parts;
}

void check_utf8(const char* text, size_t size) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(text);
    // The offset and value of the first byte of the ill-formed sequence: a Latin-1 letter, not
    // the quote after it.
    auto refuse = [&](size_t at) {
        char hex[8];
        std::snprintf(hex, sizeof(hex), "0x%02X", bytes[at]);
        throw GltfError("json", "the JSON is not UTF-8 (glTF requires it): byte " +
                                    std::to_string(at) + " (" + hex +
                                    ") does not start a well-formed UTF-8 character");
    };
    for (size_t i = 0; i < size;) {
        const unsigned char b = bytes[i];
        // The sequence's length and its second byte's range (RFC 3629: no overlong forms, no
        // surrogates, nothing above U+10FFFF).
        size_t length = 1;
        unsigned char low = 0x80, high = 0xBF;
        if (b < 0x80) {
            ++i;
            continue;
        } else if (b >= 0xC2 && b <= 0xDF) {
            length = 2;
        } else if (b >= 0xE0 && b <= 0xEF) {
            length = 3;
            if (b == 0xE0) low = 0xA0;
            if (b == 0xED) high = 0x9F;
        } else if (b >= 0xF0 && b <= 0xF4) {
            length = 4;
            if (b == 0xF0) low = 0x90;
            if (b == 0xF4) high = 0x8F;
        } else {
            refuse(i);
        }
        for (size_t k = 1; k < length; ++k) {
            if (i + k >= size) refuse(i);
            const unsigned char next = bytes[i + k];
            if (k == 1 ? (next < low || next > high) : (next < 0x80 || next > 0xBF)) refuse(i);
        }
        i += length;
    }
}

void check_json_depth(const char* text, size_t size, int max_depth) {
    int depth = 0;
    bool in_string = false;
    for (size_t i = 0; i < size; ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') {
                ++i;  // the escaped character cannot end the string
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth) {
                throw GltfError("json", "JSON nests deeper than " + std::to_string(max_depth) +
                                            " levels (at byte " + std::to_string(i) +
                                            "); refused before parsing");
            }
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

std::vector<uint8_t> read_file(const std::string& path, uint64_t max_bytes) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) throw GltfError("io", "cannot open " + path);
    if (!S_ISREG(st.st_mode)) throw GltfError("io", path + " is not a regular file");
    if (static_cast<uint64_t>(st.st_size) > max_bytes) {
        throw GltfError("io", path + " is larger than " + std::to_string(max_bytes) + " bytes");
    }
    std::unique_ptr<FILE, decltype(&std::fclose)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
    if (!file) throw GltfError("io", "cannot open " + path);
    std::vector<uint8_t> bytes(static_cast<size_t>(st.st_size));
    if (!bytes.empty() && std::fread(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) {
        throw GltfError("io", "cannot read " + path);
    }
    return bytes;
}

std::string real_folder_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash + 1);
    const std::string real = real_path(folder);
    if (real.empty()) throw GltfError("io", "cannot resolve the folder of " + path);
    return real;
}

bool is_data_uri(const std::string& uri) {
    return uri.compare(0, 5, "data:") == 0;
}

namespace {

// The media type and its ;name=value parameters (RFC 2397), all RFC 2045 tokens.
std::string data_uri_media_type(const std::string& media,
                                const std::function<void(const std::string&)>& fail) {
    if (media.empty()) return "";
    std::string mime;
    size_t start = 0;
    bool first = true;
    while (true) {
        const size_t end = media.find(';', start);
        const std::string part =
            media.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (first) {
            const size_t slash = part.find('/');
            if (slash == std::string::npos || !is_token(part.substr(0, slash)) ||
                !is_token(part.substr(slash + 1))) {
                fail("media type '" + part + "'");
            }
            mime = part;
            first = false;
        } else {
            const size_t eq = part.find('=');
            if (eq == std::string::npos || !is_token(part.substr(0, eq)) || part.size() == eq + 1) {
                fail("parameter '" + part + "'");
            }
        }
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return mime;
}

std::vector<uint8_t> decode_base64(const std::string& text, size_t begin,
                                   const std::function<void(const std::string&)>& fail) {
    size_t length = text.size() - begin;
    size_t padding = 0;
    while (length > 0 && padding < 2 && text[begin + length - 1] == '=') {
        --length;
        ++padding;
    }
    if (length % 4 == 1 || (padding > 0 && (length + padding) % 4 != 0)) fail("base64 length");
    std::vector<uint8_t> bytes;
    bytes.reserve(length / 4 * 3 + 2);
    uint32_t accumulator = 0;
    int bits = 0;
    for (size_t i = 0; i < length; ++i) {
        const int value = base64_value(static_cast<unsigned char>(text[begin + i]));
        if (value < 0) fail("'" + std::string(1, text[begin + i]) + "' is not base64");
        accumulator = (accumulator << 6) | uint32_t(value);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            bytes.push_back(static_cast<uint8_t>(accumulator >> bits));
            accumulator &= (1u << bits) - 1;
        }
    }
    return bytes;
}

// RFC 2397 without ;base64: the data are the uri's characters, %XX escapes decoded.
std::vector<uint8_t> decode_percent(const std::string& text, size_t begin,
                                    const std::function<void(const std::string&)>& fail) {
    std::vector<uint8_t> bytes;
    bytes.reserve(text.size() - begin);
    for (size_t i = begin; i < text.size(); ++i) {
        if (text[i] != '%') {
            bytes.push_back(static_cast<uint8_t>(text[i]));
            continue;
        }
        const int hi = i + 2 < text.size() ? hex_value(text[i + 1]) : -1;
        const int lo = i + 2 < text.size() ? hex_value(text[i + 2]) : -1;
        if (hi < 0 || lo < 0) fail("bad percent-encoding");
        bytes.push_back(static_cast<uint8_t>(hi * 16 + lo));
        i += 2;
    }
    return bytes;
}

}  // namespace

DataUri decode_data_uri(const std::string& uri, const std::string& what) {
    const std::function<void(const std::string&)> fail = [&](const std::string& why) {
        throw GltfError("uri", what + ": malformed data uri (" + why + ")");
    };
    const size_t comma = uri.find(',');
    if (comma == std::string::npos) fail("no ','");
    const std::string header = uri.substr(5, comma - 5);
    const std::string marker = ";base64";
    const bool base64 = header.size() >= marker.size() &&
                        header.compare(header.size() - marker.size(), marker.size(), marker) == 0;
    DataUri out;
    out.mime = data_uri_media_type(
        base64 ? header.substr(0, header.size() - marker.size()) : header, fail);
    out.bytes = base64 ? decode_base64(uri, comma + 1, fail) : decode_percent(uri, comma + 1, fail);
    return out;
}

std::string resolve_inside(const std::string& folder, const std::string& uri,
                           const std::string& what) {
    auto refuse = [&](const std::string& why) {
        throw GltfError("uri", what + ": uri '" + uri + "' refused: " + why);
    };
    if (uri.empty()) refuse("empty");
    // A scheme is letters, digits, + - . before the first ':' that comes before any '/'.
    const size_t colon = uri.find(':');
    if (colon != std::string::npos && colon < uri.find('/')) {
        refuse("only relative paths inside the asset's folder are read (no scheme)");
    }
    std::string decoded;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%') {
            const int hi = i + 2 < uri.size() ? hex_value(uri[i + 1]) : -1;
            const int lo = i + 2 < uri.size() ? hex_value(uri[i + 2]) : -1;
            if (hi < 0 || lo < 0) refuse("bad percent-encoding");
            decoded += static_cast<char>(hi * 16 + lo);
            i += 2;
        } else {
            decoded += uri[i];
        }
    }
    if (decoded.find('\0') != std::string::npos) refuse("NUL byte");
    if (decoded.find('\\') != std::string::npos) refuse("backslash");
    if (decoded[0] == '/') refuse("absolute path");
    size_t start = 0;
    while (start <= decoded.size()) {
        const size_t end = std::min(decoded.find('/', start), decoded.size());
        if (decoded.compare(start, end - start, "..") == 0 && end - start == 2) {
            refuse("'..' leaves the asset's folder");
        }
        start = end + 1;
    }
    const std::string joined = folder + "/" + decoded;
    struct stat st;
    if (lstat(joined.c_str(), &st) != 0) return "";
    const std::string real = real_path(joined);
    if (real == folder) refuse("it names the asset's folder itself, not a file");
    if (!inside(folder, real)) refuse("it resolves (through a link) outside the asset's folder");
    if (!is_regular_file(real)) refuse("not a regular file");
    return real;
}

}  // namespace raps_gltf
