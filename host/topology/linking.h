/* Linking numbers of a link's closed components: in a projection along a
 * generic direction, the signs of the crossings where component i passes
 * over component j sum to lk(i, j) (knot_diagram.h's sign convention;
 * edges swept along one axis, ~N log N). A direction is used only when
 * every crossing is well inside both edges and the strands are clearly
 * apart in height and not parallel in projection; where none of a fixed
 * few is, the Gauss integral, exactly for polygons (the sum over edge
 * pairs of the signed solid angle each subtends, Klenin and Langowski
 * 2000, Biopolymers 54:307; O(N_i N_j)), an integer up to rounding. */
#ifndef TR_LINKING_H
#define TR_LINKING_H

#include "curve/curve.h"

/* lk[i * ncomp + j]: the linking number of closed components i and j (the
 * components' own orientation), 0 on the diagonal; lk has ncomp^2 entries.
 * TR_EINVAL for an open component or a coordinate that is not finite;
 * TR_EGEOMETRY when the Gauss sum is not within 0.05 of an integer (two
 * components touch or cross). */
int tr_linking_numbers(const tr_curve *c, int *lk, tr_error *err);

#endif
