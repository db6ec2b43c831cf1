#include "gltf_load.h"

#include "gltf_document.h"
#include "gltf_error.h"
#include "gltf_safety.h"

namespace raps_gltf {

namespace {

constexpr uint64_t kMaxBufferBytes = uint64_t(1) << 40;

// Every buffer's bytes, checked against its byteLength: a data uri (either encoding), a file
// inside the asset's folder, a GLB's BIN chunk (buffer 0 without a uri), or none (a
// placeholder). Data may run past byteLength (padding): only byteLength bytes are kept.
void load_buffers(Asset& asset, const std::vector<uint8_t>& file, const GlbParts* glb) {
    const Json& buffers = array_of(asset.doc, "buffers");
    for (size_t i = 0; i < buffers.size(); ++i) {
        const Json& b = buffers[i];
        const std::string what = "buffer " + std::to_string(i);
        const uint64_t length = get_uint(b, "byteLength", what, true, 0, 1, kMaxBufferBytes);
        std::vector<uint8_t> bytes;
        bool has_data = true;
        if (!member(b, "uri")) {
            if (glb && i == 0) {
                if (!glb->has_bin) throw GltfError("buffer", what + ": the GLB has no BIN chunk");
                if (length > glb->bin_size) {
                    throw GltfError("buffer", what + ": byteLength " + std::to_string(length) +
                                                  " is more than the BIN chunk's " +
                                                  std::to_string(glb->bin_size) + " bytes");
                }
                bytes.assign(file.begin() + glb->bin_offset,
                             file.begin() + glb->bin_offset + length);
            } else {
                has_data = false;
            }
        } else {
            const std::string uri = get_string(b, "uri", what);
            if (is_data_uri(uri)) {
                bytes = decode_data_uri(uri, what).bytes;
            } else {
                const std::string path = resolve_inside(asset.folder, uri, what);
                if (path.empty()) {
                    throw GltfError("io", what + ": '" + uri + "' not found in the asset's folder");
                }
                bytes = read_file(path, kMaxFileBytes);
            }
            // The specification asks for at least byteLength bytes (the validator's
            // BUFFER_BYTE_LENGTH_MISMATCH is "less than"): exporters pad .bin files to 4 bytes.
            if (bytes.size() < length) {
                throw GltfError("buffer", what + ": byteLength " + std::to_string(length) +
                                              " but its data has only " +
                                              std::to_string(bytes.size()) + " bytes");
            }
            if (bytes.size() > length) {
                asset.warnings.push_back(what + ": its data has " + std::to_string(bytes.size()) +
                                         " bytes, past its byteLength " + std::to_string(length) +
                                         ": the rest is ignored");
                bytes.resize(length);
            }
        }
        if (!has_data) {
            asset.warnings.push_back(what +
                                     " has no uri and no BIN chunk: a placeholder without data; "
                                     "primitives that read it are left as they are");
        }
        asset.buffers.push_back(std::move(bytes));
        asset.buffer_has_data.push_back(has_data);
    }
}

// Images are never decoded; a uri must still name something the output can carry along.
void check_image_uris(const Asset& asset) {
    const Json& images = array_of(asset.doc, "images");
    for (size_t i = 0; i < images.size(); ++i) {
        if (!member(images[i], "uri")) continue;
        const std::string what = "image " + std::to_string(i);
        const std::string uri = get_string(images[i], "uri", what);
        if (is_data_uri(uri)) {
            decode_data_uri(uri, what);
        } else if (resolve_inside(asset.folder, uri, what).empty()) {
            throw GltfError("io", what + ": '" + uri + "' not found in the asset's folder");
        }
    }
}

std::vector<uint64_t> buffer_sizes(const Asset& asset) {
    std::vector<uint64_t> sizes;
    for (const Json& b : array_of(asset.doc, "buffers"))
        sizes.push_back(b["byteLength"].get<uint64_t>());
    return sizes;
}

}  // namespace

Asset load_asset(const std::string& path) {
    Asset asset;
    asset.path = path;
    const std::vector<uint8_t> bytes = read_file(path, kMaxFileBytes);
    asset.folder = real_folder_of(path);
    asset.binary = looks_like_glb(bytes);
    GlbParts glb;
    const char* text = reinterpret_cast<const char*>(bytes.data());
    size_t text_size = bytes.size();
    if (asset.binary) {
        glb = split_glb(bytes);
        text += glb.json_offset;
        text_size = glb.json_size;
        if (glb.trailing) {
            asset.warnings.push_back(std::to_string(glb.trailing) +
                                     " bytes after the GLB's declared length, ignored");
        }
    }
    check_json_depth(text, text_size, kMaxJsonDepth);
    check_utf8(text, text_size);
    try {
        asset.doc = Json::parse(text, text + text_size);
    } catch (const nlohmann::json::exception& e) {
        throw GltfError("json", std::string("invalid JSON: ") + e.what());
    }
    check_header(asset.doc);
    normalize_integers(asset.doc);
    load_buffers(asset, bytes, asset.binary ? &glb : nullptr);
    check_document(asset.doc, buffer_sizes(asset));
    const std::string dropped = drop_draco_fallback_copies(asset.doc);
    if (!dropped.empty()) asset.warnings.push_back(dropped);
    check_image_uris(asset);
    return asset;
}

}  // namespace raps_gltf
