/* The Alexander polynomial and the determinant of a knot, from a PD code
 * (topology/knot_diagram.h makes one from a curve; a name table can give
 * one from KnotInfo).
 *
 * Delta(t) is the determinant of the Alexander matrix of the Wirtinger
 * presentation (Fox calculus; one row per crossing, one column per arc, one
 * of each struck out), defined up to a unit +-t^k; it is returned in
 * Conway's normalisation: symmetric, Delta(t) = Delta(1/t), with
 * Delta(1) = 1. So the trefoil is t^-1 - 1 + t -> (1, -1, 1), the figure
 * eight -t^-1 + 3 - t -> (-1, 3, -1). (Rolfsen's and KnotInfo's tables
 * write it with a positive leading coefficient instead: 1 -3 1 for the
 * figure eight; tr_alexander_equal compares up to that sign.) The
 * determinant is |Delta(-1)|. The mirror image has the same polynomial. */
#ifndef TR_ALEXANDER_H
#define TR_ALEXANDER_H

#include "curve/curve.h"
#include "util/error.h"

/* The largest diagram the exact arithmetic takes: the coefficients of the
 * (n-1)-minor are below 6^((n-1)/2) (Hadamard's bound on |t| = 1, rows of
 * norm^2 <= |1-t|^2 + 1 + 1), under half the product of the two ~2^61
 * primes it is computed modulo while n <= 90. Kinks are removed before,
 * and a tight knot's diagram has a few dozen crossings at most. */
#define TR_ALEXANDER_MAX_CROSSINGS 90

typedef struct tr_alexander {
    /* Coefficients of t^-h .. t^h, h = span / 2: span + 1 numbers,
     * symmetric, summing to 1 (Delta(1) = 1). The unknot: span 0, (1). */
    int span;
    long long coef[TR_ALEXANDER_MAX_CROSSINGS + 1];
    long long determinant; /* |Delta(-1)| */
} tr_alexander;

/* Delta of the knot with PD code pd[0..n-1] (edges 1..2n along the knot,
 * X[a, b, c, d] with a the incoming under edge, c = a+1 the outgoing one,
 * b and d the over strand's edges, as in tr_knot_diagram). n = 0 is the
 * unknot. TR_EINVAL for a code that is not one knot's diagram (edge labels
 * outside 1..2n or not each used twice, an under strand that does not run
 * a -> a+1, an over strand whose edges are not consecutive), with the
 * crossing named; TR_EUNSUPPORTED above TR_ALEXANDER_MAX_CROSSINGS. */
int tr_alexander_from_pd(const int (*pd)[4], int n, tr_alexander *a, tr_error *err);

/* 1 when a and b are the same polynomial up to sign (Conway's or a table's
 * positive-leading-coefficient normalisation). */
int tr_alexander_equal(const tr_alexander *a, const tr_alexander *b);

/* What a curve's knot type is checked by: the diagram's crossing counts,
 * the Alexander polynomial and the signature. */
typedef struct tr_knot_invariants {
    int crossings;           /* the diagram's, after removing kinks */
    int projected_crossings; /* the projection's, kinks included */
    double direction[3];     /* the projection's (topology/knot_diagram.h) */
    tr_alexander alexander;
    int signature;           /* topology/signature.h: KnotInfo's convention */
} tr_knot_invariants;

/* The invariants of curve c (one closed component): tr_knot_diagram_of,
 * then tr_alexander_from_pd and tr_signature_from_pd; the errors are
 * theirs. */
int tr_knot_invariants_of(const tr_curve *c, tr_knot_invariants *inv, tr_error *err);

#endif
