/* An atlas result as the tests read it through the C ABI, and the checks every atlas must pass:
 * every input triangle present over the right input vertices, uvs in [0,1]^2, no uv triangle
 * flipped or squashed, no two charts sharing a texel or closer than the padding, no texel
 * centre covered twice within a chart (checked by rasterising the atlas at its texel size). */
#ifndef RAPS_TEST_ATLAS_CHECKS_H
#define RAPS_TEST_ATLAS_CHECKS_H

#include <stddef.h>
#include <stdint.h>

#include "raps.h"
#include "test_meshes.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct atlas {
    size_t vertex_count, index_count;
    float* uv;
    uint32_t* indices;
    uint32_t* remap;
    uint32_t* chart;
    raps_stats stats;
} atlas;

/* The result's uvs, indices, vertex remap, chart ids and stats, copied (atlas_free frees). */
atlas atlas_of(const raps_result* result);
void atlas_free(atlas* a);

void check_atlas_structure(const test_mesh* mesh, const atlas* a);
void check_atlas_overlap(const test_mesh* mesh, const atlas* a, int padding);

#ifdef __cplusplus
}
#endif

#endif
