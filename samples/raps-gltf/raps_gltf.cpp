// raps-gltf: bake texture coordinates into glTF 2.0 assets with raps's atlas domain.
//
//   raps-gltf IN OUT [options]             one asset (.gltf or .glb in and out)
//   raps-gltf IN... -o OUTDIR [options]    batch: files and folders, --jobs N at once
//
// Prints one JSON object on stdout (see --help); exit status 0 baked, 1 refused or failed,
// 2 usage error, 3 nothing to bake (no output written). Like raps-param, this tool is a
// contract that scripts and tests drive: keep its flags, JSON and exit codes stable.
#include <sys/stat.h>
#include <unistd.h>

#include <dirent.h>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gltf_bake.h"
#include "gltf_error.h"
#include "gltf_load.h"
#include "gltf_output.h"
#include "parameter_text.h"
#include "preview.h"
#include "raps.h"
#include "report.h"

namespace {

using raps_gltf::Json;

const char* kUsage = R"(usage: raps-gltf IN OUT [options]
       raps-gltf IN... -o OUTDIR [--jobs N] [options]

Writes new texture coordinates (TEXCOORD_0 by default) into every triangle primitive of a glTF
2.0 asset and keeps everything else: other attributes and morph targets are carried to the
vertices split at seams, materials, images (byte for byte), animations, skins, cameras, nodes,
extensions and extras are kept. IN and OUT are .gltf (external buffers or data uris) or .glb;
OUT's extension picks the format. Points and lines are left as they are.

Prints one JSON object on stdout: the settings, per atlas (one per mesh by default) its charts,
size, utilization, distortion figures and times, per primitive its counts and attributes, what
was skipped and why, and the files written; with --group scene also "scene": per page its size
and utilization, per mesh its instances and scale, per chart its mesh, page and texel rectangle.
On failure it prints {"error": {...}} and a message on stderr and writes nothing. Exit status: 0 baked, 1 refused or failed, 2 usage error,
3 nothing to bake (no triangle primitive; no output written).

options:
  --texcoord N               the set to write, TEXCOORD_N (default 0; 1 for lightmaps). Lower
                             sets the asset lacks get the same uvs (glTF's continuity rule)
  --overwrite                replace the set when a primitive already has it (without this flag
                             such an asset is refused)
  --group mesh|primitive|scene
                             one atlas per mesh (default; primitives sharing a texture must
                             share an atlas), one per primitive, or one for every mesh the
                             default scene draws, each at its world scale (a mesh drawn at
                             several scales at its largest), so one texel covers the same
                             surface everywhere; each mesh's page goes into its extras
                             ("raps_atlas": {"page": N})
  --uv-format float|unorm16  the new set's components: float (default) or normalized unsigned
                             shorts (core glTF; half the size; every vertex stays in its texel)
  --keep-uv-seams            the seams of the asset's TEXCOORD_0 stay chart boundaries (split
                             normals and colours do not cut charts)
  --lightmap                 a lightmap: writes TEXCOORD_1 (unless --texcoord says otherwise)
                             beside the asset's own uvs, padding 2, --rotate quarter, each
                             mesh's charts on one page, charts on whole texels at --resolution
                             or at --texels-per-unit (--padding and --rotate given override)
  --embed                    .gltf output: the buffer as a data uri instead of OUT.<hash>.bin
  --report FILE              also write the JSON to FILE
  --preview FILE.png         write a picture: the uv layout with chart outlines beside the model
                             rendered with a checker texture through the new uvs
  --progress, --no-progress  progress on stderr (default: when stderr is a terminal)
batch:
  -o, --output-dir DIR       write each input's result into DIR (folders given as inputs are
                             searched for .gltf and .glb, their sub-folders kept)
  --format glb|gltf          output format in batch mode (default: the input's)
  --previews                 write OUT.png beside each output
  --jobs N                   assets baked at once (default 1)
atlas (the library's settings; see include/raps.h):
  --monitor none|area|length|angle
                             distortion monitor of the adaptive step (default area)
  --alpha A                  exponent of W = w * e^alpha (default 1)
  --iterations K             adaptive solves, 1..100 (default 1)
  --iteration-mode accumulate|reapply
  --weights mvc|cotan|uniform
  --resolution N             texels on the atlas's longer side, 16..16384 (default 1024)
  --padding N                texels between charts, 0..64 (default 1)
  --texels-per-unit T        pack at T texels per unit of the positions (--group scene: per
                             world unit) instead of filling --resolution: charts on whole
                             texels, pages of at most --max-size, each mesh on one page
  --max-size N               with a density: pages of at most N x N texels, 16..16384
                             (default 4096), never exceeded (a mesh too large is shrunk)
  --rotate any|quarter|none  turns the packing may give a chart (default any)
  --margin N                 with a density or --lightmap: texels free at each page's border
  --block-align              with a density or --lightmap: charts on whole 4x4 blocks
  --weld-tolerance D         weld vertices closer than D (default 0: identical positions)
  --hard-edge-angle DEG      edges whose normals differ more become seams (default 180: none)
  --max-l2-stretch S         split charts until the L2 stretch is <= S (default 1.008)
  --max-linf-stretch S       split charts stretching a triangle more than S (default 2.9)
  --max-triangles N          refuse larger atlases
  --max-memory-mb N          refuse atlases estimated to need more memory (default 0: no cap)
  --threads N                threads per atlas, 0 = all cores (default 0; 1 with --jobs > 1);
                             the output is identical for any N
  -h, --help                 this text
  --version                  the raps library version
)";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Options {
    std::vector<std::string> inputs;
    std::string output;      // single mode
    std::string output_dir;  // batch mode
    std::string format;      // batch: "", "glb" or "gltf"
    std::string report, preview;
    bool previews = false, embed = false;
    int jobs = 1;
    int progress = -1;  // -1: when stderr is a terminal
    bool threads_set = false;
    raps_gltf::BakeOptions bake;
};

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

bool has_suffix(const std::string& s, const char* suffix) {
    const size_t n = std::strlen(suffix);
    if (s.size() < n) return false;
    for (size_t i = 0; i < n; ++i) {
        if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i])
            return false;
    }
    return true;
}

// One line on stderr, rewritten in place, at most ten times a second.
class ProgressLine {
  public:
    explicit ProgressLine(bool enabled) : enabled_(enabled) {}
    bool enabled() const { return enabled_; }
    void show(const std::string& text) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        const auto now = std::chrono::steady_clock::now();
        if (now - last_ < std::chrono::milliseconds(100)) return;
        last_ = now;
        std::fprintf(stderr, "\r\033[K%s", text.c_str());
        std::fflush(stderr);
        shown_ = true;
    }
    void line(const std::string& text) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        std::fprintf(stderr, "%s%s\n", shown_ ? "\r\033[K" : "", text.c_str());
        shown_ = false;
    }
    void clear() {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        if (shown_) std::fputs("\r\033[K", stderr);
        shown_ = false;
    }

  private:
    bool enabled_;
    std::mutex mutex_;
    std::chrono::steady_clock::time_point last_{};
    bool shown_ = false;
};

struct FileResult {
    Json json;
    int status = 0;  // exit status for this file: 0, 1 or 3
    uint64_t triangles = 0;
    double ms = 0;
};

FileResult process(const std::string& input, const std::string& output, const std::string& preview,
                   const Options& options, const raps_settings* settings, ProgressLine* line) {
    FileResult r;
    const auto start = std::chrono::steady_clock::now();
    r.json = Json::object();
    r.json["input"] = input;
    r.json["output"] = output;
    try {
        auto t = std::chrono::steady_clock::now();
        const raps_gltf::Asset asset = raps_gltf::load_asset(input);
        const double load_ms = ms_since(t);
        raps_gltf::BakeOptions bake_options = options.bake;
        bake_options.settings = settings;
        if (line && line->enabled()) {
            static const char* phases[] = {"validate", "topology", "charts", "adapt",
                                           "metrics",  "segment",  "pack"};
            bake_options.progress = [line, input](const std::string& label, raps_phase phase,
                                                  double fraction) {
                line->show("raps-gltf: " + input + ": " + label + ": " +
                           (phase >= 0 && phase < RAPS_PHASE_COUNT ? phases[phase] : "") + " " +
                           std::to_string(static_cast<int>(fraction * 100)) + "%");
                return true;
            };
        }
        t = std::chrono::steady_clock::now();
        raps_gltf::BakeResult baked = raps_gltf::bake(asset, bake_options);
        const double bake_ms = ms_since(t);
        if (line) line->clear();
        r.json["format"] = has_suffix(output, ".glb") ? "glb" : "gltf";
        r.json["settings"] = raps_gltf::settings_json(settings, bake_options);
        const Json details = raps_gltf::bake_json(baked);
        for (auto it = details.begin(); it != details.end(); ++it) r.json[it.key()] = it.value();
        if (!asset.warnings.empty()) r.json["loader_warnings"] = asset.warnings;
        if (baked.groups.empty()) {
            r.status = 3;
            r.json["nothing_to_bake"] = true;
            r.json["message"] = "no triangle primitive with positions to bake; nothing written";
            r.json.erase("output");
            r.ms = ms_since(start);
            return r;
        }
        t = std::chrono::steady_clock::now();
        raps_gltf::WriteOptions write_options;
        write_options.embed = options.embed;
        const raps_gltf::WriteReport written =
            raps_gltf::write_output(asset, baked, output, write_options);
        const double write_ms = ms_since(t);
        r.json["written"] = raps_gltf::output_json(written);
        double preview_ms = 0;
        if (!preview.empty()) {
            t = std::chrono::steady_clock::now();
            raps_gltf::write_preview(preview, asset, baked, raps_gltf::PreviewOptions());
            preview_ms = ms_since(t);
            r.json["preview"] = preview;
        }
        r.triangles = baked.baked_triangles;
        r.ms = ms_since(start);
        r.json["time_ms"] = {{"load", load_ms},
                             {"bake", bake_ms},
                             {"write", write_ms},
                             {"preview", preview_ms},
                             {"total", r.ms}};
    } catch (const raps_gltf::GltfError& e) {
        if (line) line->clear();
        r.status = 1;
        r.json.erase("output");
        r.json["error"] = {{"kind", e.kind}, {"message", e.what()}};
    } catch (const std::exception& e) {
        if (line) line->clear();
        r.status = 1;
        r.json.erase("output");
        r.json["error"] = {{"kind", "internal"}, {"message", e.what()}};
    }
    r.ms = ms_since(start);
    return r;
}

// Inputs for batch mode: files as given, folders searched (sorted) for .gltf and .glb; each with
// its output path under the output folder (a folder's sub-folders are kept).
void collect(const std::string& path, const std::string& relative,
             std::vector<std::pair<std::string, std::string>>* out, int depth) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) throw UsageError("no such file or folder: " + path);
    if (!S_ISDIR(st.st_mode)) {
        out->emplace_back(path, relative);
        return;
    }
    if (depth > 32) return;
    DIR* dir = opendir(path.c_str());
    if (!dir) throw UsageError("cannot read the folder " + path);
    std::vector<std::string> names;
    while (dirent* entry = readdir(dir)) {
        const std::string name = entry->d_name;
        if (name != "." && name != "..") names.push_back(name);
    }
    closedir(dir);
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
        const std::string child = path + "/" + name;
        const std::string child_relative = relative.empty() ? name : relative + "/" + name;
        if (stat(child.c_str(), &st) != 0) continue;
        if (S_ISDIR(st.st_mode)) {
            collect(child, child_relative, out, depth + 1);
        } else if (has_suffix(name, ".gltf") || has_suffix(name, ".glb")) {
            out->emplace_back(child, child_relative);
        }
    }
}

void write_json_file(const std::string& path, const Json& json) {
    const std::string text = json.dump(2) + "\n";
    raps_gltf::write_file_atomically(path, std::vector<uint8_t>(text.begin(), text.end()));
}

struct SettingsHandle {
    raps_settings* settings = nullptr;
    ~SettingsHandle() { raps_settings_destroy(settings); }
};

// Which flags the command line gave, for the checks of their combinations.
struct GivenFlags {
    bool texcoord = false, lightmap = false, resolution = false, max_size = false, margin = false,
         block_align = false;
};

// Reads the command line into the options and the library's settings. Returns false for --help
// and --version (printed).
bool parse_arguments(int argc, char** argv, raps_settings* settings, Options& options,
                     GivenFlags& given) {
    for (int i = 1; i < argc; ++i)
        given.lightmap = given.lightmap || !std::strcmp(argv[i], "--lightmap");
    if (given.lightmap) {
        const std::string error = raps_samples::apply_lightmap_preset(settings);
        if (!error.empty()) throw std::runtime_error(error);
    }
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(arg + " needs a value");
            return argv[++i];
        };
        auto whole = [&](const std::string& text, long lo, long hi) {
            char* end = nullptr;
            errno = 0;
            const long v = std::strtol(text.c_str(), &end, 10);
            if (end == text.c_str() || *end || errno || v < lo || v > hi) {
                throw UsageError(arg + " needs a whole number in [" + std::to_string(lo) + ", " +
                                 std::to_string(hi) + "], not '" + text + "'");
            }
            return static_cast<int>(v);
        };
        if (arg == "-h" || arg == "--help") {
            std::fputs(kUsage, stdout);
            return false;
        } else if (arg == "--version") {
            std::printf("raps-gltf (raps %s)\n", raps_version_string());
            return false;
        } else if (arg == "--texcoord") {
            options.bake.texcoord = whole(value(), 0, 31);
            given.texcoord = true;
        } else if (arg == "--overwrite") {
            options.bake.overwrite = true;
        } else if (arg == "--group") {
            const std::string g = value();
            if (g != "mesh" && g != "primitive" && g != "scene")
                throw UsageError("--group is mesh, primitive or scene");
            options.bake.grouping = g == "mesh"        ? raps_gltf::Grouping::kMesh
                                    : g == "primitive" ? raps_gltf::Grouping::kPrimitive
                                                       : raps_gltf::Grouping::kScene;
        } else if (arg == "--lightmap") {
            continue;  // applied above
        } else if (arg == "--max-size") {
            const std::string error = raps_samples::set_max_size(settings, value());
            if (!error.empty()) throw UsageError(error);
            given.max_size = true;
        } else if (arg == "--uv-format") {
            const std::string f = value();
            if (f != "float" && f != "unorm16") throw UsageError("--uv-format is float or unorm16");
            options.bake.uv_format =
                f == "float" ? raps_gltf::UvFormat::kFloat : raps_gltf::UvFormat::kUnorm16;
        } else if (const raps_samples::SwitchFlag* on = raps_samples::find_switch_flag(arg);
                   on && on->gltf) {
            const std::string error = raps_samples::set_switch(settings, *on);
            if (!error.empty()) throw UsageError(arg + ": " + error);
            options.bake.keep_uv_seams = options.bake.keep_uv_seams || arg == "--keep-uv-seams";
            given.block_align = given.block_align || arg == "--block-align";
        } else if (arg == "--embed") {
            options.embed = true;
        } else if (arg == "--report") {
            options.report = value();
        } else if (arg == "--preview") {
            options.preview = value();
        } else if (arg == "--previews") {
            options.previews = true;
        } else if (arg == "--progress") {
            options.progress = 1;
        } else if (arg == "--no-progress") {
            options.progress = 0;
        } else if (arg == "-o" || arg == "--output-dir") {
            options.output_dir = value();
        } else if (arg == "--format") {
            options.format = value();
            if (options.format != "glb" && options.format != "gltf") {
                throw UsageError("--format is glb or gltf");
            }
        } else if (arg == "--jobs") {
            options.jobs = whole(value(), 1, 256);
        } else if (const raps_samples::ParameterFlag* flag = raps_samples::find_parameter_flag(arg);
                   flag && flag->atlas) {
            const std::string error =
                raps_samples::set_parameter_from_text(settings, *flag, value());
            if (!error.empty()) throw UsageError(error);
            options.threads_set = options.threads_set || arg == "--threads";
            given.resolution = given.resolution || arg == "--resolution";
            given.margin = given.margin || arg == "--margin";
        } else if (!arg.empty() && arg[0] == '-' && arg != "-") {
            throw UsageError("unknown option " + arg);
        } else {
            options.inputs.push_back(arg);
        }
    }
    // A lightmap goes beside the asset's own uvs unless told otherwise.
    if (given.lightmap && !given.texcoord) options.bake.texcoord = 1;
    return true;
}

// Flags that would be ignored are refused: a user who asks for pages or a margin must get them.
void check_atlas_flags(const GivenFlags& given, const raps_settings* settings) {
    double density = 0;
    int64_t whole_texels = 0;
    raps_settings_get_float(settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, &density);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_WHOLE_TEXELS, &whole_texels);
    if (density > 0 && given.resolution) {
        throw UsageError(
            "--resolution and --texels-per-unit exclude each other: a density sizes "
            "the pages itself (bounded by --max-size)");
    }
    if (density == 0 && given.max_size) {
        throw UsageError(
            "--max-size bounds the pages of a density: give --texels-per-unit too "
            "(without one, --resolution sizes the atlas)");
    }
    if (density == 0 && !whole_texels && (given.margin || given.block_align)) {
        throw UsageError(std::string(given.margin ? "--margin" : "--block-align") +
                         " places charts on whole texels: give --texels-per-unit or --lightmap "
                         "too");
    }
}

// Checks the inputs and outputs of single and batch mode.
void check_files(Options& options) {
    const bool batch = !options.output_dir.empty();
    if (!batch) {
        if (options.inputs.size() != 2) {
            throw UsageError(options.inputs.empty() ? "no input file"
                             : options.inputs.size() == 1
                                 ? "no output file (raps-gltf IN OUT, or -o DIR for batch mode)"
                                 : "one input and one output, or -o DIR for batch mode");
        }
        options.output = options.inputs[1];
        options.inputs.pop_back();
        if (!has_suffix(options.output, ".glb") && !has_suffix(options.output, ".gltf")) {
            throw UsageError("the output must end in .glb or .gltf: " + options.output);
        }
        if (options.previews || options.jobs != 1 || !options.format.empty()) {
            throw UsageError("--previews, --jobs and --format are batch options (-o DIR)");
        }
        if (options.embed && !has_suffix(options.output, ".gltf")) {
            throw UsageError("--embed is for .gltf output");
        }
    } else {
        if (options.inputs.empty()) throw UsageError("no input file or folder");
        if (!options.preview.empty())
            throw UsageError("batch mode writes previews with --previews");
    }
}

int run(int argc, char** argv) {
    Options options;
    GivenFlags given;
    SettingsHandle h;
    if (raps_settings_create(&h.settings) != RAPS_OK)
        throw std::runtime_error("cannot create settings");
    if (!parse_arguments(argc, argv, h.settings, options, given)) return 0;
    check_atlas_flags(given, h.settings);
    check_files(options);
    const bool batch = !options.output_dir.empty();
    if (options.jobs > 1 && !options.threads_set) {
        raps_settings_set_int(h.settings, RAPS_PARAM_THREADS, 1);  // files in parallel instead
    }
    ProgressLine line(options.progress < 0 ? isatty(STDERR_FILENO) != 0 : options.progress == 1);

    if (!batch) {
        const FileResult r =
            process(options.inputs[0], options.output, options.preview, options, h.settings, &line);
        std::puts(r.json.dump().c_str());
        if (r.status == 1) {
            std::fprintf(stderr, "raps-gltf: %s: %s\n", options.inputs[0].c_str(),
                         r.json["error"]["message"].get<std::string>().c_str());
        } else if (r.status == 3) {
            std::string why;
            for (const Json& skip : r.json["skipped"]) {
                why += "; mesh " + skip["mesh"].dump() + " primitive " + skip["primitive"].dump() +
                       ": " + skip["reason"].get<std::string>();
            }
            std::fprintf(stderr, "raps-gltf: %s: nothing to bake, no output written%s\n",
                         options.inputs[0].c_str(), why.c_str());
        }
        if (!options.report.empty()) write_json_file(options.report, r.json);
        return r.status;
    }

    std::vector<std::pair<std::string, std::string>> files;
    for (const std::string& input : options.inputs) {
        const size_t slash = input.find_last_of('/');
        struct stat st;
        const bool is_dir = stat(input.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
        collect(input, is_dir ? "" : input.substr(slash == std::string::npos ? 0 : slash + 1),
                &files, 0);
    }
    if (mkdir(options.output_dir.c_str(), 0755) != 0 && errno != EEXIST) {
        throw UsageError("cannot create the output folder " + options.output_dir);
    }
    std::vector<FileResult> results(files.size());
    std::atomic<size_t> next{0}, finished{0};
    auto worker = [&]() {
        for (size_t i; (i = next++) < files.size();) {
            std::string relative = files[i].second;
            const std::string format = !options.format.empty()
                                           ? options.format
                                           : (has_suffix(relative, ".glb") ? "glb" : "gltf");
            relative = relative.substr(0, relative.find_last_of('.')) + "." + format;
            const std::string output = options.output_dir + "/" + relative;
            for (size_t slash = options.output_dir.size() + 1;
                 (slash = output.find('/', slash)) != std::string::npos; ++slash) {
                mkdir(output.substr(0, slash).c_str(), 0755);
            }
            const std::string preview =
                options.previews ? output.substr(0, output.find_last_of('.')) + ".png" : "";
            results[i] = process(files[i].first, output, preview, options, h.settings,
                                 options.jobs == 1 ? &line : nullptr);
            const FileResult& r = results[i];
            const char* what = r.status == 0   ? "baked"
                               : r.status == 3 ? "nothing to bake"
                                               : "FAILED";
            char text[64];
            std::snprintf(text, sizeof(text), " (%.0f ms)", r.ms);
            line.line("[" + std::to_string(++finished) + "/" + std::to_string(files.size()) + "] " +
                      files[i].first + ": " + what +
                      (r.status == 1 ? ": " + r.json["error"]["message"].get<std::string>() : "") +
                      text);
        }
    };
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> threads;
    for (int j = 1; j < std::min<int>(options.jobs, static_cast<int>(files.size())); ++j)
        threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();

    Json out = Json::object();
    Json list = Json::array();
    size_t baked = 0, nothing = 0, failed = 0;
    uint64_t triangles = 0;
    for (const FileResult& r : results) {
        list.push_back(r.json);
        baked += r.status == 0;
        nothing += r.status == 3;
        failed += r.status == 1;
        triangles += r.triangles;
        if (r.status == 1) {
            std::fprintf(stderr, "raps-gltf: %s: %s\n", r.json["input"].get<std::string>().c_str(),
                         r.json["error"]["message"].get<std::string>().c_str());
        }
    }
    out["files"] = list;
    out["summary"] = {{"files", results.size()},    {"baked", baked},
                      {"nothing_to_bake", nothing}, {"failed", failed},
                      {"triangles", triangles},     {"jobs", options.jobs},
                      {"time_ms", ms_since(start)}};
    std::puts(out.dump().c_str());
    if (!options.report.empty()) write_json_file(options.report, out);
    return failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const UsageError& e) {
        Json error = {{"error", {{"kind", "usage"}, {"message", e.what()}}}};
        std::puts(error.dump().c_str());
        std::fprintf(stderr, "raps-gltf: %s\ntry raps-gltf --help\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        Json error = {{"error", {{"kind", "internal"}, {"message", e.what()}}}};
        std::puts(error.dump().c_str());
        std::fprintf(stderr, "raps-gltf: %s\n", e.what());
        return 1;
    }
}
