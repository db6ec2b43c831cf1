// raps-gltf's command line: its flags read into the options and the library's settings, and the
// combinations checked. A flag that would be ignored is refused (UsageError, exit status 2)
// before any file is read or written.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "gltf_bake.h"
#include "raps.h"

namespace raps_gltf {

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
    BakeOptions bake;
};

// Case-insensitive: s ends with the lower-case suffix.
bool has_suffix(const std::string& s, const char* suffix);

// Reads the command line into the options and settings and checks it. Returns false when
// --help or --version was printed; throws UsageError for a bad command line.
bool parse_command_line(int argc, char** argv, raps_settings* settings, Options& options);

}  // namespace raps_gltf
