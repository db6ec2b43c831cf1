/* Parameterizes a square of two triangles through the installed library. */
#include <raps.h>
#include <stdio.h>

int main(void) {
    const float xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3};
    raps_mesh* mesh = NULL;
    raps_result* result = NULL;
    float uv[8];
    if (raps_mesh_create(&mesh) || raps_result_create(&result)) return 1;
    if (raps_mesh_set_positions_f32(mesh, xyz, 4, 0) || raps_mesh_set_indices_u32(mesh, tri, 6)) {
        return 2;
    }
    if (raps_parameterize(mesh, NULL, result) != RAPS_OK) {
        fprintf(stderr, "%s\n", raps_result_last_error(result));
        return 3;
    }
    if (raps_result_copy_uvs_f32(result, uv, 4, 0) != RAPS_OK) return 4;
    printf("raps %s: uv[0] = (%.3f, %.3f)\n", raps_version_string(), uv[0], uv[1]);
    raps_result_destroy(result);
    raps_mesh_destroy(mesh);
    return 0;
}
