#include "gltf_output.h"

#include "output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <set>

#include "gltf_accessors.h"
#include "gltf_document.h"
#include "gltf_error.h"
#include "gltf_safety.h"

namespace raps_gltf {

namespace {

constexpr uint64_t kAlignment = 16;

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                      [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

std::string folder_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : path.substr(0, slash == 0 ? 1 : slash);
}

std::string base_name(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string real_or_empty(const std::string& path) {
    std::unique_ptr<char, decltype(&std::free)> real(realpath(path.c_str(), nullptr), &std::free);
    return real ? std::string(real.get()) : std::string();
}

// The absolute path a file will have: an existing one's, through its links (a .gltf's buffer
// file then goes beside the file a link names), else its folder's (it may not exist yet).
std::string absolute_target(const std::string& path) {
    if (const std::string real = real_or_empty(path); !real.empty()) return real;
    std::unique_ptr<char, decltype(&std::free)> folder(realpath(folder_of(path).c_str(), nullptr),
                                                       &std::free);
    if (!folder) throw GltfError("io", "the output folder of " + path + " does not exist");
    return std::string(folder.get()) + "/" + base_name(path);
}

// Files are staged as temporaries, then renamed in order; the destructor removes temporaries
// that were never renamed (a failure part-way leaves no partial file behind).
class StagedFiles {
  public:
    ~StagedFiles() {
        for (const auto& f : files_) {
            if (!f.second.empty()) unlink(f.second.c_str());
        }
    }
    void stage(const std::string& given, const uint8_t* data, size_t size) {
        raps_samples::OutputFile target;
        try {
            target = raps_samples::output_file(given);
        } catch (const std::runtime_error& e) {
            throw GltfError("io", e.what());
        }
        const std::string& path = target.path;
        if (target.direct) {  // a device or a pipe: written into at commit
            direct_.emplace_back(path, std::vector<uint8_t>(data, data + size));
            return;
        }
        std::string temp = path + ".tmp-XXXXXX";
        std::vector<char> name(temp.begin(), temp.end());
        name.push_back('\0');
        const int fd = mkstemp(name.data());
        if (fd < 0) throw GltfError("io", "cannot create a temporary file beside " + path);
        temp = name.data();
        files_.emplace_back(path, temp);
        size_t done = 0;
        while (done < size) {
            const ssize_t n = ::write(fd, data + done, size - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                close(fd);
                throw GltfError("io", "cannot write " + path + ": " + std::strerror(errno));
            }
            done += static_cast<size_t>(n);
        }
        fchmod(fd, 0644);
        if (fsync(fd) != 0 || close(fd) != 0) throw GltfError("io", "cannot write " + path);
    }
    void commit() {
        for (auto& f : files_) {
            if (std::rename(f.second.c_str(), f.first.c_str()) != 0) {
                throw GltfError("io",
                                "cannot rename into " + f.first + ": " + std::strerror(errno));
            }
            f.second.clear();
        }
        for (const auto& f : direct_) {
            try {
                raps_samples::write_into(f.first, f.second.data(), f.second.size());
            } catch (const std::runtime_error& e) {
                throw GltfError("io", e.what());
            }
        }
    }

  private:
    std::vector<std::pair<std::string, std::string>> files_;            // (final path, temporary)
    std::vector<std::pair<std::string, std::vector<uint8_t>>> direct_;  // (device, bytes)
};

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t n = (uint32_t(bytes[i]) << 16) |
                           (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                           (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
        out += kAlphabet[(n >> 18) & 63];
        out += kAlphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
    }
    return out;
}

std::string sniff_mime(const std::vector<uint8_t>& b, const std::string& uri) {
    if (b.size() >= 8 && std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return "image/png";
    if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "image/jpeg";
    if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 &&
        std::memcmp(b.data() + 8, "WEBP", 4) == 0) {
        return "image/webp";
    }
    if (b.size() >= 12 && std::memcmp(b.data(), "\xABKTX 20\xBB\r\n\x1A\n", 12) == 0) {
        return "image/ktx2";
    }
    if (ends_with(uri, ".png")) return "image/png";
    if (ends_with(uri, ".jpg") || ends_with(uri, ".jpeg")) return "image/jpeg";
    return "";
}

// Every accessor index the document refers to, where glTF 2.0 (and EXT_mesh_gpu_instancing)
// puts one. `visit` may rewrite the index in place.
template <typename Visit>
void for_each_accessor_ref(Json& doc, Visit visit) {
    auto each_index_in = [&](Json& object) {
        if (!object.is_object()) return;
        for (auto it = object.begin(); it != object.end(); ++it) {
            if (it.value().is_number_integer()) visit(it.value());
        }
    };
    if (doc.contains("meshes")) {
        for (Json& mesh : doc["meshes"]) {
            for (Json& prim : mesh["primitives"]) {
                each_index_in(prim["attributes"]);
                if (prim.contains("indices")) visit(prim["indices"]);
                if (prim.contains("targets")) {
                    for (Json& target : prim["targets"]) each_index_in(target);
                }
            }
        }
    }
    if (doc.contains("animations") && doc["animations"].is_array()) {
        for (Json& animation : doc["animations"]) {
            if (!animation.contains("samplers")) continue;
            for (Json& sampler : animation["samplers"]) {
                if (sampler.contains("input")) visit(sampler["input"]);
                if (sampler.contains("output")) visit(sampler["output"]);
            }
        }
    }
    if (doc.contains("skins") && doc["skins"].is_array()) {
        for (Json& skin : doc["skins"]) {
            if (skin.contains("inverseBindMatrices")) visit(skin["inverseBindMatrices"]);
        }
    }
    if (doc.contains("nodes") && doc["nodes"].is_array()) {
        for (Json& node : doc["nodes"]) {
            if (!node.contains("extensions")) continue;
            Json& ext = node["extensions"];
            if (ext.contains("EXT_mesh_gpu_instancing") &&
                ext["EXT_mesh_gpu_instancing"].contains("attributes")) {
                each_index_in(ext["EXT_mesh_gpu_instancing"]["attributes"]);
            }
        }
    }
}

template <typename Visit>
void for_each_view_ref(Json& doc, Visit visit) {
    if (doc.contains("accessors")) {
        for (Json& a : doc["accessors"]) {
            if (a.contains("bufferView")) visit(a["bufferView"]);
            if (a.contains("sparse")) {
                visit(a["sparse"]["indices"]["bufferView"]);
                visit(a["sparse"]["values"]["bufferView"]);
            }
        }
    }
    if (doc.contains("images")) {
        for (Json& image : doc["images"]) {
            if (image.contains("bufferView")) visit(image["bufferView"]);
        }
    }
}

std::set<uint64_t> accessor_refs(const Json& doc) {
    std::set<uint64_t> refs;
    Json copy = doc;
    for_each_accessor_ref(copy, [&](Json& v) { refs.insert(v.get<uint64_t>()); });
    return refs;
}

std::set<uint64_t> view_refs(const Json& doc) {
    std::set<uint64_t> refs;
    Json copy = doc;
    for_each_view_ref(copy, [&](Json& v) { refs.insert(v.get<uint64_t>()); });
    return refs;
}

// Removes the array entries in `remove` and renumbers the references that `for_each` visits.
template <typename ForEach>
void remove_entries(Json& doc, const char* array, const std::set<uint64_t>& remove,
                    ForEach for_each) {
    if (remove.empty()) return;
    std::vector<int64_t> new_index(doc[array].size(), -1);
    Json kept = Json::array();
    for (size_t i = 0; i < doc[array].size(); ++i) {
        if (remove.count(i)) continue;
        new_index[i] = static_cast<int64_t>(kept.size());
        kept.push_back(doc[array][i]);
    }
    doc[array] = kept;
    for_each(doc, [&](Json& v) { v = new_index.at(v.get<uint64_t>()); });
}

// A .gltf output's buffer file is named after its content, OUT.<16 hex digits>.bin. The .gltf
// and its .bin are two files renamed one after the other; with a fixed name, a process killed
// between the two renames would leave the old .gltf reading a new buffer of another layout.
// Named by content, the old .gltf keeps its own .bin until the new .gltf has replaced it, and
// that old .bin is removed only then.
std::string content_addressed_bin(const std::string& stem, const std::vector<uint8_t>& bytes) {
    uint64_t hash = 0xcbf29ce484222325ull;  // FNV-1a, 64 bits
    for (uint8_t b : bytes) {
        hash ^= b;
        hash *= 0x100000001b3ull;
    }
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash));
    return stem + "." + hex + ".bin";
}

// The buffer file that an earlier output at `main_path` names, when it is one this tool wrote
// (stem.<16 hex digits>.bin); empty otherwise. A plain search of the old file's text: it may be
// anything, and it is not parsed.
std::string earlier_bin(const std::string& main_path, const std::string& stem) {
    struct stat info;
    if (stat(main_path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return {};
    std::vector<uint8_t> bytes;
    try {
        bytes = read_file(main_path, kMaxFileBytes);
    } catch (const GltfError&) {
        return {};
    }
    const std::string text(bytes.begin(), bytes.end());
    const std::string prefix = "\"" + stem + ".";
    for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
        const std::string name = text.substr(at + 1, stem.size() + 1 + 16 + 4);
        const std::string digits = name.substr(stem.size() + 1, 16);
        if (name.size() == stem.size() + 21 && name.compare(name.size() - 4, 4, ".bin") == 0 &&
            digits.find_first_not_of("0123456789abcdef") == std::string::npos &&
            text.compare(at + 1 + name.size(), 1, "\"") == 0) {
            return name;
        }
    }
    return {};
}

// Where a bufferView's bytes come from, by its index in the output document as it is renumbered.
// A view into a placeholder buffer has no bytes: it keeps its offset in that buffer, which the
// output carries along without data.
struct ViewSource {
    const uint8_t* data;
    uint64_t size;
    uint64_t old_offset;
    int64_t placeholder;  // index of the input's placeholder buffer, or -1
};

std::vector<ViewSource> view_sources(const Asset& asset, const BakeResult& bake) {
    std::vector<ViewSource> out;
    const Json& doc = bake.doc;
    for (size_t i = 0; i < doc["bufferViews"].size(); ++i) {
        if (i < bake.first_new_view) {
            const Json& v = asset.doc["bufferViews"][i];
            const uint64_t offset = v.value("byteOffset", uint64_t(0));
            const size_t buffer = v["buffer"].get<size_t>();
            const uint64_t size = v["byteLength"].get<uint64_t>();
            if (!asset.buffer_has_data.at(buffer)) {
                out.push_back({nullptr, size, offset, static_cast<int64_t>(buffer)});
            } else {
                out.push_back({asset.buffers.at(buffer).data() + offset, size, offset, -1});
            }
        } else {
            const auto& data = bake.new_views[i - bake.first_new_view];
            out.push_back({data.data(), data.size(), 0, -1});
        }
    }
    return out;
}

// The first extension the asset uses that might refer to accessors or bufferViews ("" if none).
std::string unknown_extension(const Json& doc) {
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
        if (!doc.contains(list)) continue;
        for (const Json& name : doc[list]) {
            if (!extension_is_known(name.get<std::string>())) return name.get<std::string>();
        }
    }
    return "";
}

// Animation and skin data may not sit in strided bufferViews (validator errors
// ANIMATION_SAMPLER_ / SKIN_IBM_ACCESSOR_WITH_BYTESTRIDE). When the stride equals the element
// size of every accessor in the view, dropping it changes no byte's meaning.
size_t repair_animation_strides(Json& doc) {
    std::set<uint64_t> animation_accessors;
    if (doc.contains("animations")) {
        for (const Json& animation : doc["animations"]) {
            for (const Json& s : animation.value("samplers", Json::array())) {
                for (const char* key : {"input", "output"}) {
                    if (s.contains(key)) animation_accessors.insert(s[key].get<uint64_t>());
                }
            }
        }
    }
    if (doc.contains("skins")) {
        for (const Json& skin : doc["skins"]) {
            if (skin.contains("inverseBindMatrices")) {
                animation_accessors.insert(skin["inverseBindMatrices"].get<uint64_t>());
            }
        }
    }
    std::map<uint64_t, bool> view_repairable;
    for (size_t i = 0; i < doc["accessors"].size(); ++i) {
        const Json& a = doc["accessors"][i];
        // An accessor of a type glTF does not define (kept, unused) has no element size.
        if (!a.contains("bufferView") || !a.contains("type") || !a["type"].is_string()) continue;
        const uint64_t v = a["bufferView"].get<uint64_t>();
        const Json& view = doc["bufferViews"][v];
        if (!view.contains("byteStride")) continue;
        const bool exact =
            animation_accessors.count(i) &&
            element_size(a["type"].get<std::string>(), a["componentType"].get<int>()) ==
                view["byteStride"].get<uint64_t>();
        auto it = view_repairable.emplace(v, true).first;
        it->second = it->second && exact;
    }
    size_t repaired = 0;
    for (const auto& entry : view_repairable) {
        if (!entry.second) continue;
        doc["bufferViews"][entry.first].erase("byteStride");
        ++repaired;
    }
    return repaired;
}

// Removes what the bake left unused: accessors and bufferViews referenced before, referenced no
// more (never one nothing referenced in the input: an unused accessor stays as it was).
void prune_unused(const Json& original, Json& doc, std::vector<ViewSource>& sources,
                  WriteReport& report) {
    const std::set<uint64_t> before = accessor_refs(original), after = accessor_refs(doc);
    std::set<uint64_t> unused_accessors;
    for (uint64_t a : before) {
        if (!after.count(a)) unused_accessors.insert(a);
    }
    remove_entries(doc, "accessors", unused_accessors,
                   [](Json& d, auto visit) { for_each_accessor_ref(d, visit); });
    report.removed_accessors = unused_accessors.size();
    const std::set<uint64_t> views_before = view_refs(original), views_after = view_refs(doc);
    std::set<uint64_t> unused_views;
    for (uint64_t v : views_before) {
        if (!views_after.count(v)) unused_views.insert(v);
    }
    remove_entries(doc, "bufferViews", unused_views,
                   [](Json& d, auto visit) { for_each_view_ref(d, visit); });
    std::vector<ViewSource> kept;
    for (size_t i = 0; i < sources.size(); ++i) {
        if (!unused_views.count(i)) kept.push_back(sources[i]);
    }
    sources.swap(kept);
    report.removed_buffer_views = unused_views.size();
}

std::string percent_decoded(const std::string& uri) {
    std::string plain;
    for (size_t k = 0; k < uri.size(); ++k) {
        if (uri[k] == '%' && k + 2 < uri.size()) {
            plain += static_cast<char>(std::stoi(uri.substr(k + 1, 2), nullptr, 16));
            k += 2;
        } else {
            plain += uri[k];
        }
    }
    return plain;
}

// Images given by uri: into a .glb as bufferViews (their bytes kept in `image_bytes`); beside a
// .gltf as copies, returned as (source, destination) pairs.
std::vector<std::pair<std::string, std::string>> place_images(
    const Asset& asset, Json& doc, bool glb, const std::string& out_folder,
    std::vector<std::vector<uint8_t>>& image_bytes, std::vector<ViewSource>& sources,
    WriteReport& report) {
    std::vector<std::pair<std::string, std::string>> copies;
    if (!doc.contains("images")) return copies;
    for (size_t i = 0; i < doc["images"].size(); ++i) {
        Json& image = doc["images"][i];
        if (!image.contains("uri")) continue;
        const std::string uri = image["uri"].get<std::string>();
        const std::string what = "image " + std::to_string(i);
        if (!glb) {
            // resolve_inside checked the uri; the copy goes under its percent-decoded name.
            if (!is_data_uri(uri)) {
                copies.emplace_back(resolve_inside(asset.folder, uri, what),
                                    out_folder + "/" + percent_decoded(uri));
            }
            continue;
        }
        std::vector<uint8_t> bytes;
        std::string mime;
        if (is_data_uri(uri)) {
            DataUri decoded = decode_data_uri(uri, what);
            bytes = std::move(decoded.bytes);
            mime = decoded.mime;
        } else {
            bytes = read_file(resolve_inside(asset.folder, uri, what), kMaxFileBytes);
            report.embedded_images.push_back(uri);
        }
        if (image.contains("mimeType")) mime = image["mimeType"].get<std::string>();
        if (mime.empty() || mime == "application/octet-stream") mime = sniff_mime(bytes, uri);
        if (mime.empty()) {
            throw GltfError("io", what + ": '" + uri.substr(0, 60) +
                                      "' is no image type a .glb can embed (PNG, JPEG, WebP, "
                                      "KTX2); write a .gltf instead");
        }
        image.erase("uri");
        image["mimeType"] = mime;
        image["bufferView"] = doc["bufferViews"].size();
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteLength", bytes.size()}});
        // A vector moved by image_bytes growing keeps its storage: data() stays valid.
        image_bytes.push_back(std::move(bytes));
        sources.push_back({image_bytes.back().data(), image_bytes.back().size(), 0, -1});
    }
    return copies;
}

// One data buffer, bufferView by bufferView, each keeping its offset modulo 16; views into
// placeholder buffers point at those buffers, which follow it without data. Returns the bytes
// and the output's "buffers" entries after the first (the placeholders).
std::vector<uint8_t> lay_out_buffer(const Asset& asset, Json& doc,
                                    const std::vector<ViewSource>& sources, Json* placeholders) {
    std::vector<uint8_t> buffer;
    std::map<int64_t, size_t> placeholder_index;
    *placeholders = Json::array();
    for (size_t i = 0; i < sources.size(); ++i) {
        const ViewSource& b = sources[i];
        Json& view = doc["bufferViews"][i];
        if (b.placeholder >= 0) {
            auto it = placeholder_index.find(b.placeholder);
            if (it == placeholder_index.end()) {
                it = placeholder_index.emplace(b.placeholder, placeholders->size()).first;
                placeholders->push_back(asset.doc["buffers"][static_cast<size_t>(b.placeholder)]);
            }
            view["buffer"] = 1 + it->second;
            view["byteOffset"] = b.old_offset;
            continue;
        }
        uint64_t at = buffer.size();
        while (at % kAlignment != b.old_offset % kAlignment) ++at;
        buffer.resize(at, 0);
        buffer.insert(buffer.end(), b.data, b.data + b.size);
        view["buffer"] = 0;
        view["byteOffset"] = at;
    }
    return buffer;
}

std::vector<uint8_t> glb_bytes(const Json& doc, std::vector<uint8_t>& buffer) {
    std::vector<uint8_t> main;
    std::string json = doc.dump();
    while (json.size() % 4) json += ' ';
    while (buffer.size() % 4) buffer.push_back(0);
    const uint64_t total = 12 + 8 + json.size() + (buffer.empty() ? 0 : 8 + buffer.size());
    if (total > 0xFFFFFFFFull) throw GltfError("io", "the output is too large for a GLB");
    auto u32 = [&](uint64_t v) {
        for (int k = 0; k < 4; ++k) main.push_back(static_cast<uint8_t>(v >> (8 * k)));
    };
    main.insert(main.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(total);
    u32(json.size());
    u32(0x4E4F534A);
    main.insert(main.end(), json.begin(), json.end());
    if (!buffer.empty()) {
        u32(buffer.size());
        u32(0x004E4942);
        main.insert(main.end(), buffer.begin(), buffer.end());
    }
    return main;
}

// The input's own files, by real path: never written over.
std::set<std::string> input_files(const Asset& asset) {
    std::set<std::string> inputs = {real_or_empty(asset.path)};
    for (const char* array : {"buffers", "images"}) {
        if (!asset.doc.contains(array)) continue;
        for (const Json& item : asset.doc[array]) {
            if (item.contains("uri") && !is_data_uri(item["uri"].get<std::string>())) {
                inputs.insert(resolve_inside(asset.folder, item["uri"].get<std::string>(), array));
            }
        }
    }
    return inputs;
}

}  // namespace

void write_file_atomically(const std::string& path, const std::vector<uint8_t>& bytes) {
    StagedFiles staged;
    staged.stage(path, bytes.data(), bytes.size());
    staged.commit();
}

WriteReport write_output(const Asset& asset, BakeResult& bake, const std::string& path,
                         const WriteOptions& options) {
    WriteReport report;
    const bool glb = ends_with(path, ".glb");
    if (!glb && !ends_with(path, ".gltf")) {
        throw GltfError("io", "the output must end in .glb or .gltf: " + path);
    }
    Json& doc = bake.doc;
    std::vector<ViewSource> sources = view_sources(asset, bake);
    const std::string unknown = unknown_extension(doc);
    report.pruned = unknown.empty();
    if (!report.pruned) {
        report.kept_unused_because = "the asset uses " + unknown +
                                     ", which might refer to accessors or bufferViews by index";
    } else {
        report.repaired_buffer_views = repair_animation_strides(doc);
        prune_unused(asset.doc, doc, sources, report);
    }
    std::vector<std::vector<uint8_t>> image_bytes;
    const std::string main_path = absolute_target(path);
    const std::string out_folder = folder_of(main_path);
    const auto image_copies =
        place_images(asset, doc, glb, out_folder, image_bytes, sources, report);
    Json placeholders;
    std::vector<uint8_t> buffer = lay_out_buffer(asset, doc, sources, &placeholders);
    if (doc.contains("bufferViews") && doc["bufferViews"].empty()) doc.erase("bufferViews");
    Json first_buffer =
        doc.contains("buffers") && !doc["buffers"].empty() ? doc["buffers"][0] : Json::object();
    first_buffer.erase("uri");
    first_buffer["byteLength"] = buffer.size();
    std::string bin_name, replaced_bin;
    if (!glb && !buffer.empty()) {
        if (options.embed) {
            first_buffer["uri"] = "data:application/octet-stream;base64," + base64(buffer);
        } else {
            const std::string stem = base_name(path).substr(0, base_name(path).size() - 5);
            bin_name = content_addressed_bin(stem, buffer);
            replaced_bin = earlier_bin(main_path, stem);
            first_buffer["uri"] = bin_name;
        }
    }
    if (buffer.empty() && placeholders.empty()) {
        doc.erase("buffers");
    } else {
        doc["buffers"] = Json::array({first_buffer});
        for (const Json& p : placeholders) doc["buffers"].push_back(p);
    }

    const std::set<std::string> inputs = input_files(asset);
    auto refuse_input = [&](const std::string& target) {
        const std::string real = real_or_empty(target);
        if (!real.empty() && inputs.count(real)) {
            throw GltfError("io",
                            "refusing to write " + target + ": it is one of the input's files");
        }
    };
    refuse_input(main_path);
    StagedFiles staged;
    if (!bin_name.empty()) {
        refuse_input(out_folder + "/" + bin_name);
        staged.stage(out_folder + "/" + bin_name, buffer.data(), buffer.size());
        report.files.push_back(out_folder + "/" + bin_name);
        report.bytes += buffer.size();
    }
    for (const auto& copy : image_copies) {
        if (real_or_empty(copy.second) == copy.first) continue;  // already there (same folder)
        refuse_input(copy.second);
        for (size_t slash = out_folder.size() + 1;
             (slash = copy.second.find('/', slash)) != std::string::npos; ++slash) {
            mkdir(copy.second.substr(0, slash).c_str(), 0755);
        }
        const std::vector<uint8_t> bytes = read_file(copy.first, kMaxFileBytes);
        staged.stage(copy.second, bytes.data(), bytes.size());
        report.files.push_back(copy.second);
        report.copied_images.push_back(copy.second.substr(out_folder.size() + 1));
    }

    std::vector<uint8_t> main;
    if (glb) {
        main = glb_bytes(doc, buffer);
    } else {
        const std::string json = doc.dump(2) + "\n";
        main.assign(json.begin(), json.end());
    }
    staged.stage(main_path, main.data(), main.size());
    report.files.push_back(main_path);
    report.bytes += main.size();
    staged.commit();
    if (!replaced_bin.empty() && replaced_bin != bin_name) {
        const std::string stale = out_folder + "/" + replaced_bin;
        if (!inputs.count(real_or_empty(stale))) unlink(stale.c_str());
    }
    return report;
}

}  // namespace raps_gltf
