/* A knot's PD code laid out as a space curve (issue 47: `make knot --pd`).
 *
 * The diagram is a 4-valent plane graph: the crossings are its vertices,
 * the PD code's edge labels its edges, and the order a, b, c, d of each
 * crossing (counterclockwise) its rotation system, from which the faces
 * follow (a code whose faces do not number crossings + 2 is no plane
 * diagram). Every edge is cut into LAYOUT_SUB pieces, a node put in every
 * face but the largest and joined to all of that face's nodes, the largest
 * face's nodes fixed on a circle (one whose boundary meets no crossing
 * twice) and every other node placed at the mean of its neighbours: Tutte's
 * barycentric drawing, turned over if it came out as the mirror image of
 * the code's cyclic orders. The knot then runs along its
 * edges in label order, at height +h where it passes over a crossing, -h
 * where under, 0 between, through a periodic cubic spline of those points.
 * Kinks (a face of one edge) and nugatory crossings leave no such drawing
 * and are refused. The caller checks the result's knot type against the
 * code's own (alexander.h): a layout gone wrong is an error, not a knot. */
#ifndef TR_PD_LAYOUT_H
#define TR_PD_LAYOUT_H

#include "curve/curve.h"

/* The curve of PD code pd[0..n-1] (labels 1..2n along the knot, as
 * knot_notation.h checks them), one closed component of about `dense`
 * vertices, equal chords, unscaled (the drawing spans the unit disc).
 * TR_EINVAL for a code that is not a plane diagram or that this drawing
 * cannot lay out, with the reason. */
int tr_make_pd_layout(tr_curve *out, const int (*pd)[4], int n, size_t dense, tr_error *err);

/* The polygon that spline is drawn through: the crossings and the edges'
 * LAYOUT_SUB - 1 pieces' nodes (2n LAYOUT_SUB vertices in label order),
 * lifted at the crossings. Straight segments of a plane straight-line
 * drawing meet only at its nodes, so this polygon is the code's knot
 * exactly (the spline through it may stray where the drawing is
 * crowded). */
int tr_make_pd_polygon(tr_curve *out, const int (*pd)[4], int n, tr_error *err);

#endif
