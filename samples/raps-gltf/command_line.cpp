#include "command_line.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "parameter_text.h"

namespace raps_gltf {

namespace {

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
  --stack, --stack-mirrored  congruent charts (the same triangles and vertex order, up to a
                             rigid motion; with --stack-mirrored a mirror too) share one place
                             in the atlas, so copies of a mesh cost no texels; their charts say
                             "stacked_on" in the report. Not with --lightmap or a density
  --stack-tolerance F        how far a stacked chart's vertices may lie from its original's,
                             as a fraction of the chart's extent, [0, 0.1] (default 1e-4)
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
  --resolution N             texels on each side of the square atlas, 16..16384 (default 1024)
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
            options.bake.grouping = g == "mesh"        ? Grouping::kMesh
                                    : g == "primitive" ? Grouping::kPrimitive
                                                       : Grouping::kScene;
        } else if (arg == "--lightmap") {
            continue;  // applied above
        } else if (arg == "--max-size") {
            const std::string error = raps_samples::set_max_size(settings, value());
            if (!error.empty()) throw UsageError(error);
            given.max_size = true;
        } else if (arg == "--stack" || arg == "--stack-mirrored") {
            const std::string error = raps_samples::set_stack(settings, arg, given.lightmap);
            if (!error.empty()) throw UsageError(error);
        } else if (arg == "--uv-format") {
            const std::string f = value();
            if (f != "float" && f != "unorm16") throw UsageError("--uv-format is float or unorm16");
            options.bake.uv_format = f == "float" ? UvFormat::kFloat32 : UvFormat::kUnorm16;
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
    int64_t stack = 0;
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_STACK, &stack);
    if (density > 0 && stack != RAPS_STACK_NONE) {
        throw UsageError(
            "--stack and --texels-per-unit exclude each other: with a density each mesh keeps "
            "its charts on its own page (one texture per primitive), so no chart could share "
            "another mesh's texels; give --resolution");
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

}  // namespace

bool has_suffix(const std::string& s, const char* suffix) {
    const size_t n = std::strlen(suffix);
    if (s.size() < n) return false;
    for (size_t i = 0; i < n; ++i) {
        if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i])
            return false;
    }
    return true;
}

bool parse_command_line(int argc, char** argv, raps_settings* settings, Options& options) {
    GivenFlags given;
    if (!parse_arguments(argc, argv, settings, options, given)) return false;
    check_atlas_flags(given, settings);
    check_files(options);
    return true;
}

}  // namespace raps_gltf
