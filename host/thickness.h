/* The thickness oracle: Rawdon's polygonal thickness and ropelength, as
 * octrope computes them (REFERENCE.md 2), with a uniform-grid neighbour
 * search so the cost is linear in N for tight or smooth curves. */
#ifndef TR_THICKNESS_H
#define TR_THICKNESS_H

#include "curve.h"

/* A strut: a doubly-critical closest-point pair between edges ei and ej,
 * at parameters si, sj in [0,1] along them. Edges are numbered globally as in
 * neighbour_search.h (component 0's edges first; edge l of a component runs
 * from its vertex l to l+1); ei > ej. */
typedef struct tr_strut {
    size_t ei, ej;
    double si, sj;
    double dist;
} tr_strut;

typedef struct tr_thickness {
    size_t vertices;
    double length;      /* L_p, compensated sum */
    double minrad;      /* Rawdon MinRad (interior vertices on open components); INFINITY if straight */
    size_t minrad_vertex;
    double dcsd;        /* shortest doubly-critical self distance; INFINITY if none */
    tr_strut shortest;  /* the strut realising dcsd (valid when dcsd is finite) */
    double thickness;   /* min(minrad, dcsd/2) */
    double ropelength;  /* length / thickness */
    /* The paper's lengths (REFERENCE.md 2.4); NAN unless every component is
     * closed and near-equilateral. */
    double L_p, L_c, L_a;
} tr_thickness;

typedef struct tr_strut_list {
    tr_strut *s;
    size_t n, cap;
} tr_strut_list;

typedef struct tr_thickness_opts {
    /* Also collect every strut with dist <= (1 + strut_rel_tol) * dcsd into the
     * list passed to tr_thickness_measure (octrope's "struts within epsilon"). */
    double strut_rel_tol;
    /* Look at all N^2 edge pairs instead of the tree search (tests). */
    int brute_force;
} tr_thickness_opts;

/* Whole curve. struts may be NULL. */
int tr_thickness_measure(const tr_curve *c, const tr_thickness_opts *opts, tr_thickness *out,
                         tr_strut_list *struts, tr_error *err);

/* One component on its own (as if the others were absent). */
int tr_thickness_measure_component(const tr_curve *c, int k, tr_thickness *out, tr_error *err);

void tr_strut_list_free(tr_strut_list *l);

/* Closest points of segments a0-a1 and b0-b1 (octrope's find_poca, Lumelsky's
 * method): returns the distance, parameters s on a and t on b in [0,1].
 * Parallel overlapping segments get the middle of the overlap. */
double tr_segment_closest(const double *a0, const double *a1, const double *b0, const double *b1,
                          double *s, double *t);

#endif
