// The C ABI: the only extern "C" code. It checks arguments, converts between the caller's
// arrays and the C++ types, catches every exception and turns it into a status plus a message
// stored in the handle. No algorithm lives here.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/LU>  // determinant

#include "core/error.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "parameterization.h"
#include "raps.h"

static_assert(sizeof(raps_stats) == 8 + 6 * 8 + 6 * 8 + 4 * 8 + 8 + 8 + 3 * 8,
              "raps_stats layout is ABI");
static_assert(offsetof(raps_stats, relaxation_sweeps) == 104, "raps_stats layout is ABI");
static_assert(offsetof(raps_stats, threads_used) == 144, "raps_stats layout is ABI");
static_assert(offsetof(raps_stats, texels_per_unit) == 168, "raps_stats layout is ABI");
static_assert(sizeof(raps_chart) == 32 + 8 + 8 + 3 * 8 + 8, "raps_chart layout is ABI");
static_assert(offsetof(raps_chart, stacked_on) == 72, "raps_chart layout is ABI");
static_assert(offsetof(raps_chart, rotation_deg) == 32, "raps_chart layout is ABI");

#define RAPS_CHECK_CODE(name, value) \
    static_assert(static_cast<int32_t>(raps::ErrorCode::name) == (value), #value)
RAPS_CHECK_CODE(kInvalidArgument, RAPS_ERROR_INVALID_ARGUMENT);
RAPS_CHECK_CODE(kOutOfMemory, RAPS_ERROR_OUT_OF_MEMORY);
RAPS_CHECK_CODE(kEmptyMesh, RAPS_ERROR_EMPTY_MESH);
RAPS_CHECK_CODE(kIndexCount, RAPS_ERROR_INDEX_COUNT);
RAPS_CHECK_CODE(kIndexOutOfRange, RAPS_ERROR_INDEX_OUT_OF_RANGE);
RAPS_CHECK_CODE(kNonFinitePosition, RAPS_ERROR_NON_FINITE_POSITION);
RAPS_CHECK_CODE(kRepeatedVertex, RAPS_ERROR_REPEATED_VERTEX);
RAPS_CHECK_CODE(kZeroAreaTriangle, RAPS_ERROR_ZERO_AREA_TRIANGLE);
RAPS_CHECK_CODE(kNonManifoldEdge, RAPS_ERROR_NON_MANIFOLD_EDGE);
RAPS_CHECK_CODE(kNonManifoldVertex, RAPS_ERROR_NON_MANIFOLD_VERTEX);
RAPS_CHECK_CODE(kInconsistentOrientation, RAPS_ERROR_INCONSISTENT_ORIENTATION);
RAPS_CHECK_CODE(kIsolatedVertex, RAPS_ERROR_ISOLATED_VERTEX);
RAPS_CHECK_CODE(kMultipleComponents, RAPS_ERROR_MULTIPLE_COMPONENTS);
RAPS_CHECK_CODE(kNoBoundary, RAPS_ERROR_NO_BOUNDARY);
RAPS_CHECK_CODE(kMultipleBoundaries, RAPS_ERROR_MULTIPLE_BOUNDARIES);
RAPS_CHECK_CODE(kNonzeroGenus, RAPS_ERROR_NONZERO_GENUS);
RAPS_CHECK_CODE(kTooLarge, RAPS_ERROR_TOO_LARGE);
RAPS_CHECK_CODE(kCancelled, RAPS_ERROR_CANCELLED);
RAPS_CHECK_CODE(kSolverFailed, RAPS_ERROR_SOLVER_FAILED);
RAPS_CHECK_CODE(kInvalidOperation, RAPS_ERROR_INVALID_OPERATION);
RAPS_CHECK_CODE(kInternal, RAPS_ERROR_INTERNAL);
RAPS_CHECK_CODE(kOpenMesh, RAPS_ERROR_OPEN_MESH);
RAPS_CHECK_CODE(kInvalidTransform, RAPS_ERROR_INVALID_TRANSFORM);
RAPS_CHECK_CODE(kGroupCount, RAPS_ERROR_GROUP_COUNT);
RAPS_CHECK_CODE(kSeamNotAnEdge, RAPS_ERROR_SEAM_NOT_AN_EDGE);
RAPS_CHECK_CODE(kUvCount, RAPS_ERROR_UV_COUNT);
RAPS_CHECK_CODE(kNonFiniteUv, RAPS_ERROR_NON_FINITE_UV);
RAPS_CHECK_CODE(kDegenerateUvChart, RAPS_ERROR_DEGENERATE_UV_CHART);
#undef RAPS_CHECK_CODE

struct raps_mesh {
    raps::TriangleMesh mesh;
    Eigen::Matrix<double, 3, 4> transform = Eigen::Matrix<double, 3, 4>::Identity();
    bool indices_are_u16 = false;  // then at most 65536 vertices can be reached
    std::string last_error;
};

struct raps_progress_state {
    raps::ProgressState state;
};

// The message is mutable: a failing getter or copy, which takes a const handle, still stores
// its message in the handle, as the header promises for every failing call.
struct raps_settings {
    raps::Settings settings;
    raps_progress_fn progress = nullptr;
    void* progress_user = nullptr;
    raps_progress_state* progress_state = nullptr;  // the caller's
    mutable std::string last_error;
};

struct raps_result {
    raps::Parameterization map;
    bool has_map = false;
    mutable std::string last_error;
};

namespace {

using raps::Error;
using raps::ErrorCode;

constexpr int64_t kMaxElements = 0x7fffffff;  // int32 indexing inside the library
// Triangles accepted: the library's int32 arrays hold up to 8 entries per triangle (3 half-edges;
// a sparse system's diagonal plus 2 per edge, at most 6), so 2^28 keeps every one of them below
// 2^31. At 2^31 - 1, 3 half-edges per triangle overflowed int32 from 715,827,883 triangles on.
constexpr int64_t kMaxTriangles = int64_t{1} << 28;

// Stores a failure's message in a handle. Storing may need memory itself; when there is none,
// the handle gets a message that fits the string's inline buffer (no allocation), so that no
// exception ever leaves the catch blocks below and crosses the ABI (found by failing each
// allocation in turn: tests/test_alloc_failures.c).
void store_message(std::string* last_error, const char* message) {
    if (!last_error) return;
    try {
        *last_error = message;
    } catch (...) {
        last_error->assign("out of memory");  // 13 characters: within every std::string
    }
}

// What a successful call does to its handle's message: a call that may change the handle clears
// it; one on a const handle keeps it, so that it only reads the handle when it succeeds and
// concurrent successful calls on one const handle never write to it.
enum class OnSuccess { kClearMessage, kKeepMessage };

// Runs `body`, storing the message of any failure in `last_error`; never lets an exception
// cross the ABI.
template <typename Body>
raps_status guarded(std::string* last_error, Body&& body,
                    OnSuccess on_success = OnSuccess::kClearMessage) {
    try {
        body();
        if (last_error && on_success == OnSuccess::kClearMessage) last_error->clear();
        return RAPS_OK;
    } catch (const Error& error) {
        store_message(last_error, error.what());
        return static_cast<raps_status>(error.code());
    } catch (const std::bad_alloc&) {
        store_message(last_error, "out of memory");
        return RAPS_ERROR_OUT_OF_MEMORY;
    } catch (const std::exception& error) {
        try {
            store_message(last_error, (std::string("internal error: ") + error.what()).c_str());
        } catch (...) {
            store_message(last_error, "out of memory");
        }
        return RAPS_ERROR_INTERNAL;
    } catch (...) {
        store_message(last_error, "internal error: unknown exception");
        return RAPS_ERROR_INTERNAL;
    }
}

void require(bool condition, const char* message) {
    if (!condition) throw Error(ErrorCode::kInvalidArgument, message);
}

// The public parameters: name, inclusive bounds (for an enumeration every integer in them is a
// value) and the field of raps::Settings each reads and writes. A parameter's default is its
// field's initial value (core/settings.h), stated there only.
using raps::Settings;

template <auto Field>
int64_t read_int(const Settings& s) {
    return static_cast<int64_t>(s.*Field);
}

template <auto Field>
void write_int(Settings& s, int64_t v) {
    s.*Field = static_cast<std::decay_t<decltype(s.*Field)>>(v);
}

struct ParamInfo {
    raps_param id;
    const char* name;
    double min, max;
    int64_t (*get_int)(const Settings&);  // int parameters
    void (*set_int)(Settings&, int64_t);
    double Settings::*real;  // float parameters

    bool is_float() const { return real != nullptr; }
    double fallback() const {
        return is_float() ? Settings{}.*real : static_cast<double>(get_int(Settings{}));
    }
};

template <auto Field>
constexpr ParamInfo int_param(raps_param id, const char* name, double min, double max) {
    return {id, name, min, max, &read_int<Field>, &write_int<Field>, nullptr};
}

template <double Settings::*Field>
constexpr ParamInfo float_param(raps_param id, const char* name, double min, double max) {
    return {id, name, min, max, nullptr, nullptr, Field};
}

constexpr ParamInfo kParams[] = {
    int_param<&Settings::domain>(RAPS_PARAM_DOMAIN, "domain", RAPS_DOMAIN_DISK, RAPS_DOMAIN_ATLAS),
    int_param<&Settings::weights>(RAPS_PARAM_WEIGHTS, "weights", RAPS_WEIGHTS_MEAN_VALUE,
                                  RAPS_WEIGHTS_UNIFORM),
    int_param<&Settings::monitor>(RAPS_PARAM_MONITOR, "monitor", RAPS_MONITOR_NONE,
                                  RAPS_MONITOR_ANGLE),
    float_param<&Settings::alpha>(RAPS_PARAM_ALPHA, "alpha", 2.2250738585072014e-308, 100.0),
    int_param<&Settings::iterations>(RAPS_PARAM_ITERATIONS, "iterations", 1, 100),
    int_param<&Settings::iteration_mode>(RAPS_PARAM_ITERATION_MODE, "iteration_mode",
                                         RAPS_ITERATION_ACCUMULATE, RAPS_ITERATION_REAPPLY),
    int_param<&Settings::boundary>(RAPS_PARAM_BOUNDARY, "boundary", RAPS_BOUNDARY_CIRCLE,
                                   RAPS_BOUNDARY_SQUARE),
    int_param<&Settings::max_triangles>(RAPS_PARAM_MAX_TRIANGLES, "max_triangles", 1, kMaxElements),
    int_param<&Settings::threads>(RAPS_PARAM_THREADS, "threads", 0, 1024),
    int_param<&Settings::sphere_method>(RAPS_PARAM_SPHERE_METHOD, "sphere_method",
                                        RAPS_SPHERE_LITERAL, RAPS_SPHERE_ROBUST),
    int_param<&Settings::sphere_uv>(RAPS_PARAM_SPHERE_UV, "sphere_uv", RAPS_SPHERE_UV_NONE,
                                    RAPS_SPHERE_UV_OCTAHEDRAL),
    float_param<&Settings::sphere_damping>(RAPS_PARAM_SPHERE_DAMPING, "sphere_damping",
                                           2.2250738585072014e-308, 1.0),
    float_param<&Settings::sphere_tolerance>(RAPS_PARAM_SPHERE_TOLERANCE, "sphere_tolerance", 1e-12,
                                             1.0),
    int_param<&Settings::sphere_max_sweeps>(RAPS_PARAM_SPHERE_MAX_SWEEPS, "sphere_max_sweeps", 0,
                                            10000000),
    int_param<&Settings::sphere_alpha_steps>(RAPS_PARAM_SPHERE_ALPHA_STEPS, "sphere_alpha_steps", 1,
                                             100),
    int_param<&Settings::max_memory_mb>(RAPS_PARAM_MAX_MEMORY_MB, "max_memory_mb", 0, kMaxElements),
    int_param<&Settings::atlas_resolution>(RAPS_PARAM_ATLAS_RESOLUTION, "atlas_resolution", 16,
                                           16384),
    int_param<&Settings::atlas_padding>(RAPS_PARAM_ATLAS_PADDING, "atlas_padding", 0, 64),
    float_param<&Settings::weld_tolerance>(RAPS_PARAM_WELD_TOLERANCE, "weld_tolerance", 0.0,
                                           1.7976931348623157e308),
    float_param<&Settings::hard_edge_angle_deg>(RAPS_PARAM_HARD_EDGE_ANGLE, "hard_edge_angle", 0.0,
                                                180.0),
    float_param<&Settings::atlas_target_l2>(RAPS_PARAM_ATLAS_MAX_L2_STRETCH, "atlas_max_l2_stretch",
                                            1.0, 10.0),
    float_param<&Settings::atlas_max_linf>(RAPS_PARAM_ATLAS_MAX_LINF_STRETCH,
                                           "atlas_max_linf_stretch", 1.0, 1000.0),
    float_param<&Settings::atlas_texels_per_unit>(RAPS_PARAM_ATLAS_TEXELS_PER_UNIT,
                                                  "atlas_texels_per_unit", 0.0, 1e15),
    int_param<&Settings::atlas_max_width>(RAPS_PARAM_ATLAS_MAX_WIDTH, "atlas_max_width", 16, 16384),
    int_param<&Settings::atlas_max_height>(RAPS_PARAM_ATLAS_MAX_HEIGHT, "atlas_max_height", 16,
                                           16384),
    int_param<&Settings::atlas_rotation>(RAPS_PARAM_ATLAS_ROTATION, "atlas_rotation",
                                         RAPS_ROTATION_ANY, RAPS_ROTATION_NONE),
    int_param<&Settings::atlas_margin>(RAPS_PARAM_ATLAS_MARGIN, "atlas_margin", 0, 1024),
    int_param<&Settings::atlas_block_align>(RAPS_PARAM_ATLAS_BLOCK_ALIGN, "atlas_block_align", 0,
                                            1),
    int_param<&Settings::atlas_mesh_per_page>(RAPS_PARAM_ATLAS_MESH_PER_PAGE, "atlas_mesh_per_page",
                                              0, 1),
    int_param<&Settings::atlas_whole_texels>(RAPS_PARAM_ATLAS_WHOLE_TEXELS, "atlas_whole_texels", 0,
                                             1),
    int_param<&Settings::atlas_keep_input_seams>(RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS,
                                                 "atlas_keep_input_seams", 0, 1),
    int_param<&Settings::atlas_repack>(RAPS_PARAM_ATLAS_REPACK, "atlas_repack", 0, 1),
    int_param<&Settings::atlas_stack>(RAPS_PARAM_ATLAS_STACK, "atlas_stack", RAPS_STACK_NONE,
                                      RAPS_STACK_MIRRORED),
    float_param<&Settings::atlas_stack_tolerance>(RAPS_PARAM_ATLAS_STACK_TOLERANCE,
                                                  "atlas_stack_tolerance", 0.0, 0.1),
};

// A float as it was given, in as few digits as read back to the same double: %g's six digits
// printed 0.9999999 as "1" next to the bound [1, 10], and std::to_string -1e-9 as "-0.000000".
std::string exact_text(double value) {
    char text[32];
    for (int digits = 6; digits <= 17; ++digits) {
        std::snprintf(text, sizeof(text), "%.*g", digits, value);
        if (std::strtod(text, nullptr) == value) break;
    }
    return text;
}

// "(0, 100]" or "[0, 1e+15]": a float parameter's bounds for a message (a lower bound of the
// smallest normal double means "positive"; a lower bound of 0 is accepted, so it is closed).
std::string float_bounds(const ParamInfo& info) {
    if (info.min > 0 && info.min <= 2.2250738585072014e-308)
        return "(0, " + exact_text(info.max) + "]";
    return "[" + exact_text(info.min) + ", " + exact_text(info.max) + "]";
}

const ParamInfo* find_param(raps_param id) {
    for (const ParamInfo& info : kParams) {
        if (info.id == id) return &info;
    }
    return nullptr;
}

const ParamInfo& checked_param(raps_param id, bool want_float) {
    const ParamInfo* info = find_param(id);
    if (!info) {
        throw Error(ErrorCode::kInvalidArgument, "unknown parameter " + std::to_string(id));
    }
    if (info->is_float() != want_float) {
        throw Error(ErrorCode::kInvalidArgument,
                    std::string("parameter ") + info->name + " is " +
                        (info->is_float() ? "a float: use raps_settings_set_float/get_float"
                                          : "an int: use raps_settings_set_int/get_int"));
    }
    return *info;
}

// Coordinates beyond this are refused like non-finite ones: the algorithms multiply up to a few
// coordinates together (areas, squared areas, products of edge vectors), and a product of four
// overflows a double once coordinates pass about 1e77; 1e30 keeps every such product finite with
// a wide margin and lies far beyond any real mesh (fuzzing found coordinates near 1e151, 1e191
// and 1e307 turning areas infinite and the statistics and atlas packing into NaN).
constexpr double kMaxCoordinate = 1e30;

// Reads `count` points of three coordinates of type T at `stride` bytes into doubles, refusing
// non-finite and huge values. memcpy because the caller's data need not be aligned.
template <typename T>
void read_positions(raps_mesh* mesh, const T* xyz, size_t count, size_t stride) {
    require(mesh != nullptr, "mesh is NULL");
    require(xyz != nullptr, "positions pointer is NULL");
    if (count == 0) throw Error(ErrorCode::kEmptyMesh, "vertex_count is 0");
    if (count > static_cast<size_t>(kMaxElements)) {
        throw Error(ErrorCode::kTooLarge, "vertex_count " + std::to_string(count) +
                                              " is too large (raps accepts at most 2^31 - 1)");
    }
    if (stride == 0) stride = 3 * sizeof(T);
    if (stride < 3 * sizeof(T)) {
        throw Error(ErrorCode::kInvalidArgument, "stride_bytes " + std::to_string(stride) +
                                                     " is smaller than one point (" +
                                                     std::to_string(3 * sizeof(T)) + " bytes)");
    }
    // The last point ends at (count - 1) * stride + one point: that must be an address.
    if (count > 1 && stride > (SIZE_MAX - 3 * sizeof(T)) / (count - 1)) {
        throw Error(ErrorCode::kInvalidArgument,
                    "vertex_count " + std::to_string(count) + " points at stride_bytes " +
                        std::to_string(stride) + " span more bytes than an address can reach");
    }
    std::vector<Eigen::Vector3d> positions(count);
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(xyz);
    for (size_t i = 0; i < count; ++i) {
        T point[3];
        std::memcpy(point, bytes + i * stride, sizeof(point));
        for (int c = 0; c < 3; ++c) {
            const double value = static_cast<double>(point[c]);
            if (!(std::abs(value) <= kMaxCoordinate)) {  // also NaN
                char text[32];
                std::snprintf(text, sizeof(text), "%g", value);
                throw Error(ErrorCode::kNonFinitePosition,
                            "vertex " + std::to_string(i) +
                                (std::isfinite(value) ? " has a coordinate beyond 1e30 ("
                                                      : " has a non-finite coordinate (") +
                                text + ")");
            }
            positions[i][c] = value;
        }
    }
    mesh->mesh.positions = std::move(positions);
}

// Reads `count` uv pairs of type T at `stride` bytes into doubles, refusing non-finite and huge
// values as positions are refused; NULL with 0 removes them.
template <typename T>
void read_corner_uvs(raps_mesh* mesh, const T* uv, size_t count, size_t stride) {
    require(mesh != nullptr, "mesh is NULL");
    require(uv != nullptr || count == 0, "uv pointer is NULL");
    if (count > static_cast<size_t>(3 * kMaxTriangles)) {
        throw Error(ErrorCode::kTooLarge, "corner_count " + std::to_string(count) +
                                              " is more than the corners of the largest mesh "
                                              "raps accepts (3 * 2^28)");
    }
    if (stride == 0) stride = 2 * sizeof(T);
    if (stride < 2 * sizeof(T)) {
        throw Error(ErrorCode::kInvalidArgument, "stride_bytes " + std::to_string(stride) +
                                                     " is smaller than one uv pair (" +
                                                     std::to_string(2 * sizeof(T)) + " bytes)");
    }
    if (count > 1 && stride > (SIZE_MAX - 2 * sizeof(T)) / (count - 1)) {
        throw Error(ErrorCode::kInvalidArgument,
                    "corner_count " + std::to_string(count) + " pairs at stride_bytes " +
                        std::to_string(stride) + " span more bytes than an address can reach");
    }
    std::vector<Eigen::Vector2d> corner_uv(count);
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(uv);
    for (size_t i = 0; i < count; ++i) {
        T pair[2];
        std::memcpy(pair, bytes + i * stride, sizeof(pair));
        for (int c = 0; c < 2; ++c) {
            const double value = static_cast<double>(pair[c]);
            if (!(std::abs(value) <= kMaxCoordinate)) {  // also NaN
                char text[32];
                std::snprintf(text, sizeof(text), "%g", value);
                throw Error(ErrorCode::kNonFiniteUv,
                            "corner " + std::to_string(i) + " (triangle " + std::to_string(i / 3) +
                                ") has a uv " +
                                (std::isfinite(value) ? "beyond 1e30 (" : "that is not finite (") +
                                text + ")");
            }
            corner_uv[i][c] = value;
        }
    }
    mesh->mesh.corner_uv = std::move(corner_uv);
}

template <typename T>
void read_indices(raps_mesh* mesh, const T* indices, size_t count) {
    require(mesh != nullptr, "mesh is NULL");
    require(indices != nullptr, "indices pointer is NULL");
    if (count == 0) throw Error(ErrorCode::kEmptyMesh, "index_count is 0");
    if (count % 3 != 0) {
        throw Error(ErrorCode::kIndexCount,
                    "index_count " + std::to_string(count) + " is not a multiple of 3");
    }
    if (count / 3 > static_cast<size_t>(kMaxTriangles)) {
        throw Error(ErrorCode::kTooLarge, "index_count " + std::to_string(count) +
                                              " makes too many triangles (raps accepts at most "
                                              "2^28 = 268435456)");
    }
    std::vector<raps::Triangle> triangles(count / 3);
    for (size_t i = 0; i < count; ++i) {
        if (static_cast<uint64_t>(indices[i]) > static_cast<uint64_t>(kMaxElements)) {
            throw Error(ErrorCode::kIndexOutOfRange,
                        "index " + std::to_string(i) + " is " + std::to_string(indices[i]) +
                            ", beyond any vertex raps accepts (at most 2^31 - 1 vertices)");
        }
        triangles[i / 3][i % 3] = static_cast<int32_t>(indices[i]);
    }
    mesh->mesh.triangles = std::move(triangles);
    mesh->indices_are_u16 = sizeof(T) == 2;
}

// Copies per-output-vertex vectors of N coordinates (uvs, sphere points) as T at `stride` bytes.
template <typename T, int N>
void copy_points(const raps_result* result, const std::vector<Eigen::Matrix<double, N, 1>>& points,
                 T* dst, size_t capacity, size_t stride, const char* what) {
    require(dst != nullptr, "dst is NULL");
    if (stride == 0) stride = N * sizeof(T);
    if (stride < N * sizeof(T)) {
        throw Error(ErrorCode::kInvalidArgument,
                    std::string("stride_bytes is smaller than one of the ") + what);
    }
    const size_t count = result->map.vertex_remap.size();
    if (capacity < count) {
        throw Error(ErrorCode::kInvalidArgument, "capacity " + std::to_string(capacity) +
                                                     " is smaller than the " +
                                                     std::to_string(count) + " output vertices");
    }
    // The last one ends at (count - 1) * stride + one vector: that must be an address.
    if (count > 1 && stride > (SIZE_MAX - N * sizeof(T)) / (count - 1)) {
        throw Error(ErrorCode::kInvalidArgument, "stride_bytes " + std::to_string(stride) +
                                                     " spreads the " + std::to_string(count) +
                                                     " output vertices beyond any address");
    }
    unsigned char* bytes = reinterpret_cast<unsigned char*>(dst);
    for (size_t i = 0; i < points.size(); ++i) {
        T point[N];
        for (int c = 0; c < N; ++c) point[c] = static_cast<T>(points[i][c]);
        std::memcpy(bytes + i * stride, point, sizeof(point));
    }
}

template <typename T>
void copy_uvs(const raps_result* result, T* dst, size_t capacity, size_t stride) {
    require(result != nullptr, "result is NULL");
    if (!result->has_map) throw Error(ErrorCode::kInvalidOperation, "the result holds no map");
    if (result->map.uv.empty()) {
        throw Error(ErrorCode::kInvalidOperation,
                    "the result holds no uvs: a sphere map has them only with "
                    "RAPS_SPHERE_UV_OCTAHEDRAL (read its points with "
                    "raps_result_copy_sphere_points_*)");
    }
    copy_points<T, 2>(result, result->map.uv, dst, capacity, stride, "uv pairs");
}

template <typename T>
void copy_sphere_points(const raps_result* result, T* dst, size_t capacity, size_t stride) {
    require(result != nullptr, "result is NULL");
    if (!result->has_map) throw Error(ErrorCode::kInvalidOperation, "the result holds no map");
    if (result->map.sphere_points.empty()) {
        throw Error(ErrorCode::kInvalidOperation,
                    "the result holds no sphere points (only RAPS_DOMAIN_SPHERE has them)");
    }
    copy_points<T, 3>(result, result->map.sphere_points, dst, capacity, stride, "points");
}

void copy_u32(const raps_result* result, const std::vector<uint32_t>& source, uint32_t* dst,
              size_t capacity, const char* what) {
    require(dst != nullptr, "dst is NULL");
    if (!result->has_map) throw Error(ErrorCode::kInvalidOperation, "the result holds no map");
    if (capacity < source.size()) {
        throw Error(ErrorCode::kInvalidArgument, "capacity " + std::to_string(capacity) +
                                                     " is smaller than the " +
                                                     std::to_string(source.size()) + " " + what);
    }
    std::copy(source.begin(), source.end(), dst);
}

// Fills the fields of raps_stats that fit the caller's struct_size (an older caller's struct
// is shorter).
void copy_stats(const raps::Parameterization& map, raps_stats* stats) {
    raps_stats full;
    std::memset(&full, 0, sizeof(full));
    full.struct_size = static_cast<uint32_t>(std::min<size_t>(stats->struct_size, sizeof(full)));
    full.vertex_count = map.vertex_remap.size();
    full.triangle_count = map.indices.size() / 3;
    full.flipped_triangles = static_cast<uint64_t>(map.distortion.flipped_triangles);
    full.zero_area_triangles = static_cast<uint64_t>(map.distortion.zero_area_triangles);
    full.negative_weights = static_cast<uint64_t>(map.negative_weights);
    full.adaptive_solves = static_cast<uint64_t>(map.adaptive_solves);
    full.area_log_mean = map.distortion.area_log_mean;
    full.area_max = map.distortion.area_max;
    full.angle_mean_deg = map.distortion.angle_mean_deg;
    full.angle_max_deg = map.distortion.angle_max_deg;
    full.stretch_l2 = map.distortion.stretch_l2;
    full.stretch_linf = map.distortion.stretch_linf;
    full.chart_count = static_cast<uint64_t>(map.chart_count);
    full.atlas_width = static_cast<uint64_t>(map.atlas_width);
    full.atlas_height = static_cast<uint64_t>(map.atlas_height);
    full.utilization = map.utilization;
    full.relaxation_sweeps = static_cast<uint64_t>(map.relaxation_sweeps);
    full.threads_used = static_cast<uint64_t>(map.threads_used);
    if (!map.charts.empty()) {
        full.page_count = static_cast<uint64_t>(map.page_count);
        for (const raps::AtlasChartRecord& chart : map.charts)
            full.scaled_down_charts += chart.scaled_down ? 1 : 0;
        full.texels_per_unit = map.texels_per_unit;
    }
    // Only what fits the caller's (possibly older, shorter) struct.
    std::memcpy(stats, &full, full.struct_size);
}

// A transform that would flatten the mesh (or is not a number) has no world units to measure
// texels in. The bound is Hadamard's: |det A| <= the product of A's rows' lengths.
Eigen::Matrix<double, 3, 4> checked_transform(const double* m) {
    Eigen::Matrix<double, 3, 4> transform;
    for (int i = 0; i < 12; ++i) {
        if (!std::isfinite(m[i])) {
            char text[32];
            std::snprintf(text, sizeof(text), "%g", m[i]);
            throw Error(ErrorCode::kInvalidTransform,
                        "transform coefficient m[" + std::to_string(i) + "] is " + text);
        }
        transform(i / 4, i % 4) = m[i];
    }
    // Measured on the 3x3 part scaled to coefficients of at most 1: a scale of 1e120 cubed
    // overflowed the determinant and the bound alike (inf > inf is false) and read as singular.
    // Positions the transform takes past 1e30 are refused with the mesh (scene_mesh.cpp).
    const double largest = transform.leftCols<3>().cwiseAbs().maxCoeff();
    const Eigen::Matrix3d linear =
        largest > 0 ? Eigen::Matrix3d(transform.leftCols<3>() / largest) : Eigen::Matrix3d::Zero();
    const double rows = linear.row(0).norm() * linear.row(1).norm() * linear.row(2).norm();
    if (!(std::abs(linear.determinant()) > 1e-12 * rows)) {
        throw Error(ErrorCode::kInvalidTransform,
                    "the transform's 3x3 part is singular: it would flatten the mesh");
    }
    return transform;
}

// Fills the fields of raps_chart that fit the caller's struct_size.
void copy_chart(const raps::AtlasChartRecord& record, size_t index, raps_chart* chart) {
    raps_chart full;
    std::memset(&full, 0, sizeof(full));
    full.struct_size = static_cast<uint32_t>(std::min<size_t>(chart->struct_size, sizeof(full)));
    full.mesh = static_cast<uint32_t>(record.part);
    full.page = static_cast<uint32_t>(record.page);
    full.flags = (record.scaled_down ? static_cast<uint32_t>(RAPS_CHART_SCALED_DOWN) : 0u) |
                 (record.stacked_on != static_cast<int64_t>(index)
                      ? static_cast<uint32_t>(RAPS_CHART_STACKED)
                      : 0u);
    full.stacked_on = static_cast<uint32_t>(record.stacked_on);
    full.x = static_cast<uint32_t>(record.x);
    full.y = static_cast<uint32_t>(record.y);
    full.width = static_cast<uint32_t>(record.width);
    full.height = static_cast<uint32_t>(record.height);
    full.rotation_deg = record.rotation_deg;
    full.triangle_count = static_cast<uint64_t>(record.triangle_count);
    full.area_3d = record.area_3d;
    full.area_texels = record.area_texels;
    full.stretch_l2 = record.stretch_l2;
    std::memcpy(chart, &full, full.struct_size);
}

// The progress callback of `settings` (none for NULL) as the library takes it.
raps::Progress::Callback progress_of(const raps_settings* settings) {
    raps::Progress::Callback callback;
    if (settings && settings->progress) {
        const raps_progress_fn fn = settings->progress;
        void* user = settings->progress_user;
        callback = [fn, user](raps::Phase phase, double fraction) {
            return fn(user, static_cast<raps_phase>(phase), fraction) != 0;
        };
    }
    return callback;
}

raps::ProgressState* state_of(const raps_settings* settings) {
    return settings && settings->progress_state ? &settings->progress_state->state : nullptr;
}

void check_u16_reach(const raps_mesh* mesh, const std::string& name) {
    if (mesh->indices_are_u16 && mesh->mesh.positions.size() > 65536) {
        throw Error(ErrorCode::kTooLarge, name + " has " +
                                              std::to_string(mesh->mesh.positions.size()) +
                                              " vertices but uint16 indices reach only 65536; use "
                                              "raps_mesh_set_indices_u32");
    }
}

// guarded() for a call on a const handle: a failure's message goes into the handle (none for
// NULL), a success leaves the message as it was.
template <typename Handle, typename Body>
raps_status guarded_read(const Handle* handle, Body&& body) {
    return guarded(handle ? &handle->last_error : nullptr, std::forward<Body>(body),
                   OnSuccess::kKeepMessage);
}

const char* message_of(const std::string* last_error) {
    return last_error ? last_error->c_str() : "the handle is NULL";
}

}  // namespace

extern "C" {

uint32_t raps_version(void) {
    return RAPS_VERSION;
}

const char* raps_version_string(void) {
#define RAPS_STRINGIFY2(x) #x
#define RAPS_STRINGIFY(x) RAPS_STRINGIFY2(x)
    return RAPS_STRINGIFY(RAPS_VERSION_MAJOR) "." RAPS_STRINGIFY(
        RAPS_VERSION_MINOR) "." RAPS_STRINGIFY(RAPS_VERSION_PATCH);
#undef RAPS_STRINGIFY
#undef RAPS_STRINGIFY2
}

const char* raps_status_string(raps_status status) {
    switch (status) {
        case RAPS_OK:
            return "ok";
        case RAPS_ERROR_INVALID_ARGUMENT:
            return "invalid argument";
        case RAPS_ERROR_OUT_OF_MEMORY:
            return "out of memory";
        case RAPS_ERROR_EMPTY_MESH:
            return "empty mesh";
        case RAPS_ERROR_INDEX_COUNT:
            return "index count is not a multiple of 3";
        case RAPS_ERROR_INDEX_OUT_OF_RANGE:
            return "index out of range";
        case RAPS_ERROR_NON_FINITE_POSITION:
            return "non-finite position";
        case RAPS_ERROR_REPEATED_VERTEX:
            return "triangle with a repeated vertex";
        case RAPS_ERROR_ZERO_AREA_TRIANGLE:
            return "zero-area triangle";
        case RAPS_ERROR_NON_MANIFOLD_EDGE:
            return "non-manifold edge";
        case RAPS_ERROR_NON_MANIFOLD_VERTEX:
            return "non-manifold vertex";
        case RAPS_ERROR_INCONSISTENT_ORIENTATION:
            return "inconsistent triangle orientation";
        case RAPS_ERROR_ISOLATED_VERTEX:
            return "isolated vertex";
        case RAPS_ERROR_MULTIPLE_COMPONENTS:
            return "several connected components";
        case RAPS_ERROR_NO_BOUNDARY:
            return "no boundary";
        case RAPS_ERROR_MULTIPLE_BOUNDARIES:
            return "more than one boundary loop";
        case RAPS_ERROR_NONZERO_GENUS:
            return "genus greater than zero";
        case RAPS_ERROR_TOO_LARGE:
            return "mesh too large";
        case RAPS_ERROR_CANCELLED:
            return "cancelled";
        case RAPS_ERROR_SOLVER_FAILED:
            return "solver failed";
        case RAPS_ERROR_INVALID_OPERATION:
            return "invalid operation";
        case RAPS_ERROR_INTERNAL:
            return "internal error";
        case RAPS_ERROR_OPEN_MESH:
            return "open mesh (the sphere domain needs a closed one)";
        case RAPS_ERROR_INVALID_TRANSFORM:
            return "invalid transform";
        case RAPS_ERROR_GROUP_COUNT:
            return "triangle group count differs from the triangle count";
        case RAPS_ERROR_SEAM_NOT_AN_EDGE:
            return "seam edge is not an edge of the mesh";
        case RAPS_ERROR_UV_COUNT:
            return "corner uv count differs from three per triangle";
        case RAPS_ERROR_NON_FINITE_UV:
            return "non-finite uv";
        case RAPS_ERROR_DEGENERATE_UV_CHART:
            return "uv chart with zero area";
        default:
            return "unknown status";
    }
}

raps_status raps_mesh_create(raps_mesh** out_mesh) {
    if (!out_mesh) return RAPS_ERROR_INVALID_ARGUMENT;
    *out_mesh = nullptr;
    return guarded(nullptr, [&] { *out_mesh = new raps_mesh(); });
}

void raps_mesh_destroy(raps_mesh* mesh) {
    delete mesh;
}

raps_status raps_mesh_set_positions_f32(raps_mesh* mesh, const float* xyz, size_t vertex_count,
                                        size_t stride_bytes) {
    return guarded(mesh ? &mesh->last_error : nullptr,
                   [&] { read_positions(mesh, xyz, vertex_count, stride_bytes); });
}

raps_status raps_mesh_set_positions_f64(raps_mesh* mesh, const double* xyz, size_t vertex_count,
                                        size_t stride_bytes) {
    return guarded(mesh ? &mesh->last_error : nullptr,
                   [&] { read_positions(mesh, xyz, vertex_count, stride_bytes); });
}

raps_status raps_mesh_set_indices_u16(raps_mesh* mesh, const uint16_t* indices,
                                      size_t index_count) {
    return guarded(mesh ? &mesh->last_error : nullptr,
                   [&] { read_indices(mesh, indices, index_count); });
}

raps_status raps_mesh_set_indices_u32(raps_mesh* mesh, const uint32_t* indices,
                                      size_t index_count) {
    return guarded(mesh ? &mesh->last_error : nullptr,
                   [&] { read_indices(mesh, indices, index_count); });
}

raps_status raps_mesh_set_transform(raps_mesh* mesh, const double* m) {
    return guarded(mesh ? &mesh->last_error : nullptr, [&] {
        require(mesh != nullptr, "mesh is NULL");
        mesh->transform = m ? checked_transform(m) : Eigen::Matrix<double, 3, 4>::Identity();
    });
}

raps_status raps_mesh_set_triangle_groups(raps_mesh* mesh, const uint32_t* groups,
                                          size_t triangle_count) {
    return guarded(mesh ? &mesh->last_error : nullptr, [&] {
        require(mesh != nullptr, "mesh is NULL");
        require(groups != nullptr || triangle_count == 0, "groups is NULL");
        if (triangle_count > static_cast<size_t>(kMaxTriangles)) {
            throw Error(ErrorCode::kTooLarge, "triangle_count " + std::to_string(triangle_count) +
                                                  " is more than raps accepts (2^28)");
        }
        mesh->mesh.triangle_group.assign(groups, groups + triangle_count);
    });
}

raps_status raps_mesh_set_triangle_polygons(raps_mesh* mesh, const uint32_t* polygons,
                                            size_t triangle_count) {
    return guarded(mesh ? &mesh->last_error : nullptr, [&] {
        require(mesh != nullptr, "mesh is NULL");
        require(polygons != nullptr || triangle_count == 0, "polygons is NULL");
        if (triangle_count > static_cast<size_t>(kMaxTriangles)) {
            throw Error(ErrorCode::kTooLarge, "triangle_count " + std::to_string(triangle_count) +
                                                  " is more than raps accepts (2^28)");
        }
        mesh->mesh.triangle_polygon.assign(polygons, polygons + triangle_count);
    });
}

raps_status raps_mesh_set_seam_edges(raps_mesh* mesh, const uint32_t* vertex_pairs,
                                     size_t edge_count) {
    return guarded(mesh ? &mesh->last_error : nullptr, [&] {
        require(mesh != nullptr, "mesh is NULL");
        require(vertex_pairs != nullptr || edge_count == 0, "vertex_pairs is NULL");
        if (edge_count > static_cast<size_t>(3 * kMaxTriangles)) {
            throw Error(ErrorCode::kTooLarge, "edge_count " + std::to_string(edge_count) +
                                                  " is more than the edges of the largest mesh "
                                                  "raps accepts (3 * 2^28)");
        }
        std::vector<std::array<uint32_t, 2>> edges(edge_count);
        for (size_t i = 0; i < edge_count; ++i)
            edges[i] = {vertex_pairs[2 * i], vertex_pairs[2 * i + 1]};
        mesh->mesh.seam_edges = std::move(edges);
    });
}

raps_status raps_mesh_set_corner_uvs_f32(raps_mesh* mesh, const float* uv, size_t corner_count,
                                         size_t stride_bytes) {
    return guarded(mesh ? &mesh->last_error : nullptr,
                   [&] { read_corner_uvs(mesh, uv, corner_count, stride_bytes); });
}

raps_status raps_mesh_set_corner_uvs_f64(raps_mesh* mesh, const double* uv, size_t corner_count,
                                         size_t stride_bytes) {
    return guarded(mesh ? &mesh->last_error : nullptr,
                   [&] { read_corner_uvs(mesh, uv, corner_count, stride_bytes); });
}

size_t raps_mesh_vertex_count(const raps_mesh* mesh) {
    return mesh ? mesh->mesh.positions.size() : 0;
}

size_t raps_mesh_triangle_count(const raps_mesh* mesh) {
    return mesh ? mesh->mesh.triangles.size() : 0;
}

const char* raps_mesh_last_error(const raps_mesh* mesh) {
    return message_of(mesh ? &mesh->last_error : nullptr);
}

raps_status raps_settings_create(raps_settings** out_settings) {
    if (!out_settings) return RAPS_ERROR_INVALID_ARGUMENT;
    *out_settings = nullptr;
    return guarded(nullptr, [&] { *out_settings = new raps_settings(); });
}

raps_status raps_settings_clone(const raps_settings* settings, raps_settings** out_settings) {
    if (!out_settings) return RAPS_ERROR_INVALID_ARGUMENT;
    *out_settings = nullptr;
    if (!settings) return RAPS_ERROR_INVALID_ARGUMENT;
    return guarded_read(settings, [&] {
        *out_settings = new raps_settings(*settings);
        (*out_settings)->last_error.clear();
    });
}

void raps_settings_destroy(raps_settings* settings) {
    delete settings;
}

raps_status raps_settings_set_int(raps_settings* settings, raps_param param, int64_t value) {
    return guarded(settings ? &settings->last_error : nullptr, [&] {
        require(settings != nullptr, "settings is NULL");
        const ParamInfo& info = checked_param(param, false);
        if (static_cast<double>(value) < info.min || static_cast<double>(value) > info.max) {
            throw Error(ErrorCode::kInvalidArgument,
                        std::string("value ") + std::to_string(value) + " of parameter " +
                            info.name + " is outside [" + std::to_string(int64_t(info.min)) + ", " +
                            std::to_string(int64_t(info.max)) + "]");
        }
        info.set_int(settings->settings, value);
    });
}

raps_status raps_settings_set_float(raps_settings* settings, raps_param param, double value) {
    return guarded(settings ? &settings->last_error : nullptr, [&] {
        require(settings != nullptr, "settings is NULL");
        const ParamInfo& info = checked_param(param, true);
        if (!(value >= info.min && value <= info.max)) {  // also refuses NaN
            throw Error(ErrorCode::kInvalidArgument, "value " + exact_text(value) +
                                                         " of parameter " + info.name +
                                                         " is outside " + float_bounds(info));
        }
        settings->settings.*info.real = value;
    });
}

raps_status raps_settings_get_int(const raps_settings* settings, raps_param param,
                                  int64_t* out_value) {
    return guarded_read(settings, [&] {
        require(settings != nullptr && out_value != nullptr, "NULL pointer");
        *out_value = checked_param(param, false).get_int(settings->settings);
    });
}

raps_status raps_settings_get_float(const raps_settings* settings, raps_param param,
                                    double* out_value) {
    return guarded_read(settings, [&] {
        require(settings != nullptr && out_value != nullptr, "NULL pointer");
        *out_value = settings->settings.*checked_param(param, true).real;
    });
}

raps_status raps_param_info(raps_param param, const char** out_name, int32_t* out_is_float,
                            double* out_min, double* out_max, double* out_default) {
    const ParamInfo* info = find_param(param);
    if (!info) return RAPS_ERROR_INVALID_ARGUMENT;
    if (out_name) *out_name = info->name;
    if (out_is_float) *out_is_float = info->is_float() ? 1 : 0;
    if (out_min) *out_min = info->min;
    if (out_max) *out_max = info->max;
    if (out_default) *out_default = info->fallback();
    return RAPS_OK;
}

raps_status raps_settings_set_progress(raps_settings* settings, raps_progress_fn fn, void* user) {
    if (!settings) return RAPS_ERROR_INVALID_ARGUMENT;
    settings->progress = fn;
    settings->progress_user = user;
    settings->last_error.clear();
    return RAPS_OK;
}

raps_status raps_settings_set_progress_state(raps_settings* settings, raps_progress_state* state) {
    if (!settings) return RAPS_ERROR_INVALID_ARGUMENT;
    settings->progress_state = state;
    settings->last_error.clear();
    return RAPS_OK;
}

raps_status raps_progress_state_create(raps_progress_state** out_state) {
    if (!out_state) return RAPS_ERROR_INVALID_ARGUMENT;
    *out_state = nullptr;
    return guarded(nullptr, [&] { *out_state = new raps_progress_state(); });
}

void raps_progress_state_destroy(raps_progress_state* state) {
    delete state;
}

raps_status raps_progress_state_read(const raps_progress_state* state, raps_phase* out_phase,
                                     double* out_fraction, int64_t* out_reports) {
    if (!state) return RAPS_ERROR_INVALID_ARGUMENT;
    const raps::ProgressState::Reading reading = state->state.read();
    if (out_phase) *out_phase = reading.phase;
    if (out_fraction) *out_fraction = reading.fraction;
    if (out_reports) *out_reports = reading.reports;
    return RAPS_OK;
}

raps_status raps_progress_state_cancel(raps_progress_state* state) {
    if (!state) return RAPS_ERROR_INVALID_ARGUMENT;
    state->state.cancel();
    return RAPS_OK;
}

raps_status raps_progress_state_reset(raps_progress_state* state) {
    if (!state) return RAPS_ERROR_INVALID_ARGUMENT;
    state->state.reset();
    return RAPS_OK;
}

const char* raps_settings_last_error(const raps_settings* settings) {
    return message_of(settings ? &settings->last_error : nullptr);
}

raps_status raps_result_create(raps_result** out_result) {
    if (!out_result) return RAPS_ERROR_INVALID_ARGUMENT;
    *out_result = nullptr;
    return guarded(nullptr, [&] { *out_result = new raps_result(); });
}

void raps_result_destroy(raps_result* result) {
    delete result;
}

raps_status raps_parameterize(const raps_mesh* mesh, const raps_settings* settings,
                              raps_result* result) {
    if (!result) return RAPS_ERROR_INVALID_ARGUMENT;
    result->has_map = false;
    result->map = raps::Parameterization();
    return guarded(&result->last_error, [&] {
        require(mesh != nullptr, "mesh is NULL");
        check_u16_reach(mesh, "the mesh");
        const raps::Settings defaults;
        const raps::Settings& chosen = settings ? settings->settings : defaults;
        const raps::Progress progress(progress_of(settings), state_of(settings));
        result->map = raps::parameterize(mesh->mesh, chosen, progress);
        result->has_map = true;
    });
}

raps_status raps_parameterize_scene(const raps_mesh* const* meshes, size_t mesh_count,
                                    const raps_settings* settings, raps_result* result) {
    if (!result) return RAPS_ERROR_INVALID_ARGUMENT;
    result->has_map = false;
    result->map = raps::Parameterization();
    return guarded(&result->last_error, [&] {
        require(meshes != nullptr || mesh_count == 0, "meshes is NULL");
        require(settings != nullptr,
                "settings is NULL: a scene needs settings with RAPS_PARAM_DOMAIN = "
                "RAPS_DOMAIN_ATLAS");
        std::vector<raps::ScenePart> parts(mesh_count);
        for (size_t i = 0; i < mesh_count; ++i) {
            const std::string name = "meshes[" + std::to_string(i) + "]";
            if (!meshes[i]) throw Error(ErrorCode::kInvalidArgument, name + " is NULL");
            check_u16_reach(meshes[i], name);
            parts[i].mesh = &meshes[i]->mesh;
            parts[i].transform = meshes[i]->transform;
        }
        const raps::Progress progress(progress_of(settings), state_of(settings));
        result->map = raps::parameterize_scene(parts, settings->settings, progress);
        result->has_map = true;
    });
}

const char* raps_result_last_error(const raps_result* result) {
    return message_of(result ? &result->last_error : nullptr);
}

size_t raps_result_vertex_count(const raps_result* result) {
    return result && result->has_map ? result->map.vertex_remap.size() : 0;
}

size_t raps_result_index_count(const raps_result* result) {
    return result && result->has_map ? result->map.indices.size() : 0;
}

raps_status raps_result_copy_uvs_f32(const raps_result* result, float* dst, size_t capacity,
                                     size_t stride_bytes) {
    return guarded_read(result, [&] { copy_uvs(result, dst, capacity, stride_bytes); });
}

raps_status raps_result_copy_uvs_f64(const raps_result* result, double* dst, size_t capacity,
                                     size_t stride_bytes) {
    return guarded_read(result, [&] { copy_uvs(result, dst, capacity, stride_bytes); });
}

raps_status raps_result_copy_sphere_points_f32(const raps_result* result, float* dst,
                                               size_t capacity, size_t stride_bytes) {
    return guarded_read(result, [&] { copy_sphere_points(result, dst, capacity, stride_bytes); });
}

raps_status raps_result_copy_sphere_points_f64(const raps_result* result, double* dst,
                                               size_t capacity, size_t stride_bytes) {
    return guarded_read(result, [&] { copy_sphere_points(result, dst, capacity, stride_bytes); });
}

size_t raps_result_mesh_count(const raps_result* result) {
    return result && result->has_map ? result->map.ranges.size() : 0;
}

raps_status raps_result_mesh_range(const raps_result* result, size_t mesh, uint64_t* first_vertex,
                                   uint64_t* vertex_count, uint64_t* first_index,
                                   uint64_t* index_count) {
    return guarded_read(result, [&] {
        require(result != nullptr, "result is NULL");
        if (!result->has_map) throw Error(ErrorCode::kInvalidOperation, "the result holds no map");
        const std::vector<raps::OutputRange>& ranges = result->map.ranges;
        if (mesh >= ranges.size()) {
            throw Error(ErrorCode::kInvalidArgument,
                        "mesh " + std::to_string(mesh) + " is out of range: the result holds " +
                            std::to_string(ranges.size()) + " mesh(es)");
        }
        const raps::OutputRange& range = ranges[mesh];
        if (first_vertex) *first_vertex = static_cast<uint64_t>(range.first_vertex);
        if (vertex_count) *vertex_count = static_cast<uint64_t>(range.vertex_count);
        if (first_index) *first_index = static_cast<uint64_t>(range.first_index);
        if (index_count) *index_count = static_cast<uint64_t>(range.index_count);
    });
}

raps_status raps_result_get_chart(const raps_result* result, size_t index, raps_chart* chart) {
    return guarded_read(result, [&] {
        require(result != nullptr, "result is NULL");
        require(chart != nullptr, "chart is NULL");
        if (chart->struct_size < 8) {
            throw Error(ErrorCode::kInvalidArgument,
                        "chart->struct_size " + std::to_string(chart->struct_size) +
                            " is below 8: set it to sizeof(raps_chart)");
        }
        if (!result->has_map || result->map.charts.empty()) {
            throw Error(ErrorCode::kInvalidOperation,
                        "the result holds no atlas (only RAPS_DOMAIN_ATLAS has chart records)");
        }
        const std::vector<raps::AtlasChartRecord>& charts = result->map.charts;
        if (index >= charts.size()) {
            throw Error(ErrorCode::kInvalidArgument, "chart " + std::to_string(index) +
                                                         " is out of range: the atlas has " +
                                                         std::to_string(charts.size()) + " charts");
        }
        copy_chart(charts[index], index, chart);
    });
}

raps_status raps_result_copy_indices_u32(const raps_result* result, uint32_t* dst,
                                         size_t capacity) {
    return guarded_read(result, [&] {
        require(result != nullptr, "result is NULL");
        copy_u32(result, result->map.indices, dst, capacity, "indices");
    });
}

raps_status raps_result_copy_vertex_remap(const raps_result* result, uint32_t* dst,
                                          size_t capacity) {
    return guarded_read(result, [&] {
        require(result != nullptr, "result is NULL");
        copy_u32(result, result->map.vertex_remap, dst, capacity, "output vertices");
    });
}

raps_status raps_result_copy_chart_ids(const raps_result* result, uint32_t* dst, size_t capacity) {
    return guarded_read(result, [&] {
        require(result != nullptr, "result is NULL");
        const std::vector<uint32_t>& ids = result->map.chart_ids;
        if (!ids.empty() || !result->has_map) {
            copy_u32(result, ids, dst, capacity, "triangles");
            return;
        }
        // The disk domain: one chart.
        require(dst != nullptr, "dst is NULL");
        const size_t triangles = result->map.indices.size() / 3;
        require(capacity >= triangles, "capacity is smaller than the output triangles");
        std::fill(dst, dst + triangles, 0u);
    });
}

raps_status raps_result_get_stats(const raps_result* result, raps_stats* stats) {
    return guarded_read(result, [&] {
        require(result != nullptr, "result is NULL");
        require(stats != nullptr, "stats is NULL");
        if (stats->struct_size < 8) {
            throw Error(ErrorCode::kInvalidArgument,
                        "stats->struct_size " + std::to_string(stats->struct_size) +
                            " is below 8: set it to sizeof(raps_stats)");
        }
        if (!result->has_map) throw Error(ErrorCode::kInvalidOperation, "the result holds no map");
        copy_stats(result->map, stats);
    });
}

double raps_result_phase_ms(const raps_result* result, raps_phase phase) {
    if (!result || !result->has_map || phase < 0 || phase >= RAPS_PHASE_COUNT) return 0.0;
    return result->map.phase_ms[phase];
}

}  // extern "C"
