#include "output_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace raps_samples {

OutputFile output_file(const std::string& path) {
    struct stat status;
    if (stat(path.c_str(), &status) != 0) return {path, false};  // a new file (or a broken link)
    if (S_ISDIR(status.st_mode)) throw std::runtime_error(path + ": is a folder, not a file");
    std::unique_ptr<char, decltype(&std::free)> real(realpath(path.c_str(), nullptr), &std::free);
    return {real ? std::string(real.get()) : path, !S_ISREG(status.st_mode)};
}

void write_into(const std::string& path, const void* data, size_t size) {
    FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) throw std::runtime_error(path + ": cannot write (" + std::strerror(errno) + ")");
    const bool written = std::fwrite(data, 1, size, file) == size;
    const int error = errno;
    if (std::fclose(file) != 0 || !written) {
        throw std::runtime_error(path + ": cannot write (" +
                                 std::strerror(written ? errno : error) + ")");
    }
}

}  // namespace raps_samples
