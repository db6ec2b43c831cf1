/*
 * raps.h - r-adaptive surface parameterization (Zayer, Roessl, Seidel: "r-Adaptive
 * Parameterization of Surfaces"). The one public header of libraps; it is the documentation.
 *
 * What it does
 *   Given a triangle mesh, compute texture coordinates (UVs) whose distortion is equidistributed
 *   rather than piled up: first a quasi-conformal map (mean value weights, boundary on a convex
 *   shape, one sparse solve), then one or more solves with adaptive weights
 *   W_ij = w_ij * e_ij^alpha built from an error monitor (area, edge length or angle) measured on
 *   the previous map (paper sections 3-6).
 *   Given a closed genus-0 mesh and RAPS_DOMAIN_SPHERE, compute a bijective map onto the unit
 *   sphere adapted with the same monitors (paper section 7), and optionally unfold it onto the
 *   square through the octahedron to get one chart of UVs.
 *
 * How to use it (C; every other language binds these same functions)
 *
 *   raps_mesh* mesh = NULL;  raps_settings* settings = NULL;  raps_result* result = NULL;
 *   raps_mesh_create(&mesh);
 *   raps_mesh_set_positions_f32(mesh, xyz, vertex_count, 0);
 *   raps_mesh_set_indices_u32(mesh, indices, index_count);
 *   raps_settings_create(&settings);                          // defaults: mean value + area
 *   raps_settings_set_int(settings, RAPS_PARAM_MONITOR, RAPS_MONITOR_AREA);
 *   raps_result_create(&result);
 *   if (raps_parameterize(mesh, settings, result) != RAPS_OK)
 *       fprintf(stderr, "raps: %s\n", raps_result_last_error(result));
 *   raps_result_copy_uvs_f32(result, uvs, raps_result_vertex_count(result), 0);
 *   raps_result_destroy(result); raps_settings_destroy(settings); raps_mesh_destroy(mesh);
 *
 * Conventions that hold for every function below
 *   - Status: every fallible function returns a raps_status (0 = RAPS_OK). The values of the
 *     status codes and of every other constant in this header are pinned forever: new values are
 *     only ever appended. Types that cross the ABI are fixed-width integers, double and pointers;
 *     the enum-like types are int32_t typedefs (a C enum's size is up to the compiler, and FFI
 *     code must be able to receive a value added by a later version).
 *   - Messages: a failing call stores a UTF-8 message naming the problem in the handle it was
 *     given (for raps_parameterize: in the result handle; for a getter, a copy out of a result or
 *     raps_settings_clone: in the handle read, const as it is). Read it with
 *     raps_*_last_error(); the pointer stays valid until the next call that may fail on that
 *     same handle. A successful call that changes its handle clears the message to ""; a
 *     successful call on a const handle leaves it as it was (it only reads the handle).
 *   - Ownership: create/destroy pairs. The caller owns every handle it created and must destroy
 *     it exactly once; destroy(NULL) is a no-op. The library copies all input arrays it is given
 *     (the caller may free them on return) and never keeps a caller pointer except the progress
 *     callback's user pointer and the progress state (raps_settings_set_progress_state).
 *     Output is copied into caller-owned buffers (raps_result_copy_*).
 *   - Threading: there is no global state. Distinct handles may be used from any threads at
 *     once. Functions taking a const handle only read it, unless they fail: one mesh and one
 *     settings handle may be shared by any number of concurrent raps_parameterize calls, each
 *     with its own result handle (raps_parameterize never writes its mesh or settings), and one
 *     result read by any number of concurrent copies. A const call that fails writes its message
 *     into the handle (see Messages), so a call that can fail on a shared handle (a capacity
 *     that may be too small, an unknown parameter) must not run while another call uses it. A
 *     handle must not be passed to a non-const function while any other call uses it.
 *   - Errors never crash: no function aborts, throws across the ABI or leaves a handle half
 *     changed. On failure a setter leaves its handle as it was; raps_parameterize leaves the
 *     result empty (zero counts) with its message set.
 *   - Units: positions are in any consistent unit (all distortion figures are scale-free); UVs
 *     are in texture space, [0,1]^2; times are milliseconds of wall clock; angles are degrees.
 *   - Reproducibility: raps_parameterize returns the same bits (uvs, sphere points, indices,
 *     remap, chart ids, every raps_stats field but threads_used) for the same input and
 *     settings: on every run; for every RAPS_PARAM_THREADS value; on every x86-64 processor,
 *     with or without AVX2 and FMA, and on aarch64; from a GCC or a clang build, shared or
 *     static. It calls no C library function whose last bit may vary (its exp, log, sin, cos,
 *     tan, atan2 and pow are its own, from IEEE basic operations and sqrt), uses no fused
 *     multiply-add, and its files are compiled with -ffp-contract=off -fno-fast-math;
 *     configuring with -ffast-math, -Ofast or a similar flag in CMAKE_C_FLAGS/CMAKE_CXX_FLAGS is
 *     refused. Not promised: builds with another Eigen version than 3.4.0 or another C++
 *     standard library than libstdc++ (GCC's, also used by clang on Linux), other compilers
 *     (MSVC) and architectures (untested), or a process that changes the floating-point
 *     environment (a rounding mode other than to-nearest, or flush-to-zero as an application
 *     linked with -ffast-math sets). docs/reproducibility.md has the details and the tests.
 *     For testing only: with the environment variable RAPS_KERNELS=baseline (read once, at a
 *     process's first factorization) the baseline kernels run on an AVX2 processor too.
 */
#ifndef RAPS_H
#define RAPS_H

#include <stddef.h>
#include <stdint.h>

/* ---------------------------------------------------------------------------------------------
 * Export and version
 * ------------------------------------------------------------------------------------------- */

#if defined(RAPS_STATIC)
#define RAPS_API
#elif defined(_WIN32)
#if defined(RAPS_BUILDING_LIBRARY)
#define RAPS_API __declspec(dllexport)
#else
#define RAPS_API __declspec(dllimport)
#endif
#else
#define RAPS_API __attribute__((visibility("default")))
#endif

#define RAPS_VERSION_MAJOR 0
#define RAPS_VERSION_MINOR 1
#define RAPS_VERSION_PATCH 0
/* MAJOR*10000 + MINOR*100 + PATCH, as a compile-time number to compare with raps_version(). */
#define RAPS_VERSION \
    ((RAPS_VERSION_MAJOR * 10000) + (RAPS_VERSION_MINOR * 100) + RAPS_VERSION_PATCH)

#ifdef __cplusplus
extern "C" {
#endif

/* The version of the library actually loaded, encoded like RAPS_VERSION. Thread-safe. */
RAPS_API uint32_t raps_version(void);
/* "MAJOR.MINOR.PATCH" of the loaded library; a static string, never freed. Thread-safe. */
RAPS_API const char* raps_version_string(void);

/* ---------------------------------------------------------------------------------------------
 * Status codes
 * ------------------------------------------------------------------------------------------- */

typedef int32_t raps_status;

enum {
    RAPS_OK = 0,
    /* A NULL pointer where a handle or array is required, an unknown parameter or value, a value
     * outside its bounds, a stride too small for a vertex, a capacity too small for the output. */
    RAPS_ERROR_INVALID_ARGUMENT = 1,
    RAPS_ERROR_OUT_OF_MEMORY = 2,
    /* The mesh has no vertices or no triangles (or its positions or indices were never set). */
    RAPS_ERROR_EMPTY_MESH = 3,
    /* The index count is not a multiple of 3. */
    RAPS_ERROR_INDEX_COUNT = 4,
    /* An index is >= the vertex count. */
    RAPS_ERROR_INDEX_OUT_OF_RANGE = 5,
    /* A position coordinate is NaN, infinite, or beyond +-1e30 (products of such coordinates
     * would overflow a double inside the algorithms). */
    RAPS_ERROR_NON_FINITE_POSITION = 6,
    /* A triangle names the same vertex twice. */
    RAPS_ERROR_REPEATED_VERTEX = 7,
    /* A triangle has (numerically) zero area: below 1e-12 times the mean triangle area.
     * Atlas domain (which takes such triangles as they come): every triangle would get zero uv
     * area, the mesh's extent being too large next to its triangles for double precision. */
    RAPS_ERROR_ZERO_AREA_TRIANGLE = 8,
    /* An edge is shared by more than two triangles. */
    RAPS_ERROR_NON_MANIFOLD_EDGE = 9,
    /* The triangles around a vertex form more than one fan (e.g. two cones touching at a tip). */
    RAPS_ERROR_NON_MANIFOLD_VERTEX = 10,
    /* Two triangles traverse their shared edge in the same direction (inconsistent winding). */
    RAPS_ERROR_INCONSISTENT_ORIENTATION = 11,
    /* A vertex is used by no triangle. */
    RAPS_ERROR_ISOLATED_VERTEX = 12,
    /* The mesh falls apart into several edge-connected pieces. */
    RAPS_ERROR_MULTIPLE_COMPONENTS = 13,
    /* Disk domain: the mesh is closed (no boundary loop). */
    RAPS_ERROR_NO_BOUNDARY = 14,
    /* Disk domain: the mesh has more than one boundary loop (holes). */
    RAPS_ERROR_MULTIPLE_BOUNDARIES = 15,
    /* The mesh has handles (genus > 0): one boundary loop but not a topological disk. */
    RAPS_ERROR_NONZERO_GENUS = 16,
    /* The mesh is too large: 2^31 or more vertices or more than 2^28 triangles (the library
     * indexes with int32, up to 8 entries per triangle), more vertices than uint16 indices can
     * address (65536), more triangles than RAPS_PARAM_MAX_TRIANGLES allows, or a run estimated
     * to need more memory than RAPS_PARAM_MAX_MEMORY_MB allows. */
    RAPS_ERROR_TOO_LARGE = 17,
    /* The progress callback returned 0, or the progress state was cancelled. Nothing was
     * produced; the handles stay usable. */
    RAPS_ERROR_CANCELLED = 18,
    /* The sparse solver failed (a singular system, e.g. from negative cotangent weights). */
    RAPS_ERROR_SOLVER_FAILED = 19,
    /* A call that is not allowed in the handle's current state (e.g. reading a result that holds
     * no map). */
    RAPS_ERROR_INVALID_OPERATION = 20,
    /* A bug in raps. Please report it with the message. */
    RAPS_ERROR_INTERNAL = 21,
    /* Sphere domain: the mesh is not closed (it has boundary loops; the message counts them). */
    RAPS_ERROR_OPEN_MESH = 22,
    /* raps_mesh_set_transform: a coefficient is NaN or infinite, or the 3x3 part is singular
     * (it would flatten the mesh: |det| below 1e-12 times the product of its rows' lengths). */
    RAPS_ERROR_INVALID_TRANSFORM = 23,
    /* Atlas domain: the mesh's triangle groups (raps_mesh_set_triangle_groups) or triangle
     * polygons (raps_mesh_set_triangle_polygons) are not one per triangle (the indices changed
     * since, or the count was wrong). */
    RAPS_ERROR_GROUP_COUNT = 24,
    /* Atlas domain: a seam edge (raps_mesh_set_seam_edges) names two vertices that no triangle
     * joins by an edge (the message names the pair). */
    RAPS_ERROR_SEAM_NOT_AN_EDGE = 25,
    /* Atlas domain with RAPS_PARAM_ATLAS_REPACK: the mesh's corner uvs
     * (raps_mesh_set_corner_uvs_f32/f64) are not three per triangle (never set, the indices
     * changed since, or the count was wrong). */
    RAPS_ERROR_UV_COUNT = 26,
    /* raps_mesh_set_corner_uvs_f32/f64: a uv coordinate is NaN, infinite or beyond +-1e30. */
    RAPS_ERROR_NON_FINITE_UV = 27,
    /* Atlas domain with RAPS_PARAM_ATLAS_REPACK: a uv chart of the input has 3D area but
     * (numerically) no uv area (below 1e-12 times its uv bounding box's squared diagonal): it
     * has no shape to keep. The message names its first triangle. */
    RAPS_ERROR_DEGENERATE_UV_CHART = 28
};

/* A short static description of a status ("invalid argument", ...); "unknown status" for values
 * this version does not know. Never NULL. Thread-safe. */
RAPS_API const char* raps_status_string(raps_status status);

/* ---------------------------------------------------------------------------------------------
 * Mesh: the input. Positions and triangle indices, copied into the handle.
 * ------------------------------------------------------------------------------------------- */

typedef struct raps_mesh raps_mesh;

/* Creates an empty mesh. *out_mesh receives the handle (NULL on failure).
 * Errors: INVALID_ARGUMENT (out_mesh NULL), OUT_OF_MEMORY. */
RAPS_API raps_status raps_mesh_create(raps_mesh** out_mesh);
/* Destroys a mesh; NULL is a no-op. The mesh must not be in use by another call. */
RAPS_API void raps_mesh_destroy(raps_mesh* mesh);

/* Sets (replaces) the vertex positions: vertex_count points of three coordinates x, y, z,
 * the first at xyz, each next one stride_bytes further (0 = tightly packed: 12 bytes for f32,
 * 24 for f64). The data is copied; the pointer need not be aligned.
 * Errors: INVALID_ARGUMENT (mesh or xyz NULL, stride_bytes nonzero and smaller than one point,
 * or so large that the points would span more bytes than an address reaches),
 * EMPTY_MESH (vertex_count 0), TOO_LARGE (vertex_count >= 2^31),
 * NON_FINITE_POSITION (NaN, infinite or |x| > 1e30; the message names the first such vertex),
 * OUT_OF_MEMORY. */
RAPS_API raps_status raps_mesh_set_positions_f32(raps_mesh* mesh, const float* xyz,
                                                 size_t vertex_count, size_t stride_bytes);
RAPS_API raps_status raps_mesh_set_positions_f64(raps_mesh* mesh, const double* xyz,
                                                 size_t vertex_count, size_t stride_bytes);

/* Sets (replaces) the triangle list: index_count indices, three per triangle, counter-clockwise
 * seen from the front. The data is copied. Index ranges are checked against the positions when
 * the mesh is used, so positions and indices may be set in either order.
 * Errors: INVALID_ARGUMENT (mesh or indices NULL), EMPTY_MESH (index_count 0), INDEX_COUNT (not a
 * multiple of 3), TOO_LARGE (more than 2^28 triangles), OUT_OF_MEMORY. */
RAPS_API raps_status raps_mesh_set_indices_u16(raps_mesh* mesh, const uint16_t* indices,
                                               size_t index_count);
RAPS_API raps_status raps_mesh_set_indices_u32(raps_mesh* mesh, const uint32_t* indices,
                                               size_t index_count);

/* Places the mesh in world units for raps_parameterize_scene (every other call ignores it): a
 * point p goes to A p + t, with m = {A00, A01, A02, t0, A10, A11, A12, t1, A20, A21, A22, t2}
 * (3x4, row-major, as a node's world matrix without its last row). A uniform scale s is
 * {s,0,0,0, 0,s,0,0, 0,0,s,0}. Texel density is measured in world units, so meshes modelled at
 * different scales get texels in proportion to the surface they cover in the scene. NULL sets
 * the identity (the default). A mirroring transform (det < 0) is allowed.
 * Errors: INVALID_ARGUMENT (mesh NULL), INVALID_TRANSFORM (a non-finite coefficient, or the
 * 3x3 part singular; the mesh keeps its transform). */
RAPS_API raps_status raps_mesh_set_transform(raps_mesh* mesh, const double* m);

/* The artist's seams, read by the atlas domain only (raps_parameterize and
 * raps_parameterize_scene; the disk and sphere domains ignore them). No chart crosses them: the
 * charts are cut there even where the surface is smooth and welded.
 *
 * Sets (replaces) a group id per triangle (a material, a smoothing group, a user region):
 * groups[t] is triangle t's, in the order of the indices; no chart holds triangles of two
 * groups (zero-area triangles excepted, which take the chart of a neighbouring vertex). The ids
 * are only compared. NULL with triangle_count 0 removes the groups (one group,
 * the default). The data is copied. The count is checked against the triangles when the mesh
 * is used, so groups and indices may be set in either order.
 * Errors: INVALID_ARGUMENT (mesh NULL, groups NULL with a nonzero count), TOO_LARGE (more than
 * 2^28), OUT_OF_MEMORY; when used: GROUP_COUNT (not one per triangle). */
RAPS_API raps_status raps_mesh_set_triangle_groups(raps_mesh* mesh, const uint32_t* groups,
                                                   size_t triangle_count);
/* Sets (replaces) a polygon id per triangle, for a mesh of quads or n-gons triangulated for raps:
 * polygons[t] is triangle t's polygon, in the order of the indices. Two triangles that share an
 * edge and an id are parts of one polygon: they always share a chart and no cut runs between
 * them (charts grow, split and are cut open along polygon edges only), so every corner of a
 * polygon gets one output vertex, whichever of its triangles it is read from. A chart that is
 * one polygon is kept whole even where its map breaks a stretch limit. The ids are only
 * compared across shared edges. NULL with triangle_count 0 removes them (every triangle a
 * polygon of its own, the default). The data is copied; the count is checked when the mesh is
 * used, as for groups. Triangles of one polygon in different groups or across a seam edge are
 * parts of different polygons there. A zero-area triangle (an n-gon with collinear corners)
 * takes the chart of a triangle of its polygon that shares an edge with it. An edge of more
 * than two triangles is cut, except between two triangles of one polygon that meet there the
 * opposite ways.
 * Errors: INVALID_ARGUMENT (mesh NULL, polygons NULL with a nonzero count), TOO_LARGE (more than
 * 2^28), OUT_OF_MEMORY; when used: GROUP_COUNT (not one per triangle). */
RAPS_API raps_status raps_mesh_set_triangle_polygons(raps_mesh* mesh, const uint32_t* polygons,
                                                     size_t triangle_count);
/* Sets (replaces) the seam edges: edge_count pairs of input vertex indices, vertex_pairs[2i] and
 * vertex_pairs[2i + 1], in either order. Charts do not grow or merge across them, and seams
 * that close a loop or run from boundary to boundary separate charts. A chart may still hold
 * both sides of a seam path that ends inside it: it is cut open along the path, its end
 * vertices excepted, which both sides keep sharing. NULL with edge_count 0 removes them (the
 * default). The data is copied and checked when the mesh is used.
 * Errors: INVALID_ARGUMENT (mesh NULL, vertex_pairs NULL with a nonzero count), TOO_LARGE (more
 * than 3 * 2^28 pairs), OUT_OF_MEMORY; when used: INDEX_OUT_OF_RANGE (a pair names a vertex >=
 * the vertex count), SEAM_NOT_AN_EDGE (no triangle has the pair as an edge); the message names
 * the first such pair. */
RAPS_API raps_status raps_mesh_set_seam_edges(raps_mesh* mesh, const uint32_t* vertex_pairs,
                                              size_t edge_count);

/* The mesh's existing uvs, read only when RAPS_PARAM_ATLAS_REPACK repacks them (every other call
 * ignores them). Sets (replaces) one uv per triangle corner: corner_count = 3 * triangle count
 * pairs u, v; corner 3t + k is corner k of triangle t, in the order of the indices; the first
 * pair at uv, each next one stride_bytes further (0 = tightly packed: 8 bytes for f32, 16 for
 * f64). Per corner rather than per vertex, so that an OBJ's `vt` or any uv seams come as they
 * are; uvs of a vertex-indexed format (glTF) are given by repeating each corner's vertex's uv.
 * Any range and orientation is taken (they need not lie in [0,1]^2). NULL with corner_count 0
 * removes them (the default: none). The data is copied; the pointer need not be aligned. The
 * count is checked against the triangles when the mesh is repacked, so uvs and indices may be
 * set in either order.
 * Errors: INVALID_ARGUMENT (mesh NULL, uv NULL with a nonzero count, stride_bytes nonzero and
 * smaller than one pair, or so large that the pairs would span more bytes than an address
 * reaches), TOO_LARGE (more than 3 * 2^28 corners), NON_FINITE_UV (NaN, infinite or beyond
 * +-1e30; the message names the first such corner), OUT_OF_MEMORY; the mesh keeps its uvs on
 * failure. When repacked: UV_COUNT (not three per triangle). */
RAPS_API raps_status raps_mesh_set_corner_uvs_f32(raps_mesh* mesh, const float* uv,
                                                  size_t corner_count, size_t stride_bytes);
RAPS_API raps_status raps_mesh_set_corner_uvs_f64(raps_mesh* mesh, const double* uv,
                                                  size_t corner_count, size_t stride_bytes);

/* Counts as set; 0 for NULL or when not set yet. Read-only, thread-safe with other readers. */
RAPS_API size_t raps_mesh_vertex_count(const raps_mesh* mesh);
RAPS_API size_t raps_mesh_triangle_count(const raps_mesh* mesh);

/* The message of the last failed setter on this mesh, "" after a success; never NULL (a static
 * message for a NULL mesh). Valid until the next setter call on this mesh. */
RAPS_API const char* raps_mesh_last_error(const raps_mesh* mesh);

/* ---------------------------------------------------------------------------------------------
 * Settings: key/value parameters with defaults, so that new parameters never break the ABI.
 * ------------------------------------------------------------------------------------------- */

typedef struct raps_settings raps_settings;
typedef int32_t raps_param;

enum {
    /* int. The parameter domain. Default RAPS_DOMAIN_DISK. */
    RAPS_PARAM_DOMAIN = 1,
    /* int. Base (quasi-conformal) weights w_ij of the Laplace system. Default MEAN_VALUE. */
    RAPS_PARAM_WEIGHTS = 2,
    /* int. Error monitor e_ij of the adaptive step; NONE returns the initial map. Default AREA. */
    RAPS_PARAM_MONITOR = 3,
    /* float. Exponent alpha of W_ij = w_ij * e_ij^alpha, in (0, 100]. Default 1. */
    RAPS_PARAM_ALPHA = 4,
    /* int. Number of adaptive solves, 1..100 (the paper: 1). Ignored with monitor NONE.
     * Default 1. */
    RAPS_PARAM_ITERATIONS = 5,
    /* int. How iterations combine, see RAPS_ITERATION_*. Default ACCUMULATE. */
    RAPS_PARAM_ITERATION_MODE = 6,
    /* int. Convex shape the boundary is fixed to. Default RAPS_BOUNDARY_CIRCLE. */
    RAPS_PARAM_BOUNDARY = 7,
    /* int. Largest triangle count accepted, 1..2^31-1; larger meshes get RAPS_ERROR_TOO_LARGE
     * before any work is done. Default 2^31-1. */
    RAPS_PARAM_MAX_TRIANGLES = 8,
    /* int. Threads a run may use, 0..1024; 0 = one per hardware thread. The output is
     * bit-identical for every value (see Reproducibility at the top). Used by the sphere
     * relaxation (at most one thread per 4,096 vertices), the atlas, and the statistics of every
     * domain (at most one thread per 16,384 triangles there); raps_stats.threads_used says how
     * many a run computed on. Default 0. */
    RAPS_PARAM_THREADS = 9,

    /* Sphere domain (RAPS_DOMAIN_SPHERE); ignored by the others. */
    /* int. How the sphere domain computes its map, see RAPS_SPHERE_*. Default ROBUST. */
    RAPS_PARAM_SPHERE_METHOD = 10,
    /* int. Texture coordinates for the sphere domain, see RAPS_SPHERE_UV_*. Default NONE. */
    RAPS_PARAM_SPHERE_UV = 11,
    /* float. Sphere relaxation: damping lambda of algorithm 7.1, the fraction of the way to the
     * weighted mean of its ring that a vertex moves per sweep, in (0, 1]. Default 1. */
    RAPS_PARAM_SPHERE_DAMPING = 12,
    /* float. Sphere relaxation: it has converged when the root mean square of the vertices'
     * moves in one sweep (after removing the rotation that best aligns the map with the one
     * before), in units of the damping times the mean edge length, is below this, in
     * [1e-12, 1]. Default 1e-4. */
    RAPS_PARAM_SPHERE_TOLERANCE = 13,
    /* int. Sphere relaxation: most sweeps of one relaxation, 0..10^7; 0 = the method's own:
     * for ROBUST 100 for the initial relaxation and 200 for each adaptive one (measured on the
     * shared meshes and on meshes subdivided to 90K triangles, see docs/sphere-status.md), 50000
     * for LITERAL. Default 0. */
    RAPS_PARAM_SPHERE_MAX_SWEEPS = 14,
    /* int. Robust sphere method: relaxations by which each adaptive iteration reaches its
     * exponent (continuation: each multiplies the weights by e^(alpha / steps)), 1..100.
     * Default 2. */
    RAPS_PARAM_SPHERE_ALPHA_STEPS = 15,

    /* Every domain (numbered after the sphere's parameters). */
    /* int. Memory cap in MiB, 0..2^31-1; 0 = no cap. A run whose estimated peak (the memory
     * raps_parameterize adds to the handles', from the triangle count, the domain and the atlas
     * resolution; the estimate lies above the peaks measured on the shared meshes, see
     * docs/bench-memory.md) is larger gets RAPS_ERROR_TOO_LARGE before any work is done.
     * Default 0. */
    RAPS_PARAM_MAX_MEMORY_MB = 16,

    /* Atlas domain (RAPS_DOMAIN_ATLAS); ignored by the others. */
    /* int. Texels on each side of the square atlas, 16..16384. Default 1024. */
    RAPS_PARAM_ATLAS_RESOLUTION = 32,
    /* int. Texels kept free between charts, 0..64: 1 keeps bilinear filtering from mixing
     * charts, more keeps mip levels apart too. Default 1. At a resolution, 2 x padding + 3
     * must not exceed it (a texel for a chart): RAPS_ERROR_INVALID_ARGUMENT otherwise. */
    RAPS_PARAM_ATLAS_PADDING = 33,
    /* float. Vertices closer than this (in position units) are welded before charts are made,
     * >= 0; 0 welds identical positions only. Default 0. */
    RAPS_PARAM_WELD_TOLERANCE = 34,
    /* float, degrees in [0, 180]. Edges whose two triangles' normals differ by more become chart
     * seams; 180 turns this off. Default 180. */
    RAPS_PARAM_HARD_EDGE_ANGLE = 35,
    /* float in [1, 10]. Charts are split until the atlas's L2 stretch (Sander et al. 2001) is at
     * most this. Default 1.01. */
    RAPS_PARAM_ATLAS_MAX_L2_STRETCH = 36,
    /* float in [1, 1000]. No chart keeps a triangle stretched more than this (Linf stretch);
     * larger ones are split. Default 2.9. */
    RAPS_PARAM_ATLAS_MAX_LINF_STRETCH = 37,
    /* float, texels per world unit (positions' units, after raps_mesh_set_transform), >= 0.
     * 0: the density that fills the square of RAPS_PARAM_ATLAS_RESOLUTION texels with one page
     * (the charts reach two opposite sides of it; above 100 charts they are placed on whole
     * texels at the largest density within 1% that fits; raps_stats.texels_per_unit reports
     * the density found).
     * Above 0: every chart gets this density (a chart's area in texels is its surface area
     * times the square of it) and is placed on whole texels, on pages of at most
     * RAPS_PARAM_ATLAS_MAX_WIDTH x RAPS_PARAM_ATLAS_MAX_HEIGHT texels, never more; charts that
     * do not fit a page go on further pages, and a chart larger than a page is shrunk until it
     * fits (RAPS_CHART_SCALED_DOWN, raps_stats.scaled_down_charts), never dropped. Then the
     * padding holds exactly at the final texels: at least RAPS_PARAM_ATLAS_PADDING texels lie
     * between the texels that any two charts' triangles touch (2 keeps bilinear lookups of two
     * charts from sharing a texel). Default 0. */
    RAPS_PARAM_ATLAS_TEXELS_PER_UNIT = 38,
    /* int, 16..16384. With a density: the largest page width and height in texels. Every page
     * of an atlas has one size: as wide and as tall as the charts of any page reach (with the
     * margin), up to these. A run whose pages leave no more than the padding inside the margin
     * is refused (INVALID_ARGUMENT). Default 4096. */
    RAPS_PARAM_ATLAS_MAX_WIDTH = 39,
    RAPS_PARAM_ATLAS_MAX_HEIGHT = 40,
    /* int. Which turns the packing may give a chart, see RAPS_ROTATION_*. Default ANY. */
    RAPS_PARAM_ATLAS_ROTATION = 41,
    /* int, 0..1024. With a density (or whole texels): texels kept free between the charts and
     * each page's border (rounded up to whole blocks with block alignment). Default 0. */
    RAPS_PARAM_ATLAS_MARGIN = 42,
    /* int, 0 or 1. With a density (or whole texels): 1 places charts on whole 4x4 blocks of
     * texels, no block shared by two charts (block compression then never mixes them), padding
     * rounded up to whole blocks. Default 0. */
    RAPS_PARAM_ATLAS_BLOCK_ALIGN = 43,
    /* int, 0 or 1. With a density: 1 puts all charts of one mesh of a scene on one page (as a
     * lightmap needs), shrinking a mesh's charts together when they do not fit one page.
     * Default 0. */
    RAPS_PARAM_ATLAS_MESH_PER_PAGE = 44,
    /* int, 0 or 1. Without a density (RAPS_PARAM_ATLAS_TEXELS_PER_UNIT 0): 1 places the charts
     * as a density does (whole texels, the padding exact at the final texels, margin, block
     * alignment) on one page of at most RAPS_PARAM_ATLAS_RESOLUTION x
     * RAPS_PARAM_ATLAS_RESOLUTION texels, at the largest density (within 1%) at which every
     * chart fits it unshrunk (raps_stats.texels_per_unit reports it); a lightmap of a fixed
     * size: the atlas is that square, uvs texels over the resolution on both axes, the charts
     * in its lower left corner. Refused (INVALID_ARGUMENT) when no density fits the charts
     * with their padding. Default 0. */
    RAPS_PARAM_ATLAS_WHOLE_TEXELS = 45,
    /* int, 0 or 1. 0 welds vertices that share a position (within RAPS_PARAM_WELD_TOLERANCE)
     * before growing charts, so the input's own vertex splits (an exporter's uv seams, split
     * normals) do not split charts. 1 keeps every edge where the triangles on its two sides use
     * different input vertices as a chart boundary: the seams of the input's existing uvs,
     * when those are expressed, as usual, by split vertices. */
    RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS = 46,
    /* int, 0 or 1. 1 repacks the mesh's own uvs (raps_mesh_set_corner_uvs_f32/f64) instead of
     * mapping it again: the charts are the uv islands (triangles sharing an edge, whose two
     * vertices are welded by position as RAPS_PARAM_WELD_TOLERANCE says, are in one chart when
     * their corner uvs at both ends are equal, bit for bit), each scaled uniformly to the
     * atlas's one texel density (its uv area in texels is its 3D area in world units times the
     * density squared) and packed like mapped charts, by every packing setting (resolution or
     * density, pages, padding, margin, block alignment, rotation, mesh per page, whole texels).
     * A chart's uvs are only moved, turned (as RAPS_PARAM_ATLAS_ROTATION allows) and uniformly
     * scaled: its shape is kept. Charts are taken as given: flipped (clockwise) or overlapping
     * triangles stay flipped and overlapping, a mirrored chart stays mirrored, and its
     * raps_chart.stretch_l2 measures the input's own map. A uv chart whose triangles have no 3D
     * area gets no texels (its uvs all become one point, as degenerate triangles do). Triangle
     * groups and seam edges split islands as they split mapped charts: no chart holds two
     * groups, and no two triangles join across a seam edge (a seam path that ends inside an
     * island leaves it one chart, its uvs as given). Hard edges, stretch limits and
     * RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS are not used. The output is one vertex per distinct
     * (input vertex, chart, uv) and raps_stats.adaptive_solves is 0; the run enters no
     * INITIAL_MAP phase (the islands are found in SEGMENT). Errors: UV_COUNT,
     * DEGENERATE_UV_CHART. Default 0. */
    RAPS_PARAM_ATLAS_REPACK = 47,
    /* int. Whether congruent charts share one place in the atlas, see RAPS_STACK_*: duplicated
     * or instanced geometry (one mesh handle given twice to raps_parameterize_scene, copies of
     * one mesh in one mesh) then costs no extra texels. Two charts stack when they are the same
     * triangles over the same chart vertices (as copies with the same vertex and triangle order
     * give) and their 3D vertices agree, vertex for vertex, up to a rigid motion (or a mirror,
     * with RAPS_STACK_MIRRORED) within RAPS_PARAM_ATLAS_STACK_TOLERANCE; when repacking, their
     * own uvs must agree the same way (an island laid out mirrored is a mirror too). The later
     * chart takes the earlier one's uvs, texel for texel: raps_chart.flags has
     * RAPS_CHART_STACKED and raps_chart.stacked_on names the chart it shares, whose page and
     * texel rectangle it has. Charts are not cut alike on turned copies, nor mesh by mesh in a
     * scene, so a connected piece of a mesh that repeats an earlier piece, in the same mesh or
     * an earlier one (the same triangles over its vertices numbered by first use, the same
     * groups, polygons and seam edges, and vertices congruent as above, turned by any angle)
     * takes copies of that piece's charts instead of its own, each then stacked on its
     * original. A copy drawn mirrored (a transform with det < 0) is a mirror: it stacks only
     * with RAPS_STACK_MIRRORED. raps_stats.utilization counts each shared place once. With
     * RAPS_PARAM_ATLAS_MESH_PER_PAGE only charts of one mesh stack. A lightmap needs every chart
     * its own texels: leave this off for one. Default NONE. */
    RAPS_PARAM_ATLAS_STACK = 48,
    /* float in [0, 0.1]. How far, as a fraction of a chart's extent (its first vertex to its
     * farthest), a stacked chart's vertices may lie from where the rigid motion (or mirror)
     * puts the chart it shares. Default 1e-4. */
    RAPS_PARAM_ATLAS_STACK_TOLERANCE = 49
};

/* RAPS_PARAM_ATLAS_STACK values */
enum {
    RAPS_STACK_NONE = 0,     /* every chart its own texels */
    RAPS_STACK_RIGID = 1,    /* congruent up to a rigid motion: one place */
    RAPS_STACK_MIRRORED = 2  /* also congruent up to a mirror (the texture appears mirrored) */
};

/* RAPS_PARAM_ATLAS_ROTATION values */
enum {
    /* Any angle: each chart is turned to its smallest bounding box, then by the quarter turn
     * that packs best. */
    RAPS_ROTATION_ANY = 0,
    /* Quarter turns of the chart's map only (0, 90, 180 or 270 degrees). */
    RAPS_ROTATION_QUARTER = 1,
    /* None: each chart keeps its map's orientation. */
    RAPS_ROTATION_NONE = 2
};

/* RAPS_PARAM_DOMAIN values */
enum {
    /* A topological disk (one boundary loop, genus 0, one piece), mapped into [0,1]^2 with its
     * boundary on the convex shape of RAPS_PARAM_BOUNDARY. One output vertex per input vertex. */
    RAPS_DOMAIN_DISK = 0,
    /* A closed genus-0 mesh (no boundary, one piece), mapped bijectively onto the unit sphere
     * (paper section 7): read the points with raps_result_copy_sphere_points_*. One output
     * vertex per input vertex, the input triangles, no uvs, unless RAPS_PARAM_SPHERE_UV asks
     * for the octahedral unfold. Refuses an open mesh (RAPS_ERROR_OPEN_MESH), handles
     * (NONZERO_GENUS), several pieces (MULTIPLE_COMPONENTS) and non-manifold input. */
    RAPS_DOMAIN_SPHERE = 1,
    /* Any triangle mesh (several pieces, holes, handles, non-manifold or inconsistently wound
     * parts, zero-area and duplicate triangles): cut into charts, each mapped (a free-boundary
     * conformal map, then the adaptive step) and packed into one texture atlas. Output vertices
     * are duplicated along seams (raps_result_copy_vertex_remap gives each one's input vertex);
     * output triangles are the input triangles, in input order, with a chart id each. A
     * triangle repeated over the same (welded) vertices in the same winding takes its first
     * copy's uvs, corner for corner (one surface, one set of texels); wound the other way it is
     * the back of a two-sided surface and gets charts of its own. At a resolution, a chart
     * too long for the square at the density the charts' area allows is cut across into
     * pieces that keep its map: the seams grow, the stretch does not. Too long is more than
     * twice the square's side for a chart holding half the charts' area or more (a 5.7:1
     * chart alone covered 0.086 of the square, its 4 pieces 0.676), 1.25 times it for a
     * smaller one (one long mesh in a scene held the others' density down: the 19 shared
     * meshes covered 0.33 of the square, 0.73 with it cut in two); between once and 1.25
     * times the side the atlas is packed both ways and the cut kept only where it is denser
     * (the packing phase then takes about twice as long). uvs are
     * texel positions over the atlas's width x height texels (raps_stats.atlas_width/height),
     * as a texture of that size maps them: at a resolution the atlas is a square of
     * RAPS_PARAM_ATLAS_RESOLUTION texels, so u and v have the same scale; pages at a density
     * (RAPS_PARAM_ATLAS_TEXELS_PER_UNIT) are cropped to their charts. */
    RAPS_DOMAIN_ATLAS = 2
};

/* RAPS_PARAM_SPHERE_METHOD values */
enum {
    /* Paper algorithm 7.1 as written: Gauss map (centroid at the origin, project), Gauss-Seidel
     * sweeps in vertex order moving each vertex by lambda times the tangential Laplacian and
     * back onto the sphere until converged, then the same with the adaptive weights. One thread,
     * no safeguards: it may fold triangles (counted in docs/bench-method.md) and collapse
     * towards a point. */
    RAPS_SPHERE_LITERAL = 0,
    /* The same relaxation made robust (docs/method.md, "What the robust method adds"): a
     * bijective initial map (puncture, Tutte embedding, inverse stereographic projection), moves
     * that would fold a triangle halved or refused, Moebius centring after every sweep, parallel
     * Gauss-Seidel over a vertex colouring, over-relaxation, and continuation in alpha. Returns
     * no folded triangle: a final map that floating point leaves folded is
     * RAPS_ERROR_SOLVER_FAILED. */
    RAPS_SPHERE_ROBUST = 1
};

/* RAPS_PARAM_SPHERE_UV values */
enum {
    RAPS_SPHERE_UV_NONE = 0, /* sphere points only */
    /* Also unfold the sphere onto [0,1]^2 through the octahedron (Praun and Hoppe 2003): one
     * chart, cut along four paths of edges from one vertex to the equator; the vertices on the
     * cut are duplicated (more output vertices than input, see raps_result_copy_vertex_remap),
     * and no uv triangle is flipped. The statistics then describe the uv map. */
    RAPS_SPHERE_UV_OCTAHEDRAL = 1
};

/* RAPS_PARAM_WEIGHTS values */
enum {
    /* Floater's mean value weights (paper section 5): positive, so the map never folds. */
    RAPS_WEIGHTS_MEAN_VALUE = 0,
    /* Discrete harmonic (cotangent) weights; negative on obtuse triangles, so the map may fold
     * (the count of negative weights is in raps_stats.negative_weights). A disk map folded out
     * past its boundary shape is scaled uniformly about its bounding box back into [0,1]^2. */
    RAPS_WEIGHTS_COTANGENT = 1,
    /* Tutte's uniform weights: all 1. */
    RAPS_WEIGHTS_UNIFORM = 2
};

/* RAPS_PARAM_MONITOR values (paper section 6) */
enum {
    RAPS_MONITOR_NONE = 0,        /* no adaptive step: the initial quasi-conformal map */
    RAPS_MONITOR_AREA = 1,        /* 6.1: uv area / 3D area, averaged over the edge's triangles */
    RAPS_MONITOR_EDGE_LENGTH = 2, /* 6.2: uv length / 3D length of the edge */
    RAPS_MONITOR_ANGLE = 3        /* 6.3: uv angle / 3D angle at the edge's first vertex */
};

/* RAPS_PARAM_ITERATION_MODE values: with K > 1 adaptive solves, the weights of solve k are */
enum {
    /* the weights of solve k-1 times e^alpha measured on map k-1: a fixed-point iteration of the
     * equidistribution that keeps lowering the monitor's spread (measured: docs/bench-method.md,
     * "accumulating against re-applying the monitor"). */
    RAPS_ITERATION_ACCUMULATE = 0,
    /* the base weights times e^alpha measured on map k-1 (each step forgets the previous ones). */
    RAPS_ITERATION_REAPPLY = 1
};

/* RAPS_PARAM_BOUNDARY values */
enum {
    /* The circle of radius 0.5 centred at (0.5, 0.5), by chord length. */
    RAPS_BOUNDARY_CIRCLE = 0,
    /* The unit square's sides, by chord length, its corners at the boundary vertices nearest to
     * each quarter of the boundary's length. Triangles with all three vertices on one side have
     * zero uv area (counted in raps_stats.zero_area_triangles). */
    RAPS_BOUNDARY_SQUARE = 1
};

/* Creates settings holding the defaults above. Errors: INVALID_ARGUMENT, OUT_OF_MEMORY. */
RAPS_API raps_status raps_settings_create(raps_settings** out_settings);
/* Creates an independent copy of settings (including its progress callback and state).
 * Errors: INVALID_ARGUMENT, OUT_OF_MEMORY. */
RAPS_API raps_status raps_settings_clone(const raps_settings* settings,
                                         raps_settings** out_settings);
/* Destroys settings; NULL is a no-op. */
RAPS_API void raps_settings_destroy(raps_settings* settings);

/* Set an int or float parameter. An int parameter is only set through _int and a float one only
 * through _float. Errors: INVALID_ARGUMENT (NULL settings, unknown parameter, wrong type, value
 * out of bounds or not one of the parameter's values; the settings stay unchanged). */
RAPS_API raps_status raps_settings_set_int(raps_settings* settings, raps_param param,
                                           int64_t value);
RAPS_API raps_status raps_settings_set_float(raps_settings* settings, raps_param param,
                                             double value);
/* Read a parameter. Errors: INVALID_ARGUMENT (NULL pointer, unknown parameter, wrong type). */
RAPS_API raps_status raps_settings_get_int(const raps_settings* settings, raps_param param,
                                           int64_t* out_value);
RAPS_API raps_status raps_settings_get_float(const raps_settings* settings, raps_param param,
                                             double* out_value);

/* Facts about a parameter, without a settings handle: its name ("alpha", ...), whether it is a
 * float (1) or an int (0), its inclusive bounds and its default. Any out pointer may be NULL.
 * Errors: INVALID_ARGUMENT (unknown parameter). Thread-safe. */
RAPS_API raps_status raps_param_info(raps_param param, const char** out_name, int32_t* out_is_float,
                                     double* out_min, double* out_max, double* out_default);

/* Progress phases, reported to the progress callback and timed in raps_result_phase_ms. */
typedef int32_t raps_phase;
enum {
    RAPS_PHASE_VALIDATE = 0,    /* checking the input */
    RAPS_PHASE_TOPOLOGY = 1,    /* edges, boundary loop, system pattern and ordering; atlas:
                                 * welding */
    RAPS_PHASE_INITIAL_MAP = 2, /* boundary, base weights, first solve (paper sections 3, 5);
                                 * sphere: initial map and its relaxation (section 7); atlas:
                                 * every chart's map, its adaptive step included */
    RAPS_PHASE_ADAPT = 3,       /* monitors and adaptive solves (section 6); sphere: the
                                 * adaptive relaxations, and the octahedral unfold */
    RAPS_PHASE_METRICS = 4,     /* distortion statistics */
    RAPS_PHASE_SEGMENT = 5,     /* atlas: growing charts */
    RAPS_PHASE_PACK = 6,        /* atlas: packing charts */
    RAPS_PHASE_COUNT = 7        /* number of phases in this version */
};

/* Progress callback: called with the phase and the fraction of it done, in [0, 1]. Every phase
 * a run enters reports its start (0), then as it works, and its end (1); its calls are
 * contiguous and its fractions never fall. Every pass over the mesh reports every 8,192 items
 * (triangles, vertices, half-edges); the sparse factorizations every 1% of their floating-point
 * work, every 1e7 flops, and within a large front every few million multiply-adds; the
 * orderings (nested dissection) per level, separator and leaf; the sphere relaxation every 1% of
 * its sweeps and, at the same fraction, every 8,192 vertices moved; the atlas after each
 * chart, and inside a chart's map (at the fraction reached) as the steps above do. So a cancel
 * waits for a few milliseconds of work, not for a phase: raps-bench-progress prints the longest
 * wait of each phase (docs/bench-progress.md). Not split: the minimum-degree ordering of a system
 * of up to 150,000 unknowns (a chart, or a mesh of up to about 300,000 triangles: tens of
 * milliseconds at that size) and, outside the sphere domain, the release of large buffers (a
 * factorization's, a run's between two phases); the sphere gives its large buffers back in runs
 * of 16 MB with a call between two. Measured at one thread (docs/cancel-latency.md): the atlas
 * at 5.8M triangles waited at most 44 ms of work, the sphere at 5.65M 44 ms. Return
 * nonzero to go on, 0 to cancel: the run then stops at that call and returns
 * RAPS_ERROR_CANCELLED. It is called on the thread that called raps_parameterize or, with
 * RAPS_PARAM_THREADS != 1, on the run's worker threads; calls for one run never overlap. When one
 * settings handle is shared by concurrent runs, the callback receives calls from each of them. */
typedef int32_t (*raps_progress_fn)(void* user, raps_phase phase, double fraction);

/* Sets the progress callback (NULL: none) and the pointer passed to it. Errors: INVALID_ARGUMENT
 * (NULL settings). */
RAPS_API raps_status raps_settings_set_progress(raps_settings* settings, raps_progress_fn fn,
                                                void* user);

/* A progress state: progress without a callback, for callers that would rather poll. A run whose
 * settings name one (raps_settings_set_progress_state) writes every progress report into it
 * (the same reports, at the same points, as raps_progress_fn receives) and stops at its next
 * report once the state is cancelled, returning RAPS_ERROR_CANCELLED; the caller reads it
 * from any thread. For a language whose callbacks are costly to enter from the run's worker
 * threads: a Python callback called from a thread Python did not create took 40 to 90
 * microseconds per call, five to nine times the library's own time on a mesh of a few thousand
 * triangles (docs/blender.md); a report into a state costs a lock. A callback may be set too:
 * the state records each report before the callback sees it.
 * Threading: the raps_progress_state_* calls below may run on any thread at any time, also
 * while runs report into the state; destroy it only when no run uses it. Several runs may
 * share one state (a cancel stops them all; a read shows the latest report of any of them). */
typedef struct raps_progress_state raps_progress_state;

/* Creates a state: no report yet (phase -1, fraction 0, 0 reports), not cancelled.
 * Errors: INVALID_ARGUMENT (NULL out_state), OUT_OF_MEMORY. */
RAPS_API raps_status raps_progress_state_create(raps_progress_state** out_state);
/* Destroys a state; NULL is a no-op. No run may be using it. */
RAPS_API void raps_progress_state_destroy(raps_progress_state* state);
/* The latest report: its phase (a raps_phase, -1 before the first), the fraction of that phase
 * done (in [0, 1], never falling within a pass through a phase) and how many reports the state
 * has recorded since it was created or reset. The three come from one report. Any out pointer
 * may be NULL. Errors: INVALID_ARGUMENT (NULL state). */
RAPS_API raps_status raps_progress_state_read(const raps_progress_state* state,
                                              raps_phase* out_phase, double* out_fraction,
                                              int64_t* out_reports);
/* Cancels every run reporting into the state, at its next report (a few milliseconds of work
 * at most, as for the callback), and every run started with it until it is reset.
 * Errors: INVALID_ARGUMENT (NULL state). */
RAPS_API raps_status raps_progress_state_cancel(raps_progress_state* state);
/* Back to no report and not cancelled, for the next run. Errors: INVALID_ARGUMENT (NULL). */
RAPS_API raps_status raps_progress_state_reset(raps_progress_state* state);
/* Runs with these settings report into state (NULL: none); the settings keep the pointer, not
 * the state, which must outlive every run that uses it. raps_settings_clone copies the
 * pointer. Errors: INVALID_ARGUMENT (NULL settings). */
RAPS_API raps_status raps_settings_set_progress_state(raps_settings* settings,
                                                      raps_progress_state* state);

/* The message of the last failed call on these settings (a setter, a getter, a clone), "" after
 * a setter succeeds; never NULL. */
RAPS_API const char* raps_settings_last_error(const raps_settings* settings);

/* ---------------------------------------------------------------------------------------------
 * Result: the map and its statistics
 * ------------------------------------------------------------------------------------------- */

typedef struct raps_result raps_result;

/* Creates an empty result, to be filled (and refilled) by raps_parameterize.
 * Errors: INVALID_ARGUMENT, OUT_OF_MEMORY. */
RAPS_API raps_status raps_result_create(raps_result** out_result);
/* Destroys a result; NULL is a no-op. */
RAPS_API void raps_result_destroy(raps_result* result);

/* Parameterizes mesh with settings (NULL: the defaults) into result, replacing what it held.
 * mesh and settings are only read (see Threading). Runs on the calling thread; the sphere and
 * atlas domains also start up to RAPS_PARAM_THREADS - 1 worker threads of their own, every
 * domain does to measure the statistics of a mesh of 32,768 triangles or more, and all are
 * joined before it returns (the progress callback may be called from them, never two calls at
 * once; see raps_progress_fn).
 * On success result holds the output vertices (UVs and the input vertex each comes from), the
 * output triangles and the statistics. The errors below are those of every domain: the disk's
 * topology statuses (NO_BOUNDARY, MULTIPLE_BOUNDARIES, ...) do not apply to the atlas, which
 * takes any triangle mesh. On failure it holds nothing and its message names the
 * problem (for mesh problems: the first offending triangle, vertex or edge).
 * Errors: INVALID_ARGUMENT (mesh or result NULL), EMPTY_MESH, INDEX_OUT_OF_RANGE, TOO_LARGE,
 * REPEATED_VERTEX, ZERO_AREA_TRIANGLE, NON_MANIFOLD_EDGE, NON_MANIFOLD_VERTEX,
 * INCONSISTENT_ORIENTATION, ISOLATED_VERTEX, MULTIPLE_COMPONENTS, NO_BOUNDARY,
 * MULTIPLE_BOUNDARIES, NONZERO_GENUS, OPEN_MESH, CANCELLED, SOLVER_FAILED, OUT_OF_MEMORY,
 * INTERNAL; atlas domain: GROUP_COUNT, SEAM_NOT_AN_EDGE and INDEX_OUT_OF_RANGE for the artist's
 * seams (raps_mesh_set_triangle_groups, raps_mesh_set_seam_edges); UV_COUNT and
 * DEGENERATE_UV_CHART when repacking (RAPS_PARAM_ATLAS_REPACK). */
RAPS_API raps_status raps_parameterize(const raps_mesh* mesh, const raps_settings* settings,
                                       raps_result* result);

/* Parameterizes several meshes into one atlas (settings must set RAPS_PARAM_DOMAIN to
 * RAPS_DOMAIN_ATLAS): each mesh is placed in world units by its transform
 * (raps_mesh_set_transform), cut into charts of its own (no chart joins two meshes, even where
 * they touch) and every chart is packed at one texel density. The same mesh handle may appear
 * more than once (it is then packed once per appearance, or shares its first appearance's
 * texels with RAPS_PARAM_ATLAS_STACK). meshes and settings are only read,
 * as for raps_parameterize; the result is replaced.
 * The result holds the meshes' outputs one after another, in the order given:
 * raps_result_mesh_range gives each mesh's output vertices and indices, and within a mesh's
 * range everything reads as a one-mesh result would: its indices number the mesh's own output
 * vertices (from 0 at the range's first vertex) and raps_result_copy_vertex_remap gives the
 * mesh's own input vertices. Chart ids and chart records (raps_result_get_chart) are the
 * atlas's, numbered over all meshes. The copy functions copy all meshes at once.
 * Errors: those of raps_parameterize (a mesh's own problems name the mesh: "mesh 2: ...") and
 * INVALID_ARGUMENT (meshes or result NULL, meshes[i] NULL, settings NULL or not the atlas
 * domain), EMPTY_MESH (mesh_count 0, or a mesh without positions or indices),
 * NON_FINITE_POSITION (a vertex beyond 1e30 once transformed), TOO_LARGE (more than 2^31 - 1
 * vertices or 2^28 triangles together, or the limits of the settings on the whole scene). */
RAPS_API raps_status raps_parameterize_scene(const raps_mesh* const* meshes, size_t mesh_count,
                                             const raps_settings* settings, raps_result* result);

/* The message of the last failed call on this result (raps_parameterize, a copy, the stats), ""
 * after raps_parameterize succeeds; never NULL. */
RAPS_API const char* raps_result_last_error(const raps_result* result);

/* Output sizes; 0 for NULL or an empty result. For RAPS_DOMAIN_DISK, and RAPS_DOMAIN_SPHERE
 * without uvs, the output vertices are the input vertices, in input order, and the output
 * triangles are the input triangles. */
RAPS_API size_t raps_result_vertex_count(const raps_result* result);
RAPS_API size_t raps_result_index_count(const raps_result* result);

/* Copy per-output-vertex UVs (u, v pairs in [0,1]^2, v up) into dst: vertex i at byte offset
 * i * stride_bytes (0 = tightly packed). capacity is the number of vertices dst can hold and must
 * be >= raps_result_vertex_count. Errors: INVALID_ARGUMENT (NULL, capacity or stride too small,
 * or a stride that would place a vertex beyond any address), INVALID_OPERATION (the result holds
 * no map, or a sphere map without uvs). */
RAPS_API raps_status raps_result_copy_uvs_f32(const raps_result* result, float* dst,
                                              size_t capacity, size_t stride_bytes);
RAPS_API raps_status raps_result_copy_uvs_f64(const raps_result* result, double* dst,
                                              size_t capacity, size_t stride_bytes);
/* Copy per-output-vertex points on the unit sphere (x, y, z) of a RAPS_DOMAIN_SPHERE result,
 * like the uvs: vertex i at byte offset i * stride_bytes (0 = tightly packed), capacity >=
 * raps_result_vertex_count. Errors: INVALID_ARGUMENT (NULL, capacity or stride too small, or a
 * stride beyond any address, as for the uvs), INVALID_OPERATION (the result holds no sphere map,
 * e.g. a disk result). The robust method's promise of no folded triangle holds for the f64
 * points: on meshes with long thin parts a spherical triangle can be far smaller than float
 * resolution, and rounding to f32 can fold it (measured: 193 of 77K triangles of a subdivided
 * horse). Read the f64 points when the map must stay bijective. */
RAPS_API raps_status raps_result_copy_sphere_points_f32(const raps_result* result, float* dst,
                                                        size_t capacity, size_t stride_bytes);
RAPS_API raps_status raps_result_copy_sphere_points_f64(const raps_result* result, double* dst,
                                                        size_t capacity, size_t stride_bytes);
/* Input meshes the result holds: 1 after raps_parameterize, mesh_count after
 * raps_parameterize_scene, 0 for NULL or an empty result. */
RAPS_API size_t raps_result_mesh_count(const raps_result* result);
/* Where mesh `mesh` (0 .. raps_result_mesh_count - 1) lies in the output: its output vertices
 * first_vertex .. first_vertex + vertex_count - 1 and its indices first_index .. first_index +
 * index_count - 1 (three per triangle, its triangles in its input order; chart ids: triangle
 * first_index / 3 on). Any out pointer may be NULL. Errors: INVALID_ARGUMENT (result NULL, mesh
 * out of range), INVALID_OPERATION (the result holds no map). */
RAPS_API raps_status raps_result_mesh_range(const raps_result* result, size_t mesh,
                                            uint64_t* first_vertex, uint64_t* vertex_count,
                                            uint64_t* first_index, uint64_t* index_count);
/* Copy the output triangles (indices into the output vertices), capacity >= index_count. */
RAPS_API raps_status raps_result_copy_indices_u32(const raps_result* result, uint32_t* dst,
                                                  size_t capacity);
/* Copy, per output vertex, the input vertex it comes from; capacity >= vertex_count. */
RAPS_API raps_status raps_result_copy_vertex_remap(const raps_result* result, uint32_t* dst,
                                                   size_t capacity);
/* Copy, per output triangle, its chart (0 .. raps_stats.chart_count - 1); capacity >=
 * index_count / 3. Disk domain: every triangle is in chart 0. */
RAPS_API raps_status raps_result_copy_chart_ids(const raps_result* result, uint32_t* dst,
                                                size_t capacity);

/* Distortion statistics of a result. Definitions (r_t, the per-triangle area ratio, is
 * (uv area / total uv area) / (3D area / total 3D area); averages "weighted" use 3D area; the
 * atlas domain measures in texel space, where its map is isotropic).
 * For a sphere map without uvs "uv" reads "on the sphere": the exact area of the geodesic
 * triangle, the angle between great-circle arcs, flipped when det[a, b, c] < 0 (clockwise seen
 * from outside), and stretch of the flat triangle scaled to its spherical area. With the
 * octahedral unfold they describe the uv map.
 * Caller sets struct_size = sizeof(raps_stats) before the call; the library fills only the
 * fields that fit in struct_size, so a caller built against an older, shorter raps_stats keeps
 * working. Fields are only ever appended. */
typedef struct raps_stats {
    uint32_t struct_size;
    uint32_t reserved;
    uint64_t vertex_count;        /* output vertices */
    uint64_t triangle_count;      /* output triangles */
    uint64_t flipped_triangles;   /* uv triangles with the wrong (clockwise) orientation */
    uint64_t zero_area_triangles; /* |uv area| < 1e-14 * mean |uv area| */
    uint64_t negative_weights;    /* directed edges of the Laplace system with w_ij < 0 */
    uint64_t adaptive_solves;     /* adaptive solves done (0 with RAPS_MONITOR_NONE); atlas: those
                                   * behind the final charts' maps, summed */
    double area_log_mean;         /* weighted mean of |log r_t|; 0 for an area-preserving map */
    double area_max;              /* max over triangles of max(r_t, 1/r_t); 1 is ideal */
    double angle_mean_deg;        /* mean over corners of |uv angle - 3D angle|, degrees */
    double angle_max_deg;         /* max of the same */
    double stretch_l2;            /* Sander et al. 2001 L2 stretch, uv scaled to the 3D area */
    double stretch_linf;          /* Sander's Linf stretch (largest singular value); isometry 1 */
    uint64_t relaxation_sweeps;   /* sweeps of the sphere relaxation, all phases; else 0 */
    uint64_t chart_count;         /* charts (1 for the disk and sphere domains) */
    uint64_t atlas_width;         /* atlas domain: texels; 0 otherwise */
    uint64_t atlas_height;
    double utilization; /* uv area over the unit square ([0,1]^2 after normalising);
                         * texels shared by stacked charts or exact copies of a triangle
                         * count once; 0 for a sphere map without uvs */
    /* Threads the run computed on, the calling thread included: the most that any of its steps
     * shared work among, counting a worker thread only once it has computed a share. 1 when no
     * step was large enough to share (see RAPS_PARAM_THREADS) or no worker could start; at most
     * RAPS_PARAM_THREADS (the hardware's threads for 0). It describes the run, not the map
     * (which is the same bits for any count), and may differ between runs of one input. */
    uint64_t threads_used;
    /* Atlas domain (0 otherwise). Pages: every page is atlas_width x atlas_height texels; a
     * chart's page is in its record (raps_result_get_chart); 1 unless
     * RAPS_PARAM_ATLAS_TEXELS_PER_UNIT is set. utilization is then the mean over pages. */
    uint64_t page_count;
    uint64_t scaled_down_charts; /* charts shrunk below the density to fit a page */
    double texels_per_unit;      /* the atlas's density: texels per world (position) unit */
} raps_stats;

/* Fills stats (see raps_stats). Errors (the message in result, when it is not NULL):
 * INVALID_ARGUMENT (NULL, struct_size < 8), INVALID_OPERATION (the result holds no map). */
RAPS_API raps_status raps_result_get_stats(const raps_result* result, raps_stats* stats);

/* One chart of an atlas, as raps_result_get_chart fills it. Like raps_stats: the caller sets
 * struct_size = sizeof(raps_chart), the library fills what fits, fields are only appended; and
 * like the map, the records are the same bits for every RAPS_PARAM_THREADS value. */
typedef struct raps_chart {
    uint32_t struct_size;
    uint32_t mesh;  /* the input mesh it belongs to (0 for raps_parameterize) */
    uint32_t page;  /* 0 .. raps_stats.page_count - 1 */
    uint32_t flags; /* RAPS_CHART_* bits */
    /* The texels its uv triangles touch on its page (a texture of atlas_width x atlas_height
     * texels mapping the uvs): columns x .. x + width - 1, rows y .. y + height - 1, row 0 at
     * v = 0. */
    uint32_t x;
    uint32_t y;
    uint32_t width;
    uint32_t height;
    double rotation_deg;     /* counter-clockwise turn the packing gave the chart, [0, 360) */
    uint64_t triangle_count; /* output triangles with this chart id */
    double area_3d;     /* surface area, world units squared; an exact copy of a triangle
                         * (the same corners, so the same uvs) counts once */
    double area_texels; /* uv area, texels squared; exact copies count once */
    /* Sander's L2 stretch of the chart's map (scale-free: 1 for an isometry); 0 for the chart
     * that gathers degenerate triangles with no chart beside them. */
    double stretch_l2;
    /* The chart whose texels it shares (RAPS_PARAM_ATLAS_STACK; RAPS_CHART_STACKED is set);
     * its own index when it shares none. */
    uint32_t stacked_on;
    uint32_t reserved;
} raps_chart;

/* raps_chart.flags bits */
enum {
    /* The chart, at the atlas's density, was larger than a page: it was shrunk to fit (its
     * texels per world unit are below raps_stats.texels_per_unit). */
    RAPS_CHART_SCALED_DOWN = 1,
    /* The chart shares the texels of an earlier, congruent chart (raps_chart.stacked_on). */
    RAPS_CHART_STACKED = 2
};

/* Fills `chart` with chart number `index` (a chart id, 0 .. raps_stats.chart_count - 1).
 * Errors (the message in result, when it is not NULL): INVALID_ARGUMENT (NULL, struct_size < 8,
 * index out of range), INVALID_OPERATION (the result holds no atlas). */
RAPS_API raps_status raps_result_get_chart(const raps_result* result, size_t index,
                                           raps_chart* chart);

/* Wall-clock milliseconds the run that filled this result spent in a phase (RAPS_PHASE_*); 0 for
 * a phase it did not enter, for an empty result, for NULL or for an unknown phase. */
RAPS_API double raps_result_phase_ms(const raps_result* result, raps_phase phase);

#ifdef __cplusplus
}
#endif

#endif /* RAPS_H */
