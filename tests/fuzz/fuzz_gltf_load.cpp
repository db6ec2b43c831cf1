// Fuzz target: raps-gltf's loading path on untrusted bytes. The input is one file, named
// fuzz.glb when it starts with the GLB magic and fuzz.gltf otherwise, alone in a private folder
// (so every uri it names is either a data uri or a file that does not exist, or an escape that
// must be refused). It goes through everything raps-gltf does with a file: load_asset (GLB
// framing, JSON depth, uris, buffers, bufferView and accessor ranges, references, the node
// graph), bake (every accessor read, strips and fans, morph targets, the library's atlas),
// write_output, and the written file must load again.
//
// The promise: a malformed file is a GltfError naming the problem, never a crash, a hang, a
// read past what was given, a leak, or any other exception (raps-gltf reports those as
// "internal": a bug). Anything else aborts, which libFuzzer and the replay driver report.
// Runs stay short: at most kMaxTriangles triangles reach the library, on a 64-texel atlas.
// The input's last byte picks the mode, so that the seeds reach every one: bit 0 bakes with
// --group scene (the node graph's transforms, one atlas), unorm16 texcoords and TEXCOORD_0's
// seams kept; bit 1 packs at a density on pages of at most 64 x 64 texels.
// RAPS_FUZZ_VERBOSE=1 prints each input's outcome.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <unistd.h>

#include "gltf_bake.h"
#include "gltf_error.h"
#include "gltf_load.h"
#include "gltf_output.h"
#include "raps.h"

namespace {

constexpr int64_t kMaxTriangles = 4000;

[[noreturn]] void broken_promise(const char* where, const char* what) {
    std::fprintf(stderr, "fuzz_gltf_load: %s: %s\n", where, what);
    std::abort();
}

// One folder for the whole process: the input and the output are written there and removed.
const std::string& work_folder() {
    static const std::string folder = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/raps-fuzz-gltf-XXXXXX";
        if (!mkdtemp(&pattern[0])) broken_promise("setup", "cannot create a temporary folder");
        return pattern;
    }();
    return folder;
}

void write_input(const std::string& path, const uint8_t* data, size_t size) {
    FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) broken_promise("setup", "cannot write the input file");
    const bool written = std::fwrite(data, 1, size, file) == size;
    if (std::fclose(file) != 0 || !written) broken_promise("setup", "cannot write the input file");
}

raps_settings* small_atlas_settings() {
    raps_settings* settings = nullptr;
    if (raps_settings_create(&settings) != RAPS_OK ||
        raps_settings_set_int(settings, RAPS_PARAM_MAX_TRIANGLES, kMaxTriangles) != RAPS_OK ||
        raps_settings_set_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, 64) != RAPS_OK ||
        raps_settings_set_int(settings, RAPS_PARAM_THREADS, 1) != RAPS_OK) {
        broken_promise("setup", "cannot create the settings");
    }
    return settings;
}

raps_settings* density_settings() {
    raps_settings* settings = small_atlas_settings();
    if (raps_settings_set_float(settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, 8.0) != RAPS_OK ||
        raps_settings_set_int(settings, RAPS_PARAM_ATLAS_MAX_WIDTH, 64) != RAPS_OK ||
        raps_settings_set_int(settings, RAPS_PARAM_ATLAS_MAX_HEIGHT, 64) != RAPS_OK) {
        broken_promise("setup", "cannot create the settings");
    }
    return settings;
}

void report(const char* outcome, const std::string& detail) {
    static const bool verbose = std::getenv("RAPS_FUZZ_VERBOSE") != nullptr;
    if (verbose) std::fprintf(stderr, "fuzz_gltf_load: %s %s\n", outcome, detail.c_str());
}

// Load, bake, write, load the output again. GltfError is the documented way to refuse.
void bake_file(const std::string& input, const std::string& output, const raps_settings* settings,
               bool scene) {
    const raps_gltf::Asset asset = raps_gltf::load_asset(input);
    raps_gltf::BakeOptions options;
    options.settings = settings;
    options.overwrite = true;  // also rewrite sets the input already has
    if (scene) {
        options.grouping = raps_gltf::Grouping::kScene;
        options.uv_format = raps_gltf::UvFormat::kUnorm16;
        options.keep_uv_seams = true;
    }
    raps_gltf::BakeResult baked = raps_gltf::bake(asset, options);
    if (baked.groups.empty()) {  // nothing to bake: raps-gltf writes nothing either
        report("nothing to bake", "");
        return;
    }
    raps_gltf::write_output(asset, baked, output, raps_gltf::WriteOptions());
    try {
        raps_gltf::load_asset(output);
        report("baked", std::to_string(baked.baked_triangles) + " triangles");
    } catch (const raps_gltf::GltfError& e) {
        broken_promise("the written asset does not load again", e.what());
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static raps_settings* const settings = small_atlas_settings();
    static raps_settings* const paged = density_settings();
    const uint8_t mode = size ? data[size - 1] : 0;
    const bool glb =
        size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
    const std::string input = work_folder() + (glb ? "/fuzz.glb" : "/fuzz.gltf");
    const std::string output = work_folder() + "/out.glb";
    write_input(input, data, size);
    try {
        bake_file(input, output, mode & 2 ? paged : settings, (mode & 1) != 0);
    } catch (const raps_gltf::GltfError& e) {
        report("refused", e.kind + ": " + e.what());  // what a malformed file must get
    } catch (const std::exception& e) {
        broken_promise("an exception other than GltfError", e.what());
    }
    std::remove(input.c_str());
    std::remove(output.c_str());
    return 0;
}
