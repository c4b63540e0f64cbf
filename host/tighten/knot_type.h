/* The knot type of a tightening, checked, never assumed (issue 47): the
 * result's invariants against the start's, each computed from the curve's
 * own projection (knot_start.h tr_type_check_of). A knot: the Alexander
 * polynomial, the determinant and the signature; a link of closed
 * components: the linking numbers and each component's own three. A tightening is an isotopy, which keeps
 * the orientation, the components' order and the handedness (a mirror
 * image flips the signature's and the linking numbers' signs), so all are
 * compared exactly, where a name's check (tr_type_matches) allows a mirror
 * and any order. A curve with an open component (a clasp) has no type to
 * keep. */
#ifndef TR_TIGHTEN_KNOT_TYPE_H
#define TR_TIGHTEN_KNOT_TYPE_H

#include "curve/curve.h"
#include "tighten/knot_start.h"

struct tt_knot_type {
    int known;          /* 1: tc holds the type; 0: not computed, why says why */
    tr_type_check tc;
    char why[1024];
};
typedef struct tt_knot_type tt_knot_type;

/* c's type; never fails: what cannot be computed (an open component, a
 * diagram beyond the exact arithmetic, more components than the check
 * takes) leaves known 0 with the reason. */
void tt_knot_type_of(const tr_curve *c, tt_knot_type *t);

/* 1 the same type by these invariants, 0 not; both must be known */
int tt_knot_type_same(const tt_knot_type *a, const tt_knot_type *b);

#endif
