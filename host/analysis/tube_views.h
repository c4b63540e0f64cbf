/* The viewpoints of the tube pictures (tube_script.h): three orthographic
 * cameras at right angles. The front view looks along the knot's threefold
 * axis when analyze found one, so the trefoil shows its symmetry; else
 * along the direction in which the knot is thinnest (its smallest principal
 * axis of gyration, a twofold axis when one is within 10 degrees of it), so
 * it is seen flat and its crossings are readable. A twofold axis across the
 * front one points up. The top view looks down on it and the side view
 * from its right. */
#ifndef TR_TUBE_VIEWS_H
#define TR_TUBE_VIEWS_H

#include <stddef.h>

#include "analysis/symmetry.h"

/* A camera: orthonormal and right-handed (right x up = toward); the image
 * shows (p - centre).right across and (p - centre).up upwards, and depth
 * grows along toward, which points at the viewer. */
typedef struct tr_view {
    double right[3], up[3], toward[3];
} tr_view;

enum { TR_VIEW_FRONT, TR_VIEW_TOP, TR_VIEW_SIDE, TR_NVIEWS };

typedef struct tr_tube_views {
    double centre[3];        /* the vertices' centroid */
    tr_view v[TR_NVIEWS];
    const char *front_axis;  /* what the front view looks along, in words */
} tr_tube_views;

/* x: one closed component of n >= 3 vertices; sym: its symmetry as analyze
 * found it (may be NULL: no symmetry). */
void tr_tube_views_choose(const double *x, size_t n, const tr_symmetry *sym, tr_tube_views *out);

#endif
