/* Curvature and torsion of the inscribed-arc knot K_c built on a closed
 * polygon (docs/physics.md 3.2, 3.3). K_c is a chain of circular arcs, one per
 * vertex, so curvature is constant on each arc and torsion lives only at the
 * junctions between arcs, as the signed angle between osculating planes. */
#ifndef TR_ARC_PROFILE_H
#define TR_ARC_PROFILE_H

#include <stddef.h>

#include "util/error.h"

typedef struct tr_arc_profile {
    size_t n;       /* arcs = polygon vertices */
    double L;       /* period of the position coordinate */
    double *pos;    /* position of arc k (its vertex), as given by the caller */
    double *kappa;  /* curvature of arc k: 2 tan(theta/2) / min(|f_{k-1}|, |f_k|); 0 if straight */
    double *dl;     /* length of arc k, r theta */
    double *jpos;   /* position of junction k, between arc k and arc k+1 (on edge f_k) */
    double *phi;    /* signed angle between the osculating planes of arcs k and k+1 (> 0 right-handed) */
    double *tau;    /* phi_k / h_k, h_k = K_c arclength from the middle of arc k to the middle of arc k+1 */
    double *alpha;  /* accumulated torsion: sum of phi over junctions 0..k */
    double L_c;     /* length of K_c: arcs plus straight gaps */
    size_t nj;      /* junctions: n when closed, n - 1 on an open rope */
    int closed;
} tr_arc_profile;

/* w: closed polygon of n >= 4 vertices; pos[k]: the coordinate of vertex k
 * (e.g. tr_averaged_knot.pos, arclength of the input polygon), or NULL for the
 * polygon's own arclength; L: the period of pos (ignored when pos is NULL). */
int tr_arc_profile_compute(const double *w, size_t n, const double *pos, double L,
                           tr_arc_profile *out, tr_error *err);
/* An open rope w of n >= 4 vertices: arcs at the n - 2 interior vertices
 * (an end vertex has no turning angle), junctions between consecutive arcs
 * (nj = n - 3); positions are arclength from vertex 0, L the rope's length. */
int tr_arc_profile_compute_open(const double *w, size_t n, tr_arc_profile *out, tr_error *err);
void tr_arc_profile_free(tr_arc_profile *p);

#endif
