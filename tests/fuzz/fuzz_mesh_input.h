/* The byte layout of one input of the mesh fuzz target (fuzz_mesh_api.c): what a run through the
 * C ABI gets (domain, settings, positions, indices, a cancelling callback), decoded from
 * arbitrary bytes so that every byte string is a valid input. The seed writer (make_fuzz_seeds)
 * encodes meshes into the same layout, so both sides live here.
 *
 *   offset  size  field
 *   0       1     domain (value % 3: disk, sphere, atlas)
 *   1       1     flags (FUZZ_FLAG_*)
 *   2       1     bytes of padding after each point (value % 16)
 *   3       1     settings (value % 16), each 9 bytes after the header
 *   4       2     points (little endian)
 *   6       1     cancel at this progress call (with FUZZ_FLAG_CANCEL; 0 = the first call)
 *   7       1     polygons (fuzz_mesh_api.c): 0 none; else bits 0-1 how the ids are made from
 *                 the triangles and bits 2-7 a parameter k
 *   8       9n    settings: a selector byte (bits 0-5: parameter id 0..63; bit 6: for an unknown
 *                 id, set it as a float; bit 7: map the value into the parameter's bounds), then
 *                 8 bytes: an int64 or the bits of a double, little endian
 *   ...           points: 3 coordinates (f32, or f64 with FUZZ_FLAG_F64), then the padding
 *   ...           the rest: indices (u32, or u16 with FUZZ_FLAG_U16); a partial last one dropped
 *
 * Everything is little endian (coordinates and indices as the machine stores them: the targets
 * run on little-endian x86-64 and AArch64). Missing bytes read as zero and a short input has fewer
 * points than it asks for, so truncating an input (as fuzzers do) keeps it meaningful. */
#ifndef RAPS_FUZZ_MESH_INPUT_H
#define RAPS_FUZZ_MESH_INPUT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    FUZZ_FLAG_F64 = 1,               /* positions are doubles */
    FUZZ_FLAG_U16 = 2,               /* indices are uint16 */
    FUZZ_FLAG_HUGE_VERTEX_COUNT = 4, /* also claim 2^31 or more points (must be refused unread) */
    FUZZ_FLAG_HUGE_INDEX_COUNT = 8,  /* also claim 3 * 2^31 or more indices (the same) */
    FUZZ_FLAG_INDICES_FIRST = 16,    /* set the indices before the positions */
    FUZZ_FLAG_CANCEL = 32,           /* a progress callback that cancels at call cancel_at */
    FUZZ_FLAG_RUN_TWICE = 64,        /* a second run must give the same bits */
    FUZZ_FLAG_CORNER_UVS = 128       /* corner uvs from the points, repacked (fuzz_mesh_api.c) */
};

enum { FUZZ_HEADER_BYTES = 8, FUZZ_SETTING_BYTES = 9, FUZZ_MAX_SETTINGS = 16 };

/* A selector bit: the 8 value bytes are mapped into the parameter's bounds. */
#define FUZZ_SETTING_IN_BOUNDS 0x80u
/* A selector bit: an unknown parameter id is set with raps_settings_set_float. */
#define FUZZ_SETTING_AS_FLOAT 0x40u

typedef struct fuzz_setting {
    uint8_t selector;
    uint64_t raw; /* an int64 or a double's bits */
} fuzz_setting;

typedef struct fuzz_mesh_input {
    uint8_t domain;
    uint8_t flags;
    uint8_t point_padding;
    uint8_t cancel_at;
    uint8_t polygons;
    size_t setting_count;
    fuzz_setting settings[FUZZ_MAX_SETTINGS];
    size_t point_count;     /* points present in `points` */
    size_t point_stride;    /* bytes from one point to the next */
    const uint8_t* points;  /* inside the decoded bytes: unaligned */
    size_t index_count;     /* whole indices present in `indices` */
    const uint8_t* indices; /* inside the decoded bytes: unaligned */
} fuzz_mesh_input;

/* Reads `size` bytes into *input (pointers into `data`). Every byte string decodes. */
void fuzz_mesh_input_decode(const uint8_t* data, size_t size, fuzz_mesh_input* input);

/* What the seed writer encodes: a mesh, its domain and settings. */
typedef struct fuzz_mesh_seed {
    uint8_t domain;
    uint8_t flags; /* FUZZ_FLAG_F64 and FUZZ_FLAG_U16 choose how the mesh is stored */
    uint8_t point_padding;
    uint8_t cancel_at;
    uint8_t polygons;
    size_t setting_count;
    fuzz_setting settings[FUZZ_MAX_SETTINGS];
    const double* positions; /* x, y, z per vertex */
    size_t vertex_count;     /* at most 65535 */
    const uint32_t* indices;
    size_t index_count;
} fuzz_mesh_seed;

/* An int or float setting as a seed stores it (exact value, selector bit 7 clear). */
fuzz_setting fuzz_int_setting(int32_t param, int64_t value);
fuzz_setting fuzz_float_setting(int32_t param, double value);

/* Encodes *seed; returns a malloc'ed buffer (free()) of *size bytes, or NULL when out of memory
 * or the mesh does not fit the layout (more than 65535 vertices). */
uint8_t* fuzz_mesh_seed_encode(const fuzz_mesh_seed* seed, size_t* size);

#ifdef __cplusplus
}
#endif

#endif
