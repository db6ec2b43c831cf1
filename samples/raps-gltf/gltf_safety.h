// Checks that run before a glTF document is parsed or any of its data read: glTF files are
// untrusted (uris that leave the asset's folder, lengths past the file, JSON nested without
// bound). Everything here refuses with a GltfError naming the problem; nothing here opens a file
// outside the asset's folder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace raps_gltf {

// Files larger than this are refused before they are read (GLB lengths are 32-bit anyway).
constexpr uint64_t kMaxFileBytes = uint64_t(2) << 30;
// JSON nesting deeper than this is refused before parsing; real glTF documents stay near 10.
constexpr int kMaxJsonDepth = 100;

// The parts of a GLB container, checked against the GLB 2.0 layout: 12-byte header with magic,
// version 2 and a length no larger than the file (bytes past it are not the GLB's: counted in
// `trailing`); a JSON chunk first; an optional BIN chunk second; every chunk inside the declared
// length. Offsets are into the file's bytes.
struct GlbParts {
    size_t json_offset = 0, json_size = 0, trailing = 0;
    bool has_bin = false;
    size_t bin_offset = 0, bin_size = 0;
};
bool looks_like_glb(const std::vector<uint8_t>& bytes);
GlbParts split_glb(const std::vector<uint8_t>& bytes);

// Refuses JSON text whose arrays and objects nest deeper than max_depth (strings are skipped,
// escapes included), so no recursive parser or serializer downstream can run out of stack.
void check_json_depth(const char* text, size_t size, int max_depth);

// Refuses JSON text that is not UTF-8 (glTF requires it), naming the first bad byte's offset:
// a Latin-1 name would otherwise be read and then fail only when the output is written.
void check_utf8(const char* text, size_t size);

// Reads a whole regular file of at most max_bytes. Throws GltfError("io", ...).
std::vector<uint8_t> read_file(const std::string& path, uint64_t max_bytes);

// The absolute, symlink-resolved folder of a file.
std::string real_folder_of(const std::string& path);

// A data: uri, checked strictly: RFC 2397's media type and parameters, then either ;base64 (RFC
// 4648 alphabet and padding) or the percent-encoded octets themselves.
bool is_data_uri(const std::string& uri);
struct DataUri {
    std::string mime;  // "" when the uri names none
    std::vector<uint8_t> bytes;
};
DataUri decode_data_uri(const std::string& uri, const std::string& what);

// Resolves a relative uri reference (percent-decoded) against the asset's real folder. Refuses
// schemes (http:, file:, ...), absolute paths, drive letters, backslashes, `..` segments, NUL
// bytes and anything whose real path (symlinks resolved) lies outside the folder; nothing is
// opened. `what` names the referring object in messages ("buffer 0"). Returns the real path, or
// "" when the file does not exist inside the folder (the caller decides whether that is an error).
std::string resolve_inside(const std::string& folder, const std::string& uri,
                           const std::string& what);

}  // namespace raps_gltf
