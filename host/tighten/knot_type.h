/* The knot type of a tightening, checked, never assumed (issue 47): the
 * result's invariants against the start's, computed from each curve's own
 * projection (host/topology). A knot (one closed component): the Alexander
 * polynomial, the determinant and the signature; a link of closed
 * components: the linking numbers. A tightening is an isotopy, which keeps
 * the orientation, the components' order and the handedness (a mirror
 * image flips the signature's and the linking numbers' signs), so all are
 * compared exactly.
 * A curve with an open component (a clasp) has no knot type to keep. */
#ifndef TR_TIGHTEN_KNOT_TYPE_H
#define TR_TIGHTEN_KNOT_TYPE_H

#include "curve/curve.h"
#include "topology/alexander.h"
#include "util/error.h"

#define TT_TYPE_MAX_COMPONENTS 16

typedef struct tt_knot_type {
    int kind; /* 0 none (an open component, or not computed), 1 knot, 2 link */
    tr_knot_invariants inv;                                       /* kind 1 */
    int ncomp;                                                    /* kind 2 */
    int lk[TT_TYPE_MAX_COMPONENTS * TT_TYPE_MAX_COMPONENTS];      /* kind 2 */
    char why[1024]; /* kind 0: why not */
} tt_knot_type;

/* c's type; never fails: what cannot be computed (a diagram beyond the
 * exact arithmetic, more components than the table holds) leaves kind 0
 * with the reason in why. */
void tt_knot_type_of(const tr_curve *c, tt_knot_type *t);

/* 1 the same type by these invariants, 0 not; both must have kind > 0 */
int tt_knot_type_same(const tt_knot_type *a, const tt_knot_type *b);

/* what was compared, in one line (kind > 0): "Alexander polynomial 1 -1 1,
 * determinant 3, signature -2" (coefficients of t^-h .. t^h), "linking
 * numbers 1 0 -1" (pairs 01, 02, .., 12, ..) */
void tt_knot_type_line(const tt_knot_type *t, char *buf, size_t n);

#endif
