// What every benchmark here does the same way: load a shared mesh (optionally 1-to-4 subdivided)
// as triangles, run its measurements in a child process so that each case's peak resident set is
// its own and a crash costs one row, and take medians.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace raps_bench {

struct TriangleMesh {
    std::vector<double> positions;  // xyz per vertex
    std::vector<uint32_t> triangles;
};

// `file` read by raps_samples::read_mesh, then midpoint-subdivided `subdivisions` times.
TriangleMesh load_triangles(const std::string& file, int subdivisions = 0);

double median(std::vector<double> values);

template <class Sample>
struct ChildSamples {
    std::vector<Sample> samples;  // in the order the child emitted them; empty if it failed
    double peak_mb = 0;           // the child's peak resident set
};

// Forks; the child calls `produce(emit)`, where `emit(sample)` sends one Sample (a plain struct)
// back. An exception in the child is printed with `tool` and ends the child.
template <class Sample, class Produce>
ChildSamples<Sample> run_in_child(const char* tool, Produce produce) {
    static_assert(std::is_trivially_copyable<Sample>::value, "samples travel as bytes");
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        close(fds[0]);
        try {
            produce([&](const Sample& s) {
                if (write(fds[1], &s, sizeof(s)) != static_cast<ssize_t>(sizeof(s))) _exit(3);
            });
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", tool, e.what());
            _exit(2);
        }
        _exit(0);
    }
    close(fds[1]);
    ChildSamples<Sample> result;
    Sample s;
    while (read(fds[0], &s, sizeof(s)) == static_cast<ssize_t>(sizeof(s)))
        result.samples.push_back(s);
    close(fds[0]);
    int status = 0;
    struct rusage usage;
    wait4(pid, &status, 0, &usage);
    result.peak_mb = usage.ru_maxrss / 1024.0;
    return result;
}

}  // namespace raps_bench
