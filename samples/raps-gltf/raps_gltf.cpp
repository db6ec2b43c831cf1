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

#include "command_line.h"
#include "gltf_bake.h"
#include "gltf_error.h"
#include "gltf_load.h"
#include "gltf_output.h"
#include "preview.h"
#include "raps.h"
#include "report.h"

namespace {

using raps_gltf::has_suffix;
using raps_gltf::Json;
using raps_gltf::Options;
using raps_gltf::UsageError;

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
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

// One input, one output: the JSON on stdout, the reason on stderr when nothing was written.
int run_single(const Options& options, const raps_settings* settings, ProgressLine* line) {
    const FileResult r =
        process(options.inputs[0], options.output, options.preview, options, settings, line);
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

// Batch mode's inputs, each with its path relative to the output folder.
std::vector<std::pair<std::string, std::string>> batch_files(const Options& options) {
    std::vector<std::pair<std::string, std::string>> files;
    for (const std::string& input : options.inputs) {
        const size_t slash = input.find_last_of('/');
        struct stat st;
        const bool is_dir = stat(input.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
        collect(input, is_dir ? "" : input.substr(slash == std::string::npos ? 0 : slash + 1),
                &files, 0);
    }
    return files;
}

// Where a batch input's result goes (its folders created), in the format asked or its own.
std::string batch_output(const Options& options, std::string relative) {
    const std::string format =
        !options.format.empty() ? options.format : (has_suffix(relative, ".glb") ? "glb" : "gltf");
    relative = relative.substr(0, relative.find_last_of('.')) + "." + format;
    const std::string output = options.output_dir + "/" + relative;
    for (size_t slash = options.output_dir.size() + 1;
         (slash = output.find('/', slash)) != std::string::npos; ++slash) {
        mkdir(output.substr(0, slash).c_str(), 0755);
    }
    return output;
}

void show_finished(ProgressLine& line, const std::string& input, const FileResult& r,
                   size_t finished, size_t total) {
    const char* what = r.status == 0 ? "baked" : r.status == 3 ? "nothing to bake" : "FAILED";
    char text[64];
    std::snprintf(text, sizeof(text), " (%.0f ms)", r.ms);
    line.line("[" + std::to_string(finished) + "/" + std::to_string(total) + "] " + input + ": " +
              what + (r.status == 1 ? ": " + r.json["error"]["message"].get<std::string>() : "") +
              text);
}

// The batch's JSON: every file's, then the summary; failures also on stderr.
Json batch_json(const std::vector<FileResult>& results, int jobs, double ms) {
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
    Json out = Json::object();
    out["files"] = list;
    out["summary"] = {{"files", results.size()},
                      {"baked", baked},
                      {"nothing_to_bake", nothing},
                      {"failed", failed},
                      {"triangles", triangles},
                      {"jobs", jobs},
                      {"time_ms", ms}};
    return out;
}

// Files and folders into the output folder, --jobs files at once.
int run_batch(const Options& options, const raps_settings* settings, ProgressLine& line) {
    const std::vector<std::pair<std::string, std::string>> files = batch_files(options);
    if (mkdir(options.output_dir.c_str(), 0755) != 0 && errno != EEXIST) {
        throw UsageError("cannot create the output folder " + options.output_dir);
    }
    std::vector<FileResult> results(files.size());
    std::atomic<size_t> next{0}, finished{0};
    auto worker = [&]() {
        for (size_t i; (i = next++) < files.size();) {
            const std::string output = batch_output(options, files[i].second);
            const std::string preview =
                options.previews ? output.substr(0, output.find_last_of('.')) + ".png" : "";
            results[i] = process(files[i].first, output, preview, options, settings,
                                 options.jobs == 1 ? &line : nullptr);
            show_finished(line, files[i].first, results[i], ++finished, files.size());
        }
    };
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> threads;
    for (int j = 1; j < std::min<int>(options.jobs, static_cast<int>(files.size())); ++j)
        threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();
    const Json out = batch_json(results, options.jobs, ms_since(start));
    std::puts(out.dump().c_str());
    if (!options.report.empty()) write_json_file(options.report, out);
    return out["summary"]["failed"].get<size_t>() ? 1 : 0;
}

int run(int argc, char** argv) {
    Options options;
    SettingsHandle h;
    if (raps_settings_create(&h.settings) != RAPS_OK)
        throw std::runtime_error("cannot create settings");
    if (!parse_command_line(argc, argv, h.settings, options)) return 0;
    if (options.jobs > 1 && !options.threads_set) {
        raps_settings_set_int(h.settings, RAPS_PARAM_THREADS, 1);  // files in parallel instead
    }
    ProgressLine line(options.progress < 0 ? isatty(STDERR_FILENO) != 0 : options.progress == 1);
    return options.output_dir.empty() ? run_single(options, h.settings, &line)
                                      : run_batch(options, h.settings, line);
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
