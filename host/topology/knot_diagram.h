/* The knot diagram of a closed curve: a generic projection, its crossings
 * with over and under from the heights, and the Gauss and PD codes.
 *
 * The knot type of a tightened curve must be checked, never assumed (issue
 * 47): the invariants (topology/alexander.h) are computed from a diagram,
 * and the diagram from the curve's own vertices. A projection is generic
 * when every crossing of the projected polygon is a transverse crossing of
 * two edge interiors, well away from their end vertices and from every
 * other crossing, with the two strands at clearly different heights; only
 * then do rounding errors leave the diagram the polygon's own (the test is
 * spelt out in knot_diagram.c). */
#ifndef TR_KNOT_DIAGRAM_H
#define TR_KNOT_DIAGRAM_H

#include <stddef.h>

#include "curve/curve.h"

/* How many projection directions are tried (a fixed list drawn from a
 * splitmix64 stream with a fixed seed, the same on every machine); the
 * generic one with the fewest crossings is kept. */
#define TR_DIAGRAM_DIRECTIONS 8

typedef struct tr_knot_diagram {
    /* Crossings of the diagram after removing the kinks (Reidemeister I
     * loops: a crossing whose two passages follow each other along the
     * curve, with no crossing between them), numbered 0..ncross-1 in the
     * order the curve first meets them from its vertex 0. */
    int ncross;
    /* Crossings of the projection itself, kinks included. */
    int projected_crossings;
    /* 2 ncross entries, the passages in curve order: c+1 when the curve
     * passes over crossing c, -(c+1) when it passes under. */
    int *gauss;
    /* ncross entries: +1 for a right-handed crossing (seen from the
     * viewer, turning the over strand counterclockwise by less than pi
     * brings it onto the under strand), -1 for a left-handed one. */
    signed char *sign;
    /* ncross entries X[a, b, c, d], KnotTheory's convention: the edges
     * between passages are numbered 1..2 ncross along the curve (edge k
     * runs from passage k-1 to passage k, edge 1 leaves the last passage),
     * a is the incoming under edge, c = a+1 the outgoing one, and a, b, c,
     * d go counterclockwise around the crossing; so X[i, j+1, i+1, j] for a
     * right-handed crossing and X[i, j, i+1, j+1] for a left-handed one. */
    int (*pd)[4];
    /* The projection: the viewer looks from +direction down onto the
     * plane; direction_index is its place in the list of candidates. */
    double direction[3];
    int direction_index;
} tr_knot_diagram;

/* The diagram of curve c: one closed component (several components, a link,
 * give TR_EUNSUPPORTED; an open one TR_EINVAL), finite coordinates, at least
 * 3 vertices. TR_EGEOMETRY when none of the TR_DIAGRAM_DIRECTIONS
 * directions is generic (the curve passes through or within ~1e-10 of its
 * extent of itself, or is degenerate), with the reason. d is zeroed first;
 * free it with tr_knot_diagram_free (also after a failure). */
int tr_knot_diagram_of(const tr_curve *c, tr_knot_diagram *d, tr_error *err);

/* The diagram of curve c seen from the given direction (need not be unit),
 * TR_EGEOMETRY when that projection is not generic: for tests and for a
 * caller that wants a second opinion from a direction of its own. */
int tr_knot_diagram_along(const tr_curve *c, const double direction[3], tr_knot_diagram *d, tr_error *err);

void tr_knot_diagram_free(tr_knot_diagram *d);

#endif
