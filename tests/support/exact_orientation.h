/* The sign of det[a, b, c] of three points given as doubles, computed exactly: what "folded"
 * means for a spherical map in the tests (det <= 0), independent of how the library rounds its
 * own determinant. Needed because a . (b x c) in floating point rounds by about 1e-16 whatever
 * the triangle's size, while the triangles of a squeezed limb have determinants of 1e-17 and
 * less: there the rounded sign is noise (docs/sphere-status.md). */
#pragma once

#ifdef __cplusplus
extern "C" {
#endif

/* +1, 0 or -1: the sign of the exact determinant of the rows a, b, c. */
int exact_orientation_sign(const double* a, const double* b, const double* c);

#ifdef __cplusplus
}
#endif
