/* The m-averaged knot K_p^(m) (docs/physics.md 3.1): block averages of m
 * consecutive vertices, which suppress the discretisation artefacts of the
 * full-resolution polygon before curvature and torsion are read off. */
#ifndef TR_SHAPE_AVERAGE_H
#define TR_SHAPE_AVERAGE_H

#include <stddef.h>

#include "util/error.h"

typedef struct tr_averaged_knot {
    size_t n;      /* vertices w_k */
    size_t m;      /* block size (1 = the input polygon itself) */
    double *w;     /* 3n coordinates */
    double *pos;   /* where w_k sits: input-polygon arclength of its block centre, in [0, L) */
    double L;      /* length of the input polygon */
} tr_averaged_knot;

/* x: closed polygon of n vertices. Blocks start at vertex `first` (so a chosen
 * vertex can be made a block centre). If m does not divide n, the polygon is
 * first resampled at equal arclength to floor(n/m)*m points starting at
 * vertex `first`. Needs at least 4 blocks. */
int tr_shape_average(const double *x, size_t n, size_t m, size_t first, tr_averaged_knot *out,
                     tr_error *err);
void tr_averaged_knot_free(tr_averaged_knot *k);

#endif
