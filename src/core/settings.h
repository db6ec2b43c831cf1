// The settings of one run, as plain C++ values. The C API validates and converts the public
// key/value parameters into this struct; algorithms read only the fields they need.
#pragma once

#include <cstdint>

namespace raps {

enum class Domain { kDisk = 0, kSphere = 1, kAtlas = 2 };
enum class WeightScheme { kMeanValue, kCotangent, kUniform };
enum class Monitor { kNone, kArea, kEdgeLength, kAngle };
enum class IterationMode { kAccumulate, kReapply };
enum class BoundaryShape { kCircle, kSquare };
enum class SphereMethod { kLiteral, kRobust };
enum class SphereUv { kNone, kOctahedral };
// Which turns the atlas's packing may give a chart: any angle (its smallest box, then quarter
// turns), quarter turns of its map only, or none.
enum class ChartRotation { kAny = 0, kQuarter = 1, kNone = 2 };
// Whether congruent charts share one place in the atlas: never, when a rigid motion takes one
// onto the other, or also when only a mirror does.
enum class ChartStacking { kNone = 0, kRigid = 1, kMirrored = 2 };

struct Settings {
    Domain domain = Domain::kDisk;
    WeightScheme weights = WeightScheme::kMeanValue;
    Monitor monitor = Monitor::kArea;
    double alpha = 1.0;
    int iterations = 1;
    IterationMode iteration_mode = IterationMode::kAccumulate;
    BoundaryShape boundary = BoundaryShape::kCircle;
    int64_t max_triangles = 0x7fffffff;
    int threads = 0;            // 0: all hardware threads
    int64_t max_memory_mb = 0;  // 0: no cap on the estimated peak (core/memory_estimate.h)

    // Sphere domain.
    SphereMethod sphere_method = SphereMethod::kRobust;
    SphereUv sphere_uv = SphereUv::kNone;
    double sphere_damping = 1.0;
    double sphere_tolerance = 1e-4;
    int64_t sphere_max_sweeps = 0;  // 0: the method's own
    int sphere_alpha_steps = 2;

    // Atlas domain.
    int32_t atlas_resolution = 1024;   // texels on each side of the square atlas
    int32_t atlas_padding = 1;         // texels between charts
    double weld_tolerance = 0.0;       // distance under which vertices are one
    double hard_edge_angle_deg = 180;  // dihedral angle above which an edge is a seam (180: off)
    double atlas_target_l2 = 1.01;     // charts are split until the atlas's L2 stretch meets it
    double atlas_max_linf = 2.9;       // largest stretch allowed in any chart
    // Texels per world unit; 0: the density that fills atlas_resolution (one page).
    double atlas_texels_per_unit = 0;
    int32_t atlas_max_width = 4096, atlas_max_height = 4096;  // pages, with a density
    ChartRotation atlas_rotation = ChartRotation::kAny;
    int32_t atlas_margin = 0;             // texels at the page border, with a density
    bool atlas_block_align = false;       // charts on whole 4x4 blocks, with a density
    bool atlas_mesh_per_page = false;     // a scene's mesh on one page, with a density
    bool atlas_whole_texels = false;      // without a density: whole texels on one page
    bool atlas_keep_input_seams = false;  // input vertex splits stay chart boundaries
    bool atlas_repack = false;            // pack the input's own uv charts, no new map
    ChartStacking atlas_stack = ChartStacking::kNone;
    double atlas_stack_tolerance = 1e-4;  // of a chart's extent
};

}  // namespace raps
