/* The KKT certificate of a tight rope: how far a curve is from a
 * constrained critical point of its length (docs/physics.md 7.1, ridgerunner's
 * "residual"), computed on the curve alone, independently of how it was
 * made (engine, polish, another program).
 *
 * Problem (rope radius r = the oracle's thickness unless given, so any
 * scale works): minimise the polygon length over the vertices x and one
 * common edge length ebar_k per component, subject to
 *   edges    |e_a| - ebar_k = 0                              (free multiplier)
 *   MinRad   |p| - 2 r t >= 0 and |q| - 2 r t >= 0 at every vertex with two
 *            edges (t = tan(theta/2); together Rawdon's MinRad >= r, as the
 *            polish writes them, polish.h)                  (multiplier >= 0)
 *   struts   d(a, b) - 2 r >= 0 for every edge pair not excluded by index
 *            (gap ceil(pi r / ebar_k), as the engine's)      (multiplier >= 0)
 * and the vertex constraints of the file (clasp ends on planes: the force
 * and every row gradient are projected onto the allowed motion).
 * Only rows within `band` (relative) of their bound may carry a multiplier.
 *
 * Certificate: with g the projected length gradient (the tension) and y the
 * multipliers, the resolved force is r(y) = g - J^T y (the ebar part
 * weighted by 1/ne_k, the metric of backend.h); the residual is
 * min |r(y)| / |g| over y with the inequality multipliers >= 0. It is found
 * by projected Newton on the bound-constrained least squares, the free
 * set's least squares solved with a sparse Cholesky factor (rowchol.h).
 * Every iterate keeps y feasible, so the residual reported is attained by
 * admissible multipliers: an upper bound on the exact minimum even when the
 * solve stops early (converged = 0). 0 means the tension is exactly held by
 * compressive struts and curvature; 1 means nothing holds it. */
#ifndef TR_KKT_H
#define TR_KKT_H

#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"

/* Rows within 1e-6 of their bound may hold: a tight knot's contacts sit
 * at ~1e-9 (engine tolerance) while the next ring of near-contacts starts
 * ~1e-5 away at N ~ 400; a wider band lets non-touching rows "hold" and the
 * residual then says nothing (bench/notes/2026-11-23-kkt-certificate.md). */
#define TR_KKT_DEFAULT_BAND 1e-6

typedef struct tr_kkt_params {
    double radius;  /* rope radius r; <= 0: the oracle's thickness of the curve */
    double band;    /* rows with C < band (relative: C/|p|, (d - 2r)/(2r)) may be active */
    int max_outer;  /* active-set rounds */
    double opt_tol; /* converged: projected gradient of the least squares <= opt_tol |g| */
} tr_kkt_params;

void tr_kkt_params_default(tr_kkt_params *p);

typedef struct tr_kkt {
    double residual;     /* |g - J^T y| / |g| (0 if g = 0) */
    double force;        /* |g|, the projected tension */
    double radius;       /* r used */
    size_t strut_rows, minrad_rows;       /* within the band */
    size_t strut_active, minrad_active;   /* with a positive multiplier */
    double strut_force_max;               /* largest strut multiplier (compression) */
    int rounds, solves;  /* active-set rounds; solves with the sparse factors */
    double optimality;   /* projected gradient of the least squares / |g| (row-scaled) */
    int converged;       /* optimality <= opt_tol: y is the minimiser, not just admissible */
} tr_kkt;

int tr_kkt_certify(const tr_curve *c, const tr_kkt_params *p, tr_kkt *out, tr_error *err);

/* The same, and where: tension (3 nv) gets g, the projected tension at
 * every vertex, and unresolved (3 nv) the part of it no row holds, r(y) in
 * vertex space (either may be NULL). A curve that is not critical shows
 * where: |unresolved_i| against |tension_i| (measure --kkt-forces). */
int tr_kkt_certify_forces(const tr_curve *c, const tr_kkt_params *p, tr_kkt *out, double *tension,
                          double *unresolved, tr_error *err);

#endif
