/* Starts for knots and links given by notation (issue 47): a braid closure
 * (curve/braid_closure.h) or a PD code's drawing (curve/pd_layout.h),
 * relaxed, made equilateral and scaled for a rope of radius 1,
 * and the check that a curve is of the knot or link type it is said to be. */
#ifndef TR_KNOT_START_H
#define TR_KNOT_START_H

#include <stddef.h>

#include "curve/curve.h"
#include "topology/knot_table.h"

/* The thickness a start is scaled to: above 1 (the rope's radius), so the
 * engine has room to move before any strut touches. */
#define TR_KNOT_START_THICKNESS 1.25
/* The edge length a start's default vertex count aims at: short enough
 * that tighten's route for a loose start (cli_tighten.c choose_route:
 * tighten from N / 4 vertices, refine back to N) still has edges below 1
 * at N / 4. */
#define TR_KNOT_START_EDGE 0.22

/* The closure of braid b with n vertices in all (0: as many as make edges
 * of about TR_KNOT_START_EDGE), shared among the components by length,
 * equilateral per component, scaled so that its thickness (the oracle's,
 * thickness.h) is TR_KNOT_START_THICKNESS; *thickness gets the measured
 * value, never below 1. TR_EINVAL when n is too small for edges <= 1 or
 * below 8 per component. */
int tr_knot_start_from_braid(const tr_braid *b, size_t n, int relax, tr_curve *out, double *thickness, int *relaxed,
                             tr_error *err);

/* A dense closed curve relaxed (geometry/relax.h: strands pushed apart, none
 * through another) and drawn densely again along a spline, for
 * tr_knot_start_from_curve; *relaxed 0 and a copy where the curve is too
 * crowded for the relaxation's polygon (knot_start.c, RELAX_MAX_N). relax 1
 * in tr_knot_start_from_braid does this to the closure first, *relaxed
 * saying whether it was. */
int tr_knot_start_relaxed(const tr_curve *dense, tr_curve *out, int *relaxed, tr_error *err);

/* A polygon that is the knot exactly however crowded (a PD code's
 * straight-line drawing, tr_make_pd_polygon) relaxed without a resampling
 * that could cut a strand, and drawn densely along a spline, for
 * tr_knot_start_from_curve. */
int tr_knot_start_polygon_relaxed(const tr_curve *poly, tr_curve *out, tr_error *err);

/* The same for any smooth closed curve given as a dense polygon (the PD
 * code's layout, curve/pd_layout.h): resampled to n equal edges per
 * component (0: the default), scaled to TR_KNOT_START_THICKNESS. */
int tr_knot_start_from_curve(const tr_curve *dense, size_t n, tr_curve *out, double *thickness, tr_error *err);

/* What a curve's type came to, and whether it matches an entry's. */
/* the most components the type check takes (their pairs fill linking[]) */
#define TR_TYPE_CHECK_MAX_COMPONENTS 5
_Static_assert(TR_TABLE_MAX_PAIRS >= TR_TYPE_CHECK_MAX_COMPONENTS * (TR_TYPE_CHECK_MAX_COMPONENTS - 1) / 2,
               "linking[] holds every pair of components");
typedef struct tr_type_check {
    int components;
    /* knots */
    tr_knot_invariants inv;
    /* links: linking numbers of pairs (0,1), (0,2) ..., (1,2) ... */
    int npairs;
    int linking[TR_TABLE_MAX_PAIRS];
    /* links: each component's own knot type, in the curve's order (the
     * table lists none, so only a start and its result compare them);
     * comp_known[k] 0 where the component's diagram is beyond the exact
     * arithmetic (the link's check then rests on the linking numbers) */
    tr_knot_invariants comp[TR_TYPE_CHECK_MAX_COMPONENTS];
    int comp_known[TR_TYPE_CHECK_MAX_COMPONENTS];
} tr_type_check;

/* The invariants of c: for one closed component the Alexander polynomial and
 * determinant of a generic projection; for several the component count, the
 * pairwise linking numbers and each component's own invariants. Errors are
 * the topology layer's. */
int tr_type_check_of(const tr_curve *c, tr_type_check *tc, tr_error *err);

/* 1 when tc matches entry e: a knot's Alexander polynomial (up to sign),
 * determinant and signature up to sign (a name stands for a knot and its
 * mirror image; tr_type_is_mirror tells which, where the signature can); a link's
 * component count and linking numbers up to the components' order and
 * orientation (their absolute values as a multiset, the table's orientation
 * being one of several). On a mismatch why gets what differs. */
int tr_type_matches(const tr_type_check *tc, const tr_table_entry *e, char *why, size_t whysize);

/* 1 when tc (a knot's) has PD code pd's Alexander polynomial and its
 * signature, sign included; 0 not; -1 with err when the code's invariants
 * cannot be computed */
int tr_pd_type_matches(const tr_type_check *tc, const tr_pd *pd, tr_error *err);

/* 1 when tc has the opposite, nonzero signature of knot e's: the mirror
 * image of the knot KnotInfo draws. */
int tr_type_is_mirror(const tr_type_check *tc, const tr_table_entry *e);

/* The invariants in words: "Alexander polynomial 1 -1 1, determinant 3,
 * signature -2" or
 * "2 components, linking numbers 1". */
void tr_type_describe(const tr_type_check *tc, char *buf, size_t bufsize);

#endif
