// raps.h must compile as C++ (pedantic, warnings as errors) with C linkage for its functions.
#include "raps.h"

#include <cstdio>
#include <type_traits>

static_assert(std::is_same<raps_status, int32_t>::value, "statuses are int32_t");
static_assert(std::is_standard_layout<raps_stats>::value, "raps_stats is a plain C struct");

int main() {
    raps_mesh* mesh = nullptr;
    if (raps_mesh_create(&mesh) != RAPS_OK) return 1;
    raps_mesh_destroy(mesh);
    std::printf("raps %s\n", raps_version_string());
    return raps_version() == RAPS_VERSION ? 0 : 1;
}
