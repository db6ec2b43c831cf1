// How the command-line tools write a file: whole or not at all. A regular file, new or existing,
// is written to a temporary beside it and renamed over it, so that a failure leaves no
// half-written file; a symbolic link is followed, so the file it names is replaced and the link
// stays. An existing device, pipe or socket (/dev/null, /dev/stdout, a FIFO) is written into:
// renaming over it would replace it with a regular file (run as root, /dev/null itself, for
// every program on the machine).
#pragma once

#include <cstddef>
#include <string>

namespace raps_samples {

struct OutputFile {
    std::string path;     // where the temporary is renamed to, or, if direct, what is written
    bool direct = false;  // a device, pipe or socket
};

// Where `path`'s bytes go. Throws std::runtime_error naming `path` for a folder.
OutputFile output_file(const std::string& path);

// Writes `size` bytes into the existing device, pipe or socket `path`. Throws
// std::runtime_error naming `path` when it cannot.
void write_into(const std::string& path, const void* data, size_t size);

}  // namespace raps_samples
