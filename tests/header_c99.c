/* raps.h must compile as strict C99 with every warning an error, and link. */
#include "raps.h"

#include <stdio.h>

int main(void) {
    raps_stats stats;
    raps_progress_fn fn = NULL;
    stats.struct_size = (uint32_t)sizeof(stats);
    (void)fn;
    if (raps_version() != RAPS_VERSION) return 1;
    printf("raps %s, raps_stats %u bytes\n", raps_version_string(), (unsigned)stats.struct_size);
    return 0;
}
