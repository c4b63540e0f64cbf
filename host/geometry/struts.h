/* This file contains the rules about struts that the engine, the polish,
 * the second-order solver and the KKT certificate share: the candidate
 * list of the polish and the solver; which pairs of edges of one component are
 * too close along the curve to be a strut (the exclusion gap), and the
 * gradient of a strut's length with respect to its four end points. */
#ifndef TR_STRUTS_H
#define TR_STRUTS_H

#include <stddef.h>

#include "geometry/neighbour_search.h"
#include "util/error.h"

/* The exclusion gap of a component of mean edge length ebar for a rope of
 * radius r: ceil(pi r / ebar) edges, at least 2 (and 2 where ebar is not
 * positive), at most 10^9. A curve whose radius of curvature is at least r
 * (MinRad >= r) cannot come back to within 2 r of itself before it has run
 * the arclength pi r of a half circle of radius r, so two edges closer than
 * that along the curve are neighbours, never a strut (docs/physics.md). */
int tr_exclusion_gap(double radius, double ebar);

/* The gradient of the distance d = |P(s) - Q(t)| of the edges pa-pan and
 * pb-pbn (s, t, d as tr_segment_distance returns them; d > 0) with respect to
 * pa, pan, pb and pbn, times `scale`, given the connector c = P(s) - Q(t):
 * with n = scale c / d, g[0] = (1 - s) n, g[1] = s n, g[2] = -(1 - t) n,
 * g[3] = -t n. The closest points' parameters do not move to first order
 * (they minimise the distance), so the gradient is that of |P - Q| at fixed
 * s and t. The caller forms c: the KKT certificate and the polish round it
 * differently (their results are kept to the bit). */
void tr_strut_gradient(const double c[3], double s, double t, double d, double scale,
                       double g[4][3]);

/* A candidate strut: the edges starting at vertices a < b, and the
 * multiplier the caller's augmented Lagrangian gives it. */
typedef struct tr_strut_pair {
    size_t a, b;
    double lam;
} tr_strut_pair;

/* Orders pairs by (a, b), for qsort and bsearch. */
int tr_strut_pair_cmp(const void *x, const void *y);

/* Appends the pair of edges a, b (as a < b, multiplier 0) to the growable
 * list *p of *n pairs, room for *cap. Returns 0, or -1 out of memory (the
 * list left as it was). */
int tr_strut_pair_append(tr_strut_pair **p, size_t *n, size_t *cap, size_t a, size_t b);

/* Gives each pair of to (sorted, nto) that is also in from (sorted, nfrom)
 * the multiplier it has there. */
void tr_strut_pairs_carry(const tr_strut_pair *from, size_t nfrom, tr_strut_pair *to, size_t nto);

/* Every pair of edges of the curve in ns (positions x, edge a from a to
 * next[a]) not excluded by its component's gap (gap[k], along the curve)
 * and closer than cutoff, sorted by (a, b); a pair also in *list (sorted,
 * n_list pairs) keeps its multiplier, a new one gets 0. *list is replaced
 * (freed and reallocated); on error it is left as it was. */
int tr_strut_candidates(const tr_nsearch *ns, const double *x, const size_t *next, const int *gap, int ncomp,
                        double cutoff, tr_strut_pair **list, size_t *n_list, tr_error *err);

#endif
