// The settings of one run, as plain C++ values. The C API validates and converts the public
// key/value parameters into this struct; algorithms read only the fields they need.
#pragma once

#include <cstdint>

namespace raps {

enum class Domain { kDisk, kSphere };
enum class WeightScheme { kMeanValue, kCotangent, kUniform };
enum class Monitor { kNone, kArea, kEdgeLength, kAngle };
enum class IterationMode { kAccumulate, kReapply };
enum class BoundaryShape { kCircle, kSquare };
enum class SphereMethod { kLiteral, kRobust };
enum class SphereUv { kNone, kOctahedral };

struct Settings {
    Domain domain = Domain::kDisk;
    WeightScheme weights = WeightScheme::kMeanValue;
    Monitor monitor = Monitor::kArea;
    double alpha = 1.0;
    int iterations = 1;
    IterationMode iteration_mode = IterationMode::kAccumulate;
    BoundaryShape boundary = BoundaryShape::kCircle;
    int64_t max_triangles = 0x7fffffff;
    int threads = 0;  // 0: all cores
    SphereMethod sphere_method = SphereMethod::kRobust;
    SphereUv sphere_uv = SphereUv::kNone;
    double sphere_damping = 1.0;
    double sphere_tolerance = 1e-4;
    int64_t sphere_max_sweeps = 0;  // 0: the method's own
    int sphere_alpha_steps = 4;
};

}  // namespace raps
