/* The open rope's refinement: resampling along arcs inscribed at the
 * vertices, which never bends the rope more than the coarse polygon did. */
#ifndef TR_REFINE_ARCS_H
#define TR_REFINE_ARCS_H

#include "curve/curve.h"

/* m points (m >= 2) at equal arclength along open component k of c, end
 * vertices kept exactly, written to y (3 m entries). Each edge of the old
 * polygon is replaced by an arc of the circle through three consecutive
 * vertices that contains it: of the two such circles (at either end of
 * the edge) the more curved one, a straight edge where the rope ends.
 * Why: a tight rope's curvature jumps (the clasp's tip K is an arc at
 * MinRad 1 that ends at 0.5 within one edge), and every interpolation that
 * is smooth across the jump (linear resampling's kept corners, a cubic
 * spline, averaged circles) overshoots MinRad there by 4-13 %, which the
 * solver then spends thousands of crawling steps taking back. Three
 * samples on one arc have exactly its curvature; across an old vertex the
 * two arcs, each at least as curved as the vertex's own circle, turn the
 * tangent back, so no new vertex is more curved than the most curved
 * vertex next to it (to first order in the edge; torsion enters at second
 * order). The arcs bulge from the old edges by at most kappa l^2 / 8.
 * TR_ENOMEM or TR_EINVAL, nothing written to y. */
int tr_refine_arcs_open(const tr_curve *c, int k, size_t m, double *y, tr_error *err);

#endif
