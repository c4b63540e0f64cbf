/* The thickness oracle: Rawdon's polygonal thickness and ropelength, as
 * octrope computes them (docs/physics.md 2), with a tree neighbour search
 * (neighbour_search.h) so the cost is linear in N for tight or smooth curves.
 *
 * octrope's conventions, kept: MinRad(v) = min(|a|,|b|) (|a||b| + a.b) /
 * (2 |a x b|) over all vertices of closed components and the interior ones of
 * open components; a strut is the closest-point pair of two edges (Lumelsky,
 * octrope's find_poca) with s < 1 and t < 1 (except at the free end of an open
 * component), and at s = 0 (t = 0) the partner point in the normal wedge of
 * that vertex; same-component pairs closer in index than pi_count =
 * max(2, floor(pi / max turning angle)) are skipped; thickness =
 * min(MinRad, dcsd/2) (lambda = 1). A consequence: the critical pair of a
 * vertex and the opposite edge of an odd regular polygon is not a strut (it is
 * not the closest pair of any two edges), so such a polygon has dcsd = inf.
 *
 * Deliberate differences, none of which shows on the 249 TightKnot knots:
 *  - a vertex is straight (skipped in MinRad) when |a x b| <= 1e-12 |a||b|;
 *    octrope's absolute |a x b| < 1e-12 skips every vertex once edges are
 *    ~1e-5 long and loses MinRad at N ~ 10^6; a vertex where the edges are
 *    antiparallel (a hairpin, a.b < 0) is not straight but a cusp: MinRad 0,
 *    so thickness 0 (octrope would skip it and call the fold infinitely thick);
 *  - exactly parallel edges (|d1 x d2|^2 < 1e-20 |d1|^2 |d2|^2, computed as a
 *    cross product in long double) get the middle of their overlap as closest
 *    pair; octrope takes s = 0, lands on a vertex and misses the strut between
 *    overlapping parallel edges (opposite edges of a rectangle or an even
 *    regular polygon);
 *  - lengths are compensated (Neumaier) sums. */
#ifndef TR_THICKNESS_H
#define TR_THICKNESS_H

#include "curve/curve.h"
#include "util/clock.h"

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
    /* The paper's lengths (docs/physics.md 2.4); NAN unless every component is
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
    /* NULL: none. Else the measure stops with TR_EINTERRUPTED once it has
     * passed (its searches look at it as they go): a start of 10^7
     * vertices is tens of seconds a measure, within a --time-limit. */
    const tr_deadline *bound;
} tr_thickness_opts;

/* Whole curve. struts may be NULL. */
int tr_thickness_measure(const tr_curve *c, const tr_thickness_opts *opts, tr_thickness *out,
                         tr_strut_list *struts, tr_error *err);

/* One component on its own (as if the others were absent). */
int tr_thickness_measure_component(const tr_curve *c, int k, tr_thickness *out, tr_error *err);

void tr_strut_list_free(tr_strut_list *l);

/* The thickness against a gate, for many measures of one topology: the
 * crankshaft shuffle (tighten/shuffle.c) asks 10^5 times of a rope of ~100
 * vertices a component whether a move keeps its thickness at or above a
 * gate, and what the thickness is if so. Where the thickness is >= gate
 * *thickness is tr_thickness_measure's, bit for bit (the same MinRad, the
 * same strut test and pi_count rule, every pair looked at); below the gate
 * the evaluation stops at the first vertex or strut that proves it and gives
 * that number (< gate, at or above the thickness). A curve through itself
 * gets 0 (the measure refuses it); a curve the measure refuses otherwise
 * (not finite, beyond the doubles' resolution) is refused alike, and one the
 * measure takes to another frame is measured by it. The pairs are
 * enumerated, pruned by the edges' midpoints: O(N^2), for N of a few
 * hundred, where the measure's tree costs more than it saves. c's topology
 * (components, closed, counts) is copied and must outlive the gate; its
 * coordinates are each evaluation's x (3 nv doubles, no low parts). */
typedef struct tr_thickness_gate tr_thickness_gate;
int tr_thickness_gate_new(const tr_curve *c, tr_thickness_gate **out, tr_error *err);
int tr_thickness_gate_eval(tr_thickness_gate *g, const double *x, double gate, double *thickness, tr_error *err);
void tr_thickness_gate_free(tr_thickness_gate *g);

/* Closest points of segments a0-a1 and b0-b1 (octrope's find_poca, Lumelsky's
 * method): returns the distance, parameters s on a and t on b in [0,1].
 * Parallel overlapping segments get the middle of the overlap. */
double tr_segment_closest(const double *a0, const double *a1, const double *b0, const double *b1,
                          double *s, double *t);

#endif
