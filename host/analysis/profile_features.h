/* Features read off a curvature/torsion profile: the kappa = 1 plateaus
 * (where the rope is bent as tightly as its thickness allows) and jumps of
 * kappa and of the accumulated torsion alpha at a point, measured by one-sided
 * fits (docs/physics.md 3.4). */
#ifndef TR_PROFILE_FEATURES_H
#define TR_PROFILE_FEATURES_H

#include <stddef.h>

#include "analysis/arc_profile.h"
#include "util/error.h"

typedef struct tr_plateau {
    size_t first, last;  /* arcs first..last (cyclic) all have kappa >= kappa_max (1 - eps) */
    double l1, l2;       /* ends: the outer edges of the first and last arc, in position units */
} tr_plateau;

/* Maximal cyclic runs of arcs with kappa >= level, at least min_arcs long.
 * *out is allocated (free()), *nout may be 0. A profile that is all plateau
 * (a circle of radius 1/level) gives one run with first = 0, last = n-1. */
int tr_profile_find_plateaus(const tr_arc_profile *p, double level, size_t min_arcs, tr_plateau **out,
                             size_t *nout, tr_error *err);

/* Plateaus with a margin: maximal cyclic runs of arcs with kappa >=
 * edge_level that hold at least min_core arcs with kappa >= core_level
 * (edge_level <= core_level). A tight polygon short of convergence dips by
 * 1e-5..5e-3 at single arcs of its plateau (the solver's N = 9600 trefoil:
 * 22 runs at 1 - 1e-6 for 6 plateaus); a jump at a plateau's end (0.1 or
 * more for the trefoil) clears the margin, so the ends stay at the jumps.
 * edge_level = core_level is tr_profile_find_plateaus. */
int tr_profile_find_plateaus_margin(const tr_arc_profile *p, double core_level, double edge_level,
                                    size_t min_core, tr_plateau **out, size_t *nout, tr_error *err);

typedef enum tr_jump_quantity { TR_JUMP_KAPPA = 0, TR_JUMP_ALPHA = 1 } tr_jump_quantity;

typedef struct tr_jump {
    double at;           /* where it was measured */
    double left, right;  /* one-sided extrapolations to `at`: quadratics over [w, 2W - w]
                            (lines over [w, W] when a side has fewer than 5 points there) */
    double jump;         /* right - left */
    double err;          /* sqrt(statistical^2 + model^2): standard errors of both intercepts,
                            and the change when lines over [w, W] replace the quadratics */
    size_t nleft, nright;
} tr_jump;

/* Fits quadratics to the quantity on [at - (2W - w), at - w] and
 * [at + w, at + 2W - w] (periodic distances, neighbours averaged in pairs)
 * and extrapolates both to `at`; lines on [at - W, at - w], [at + w, at + W]
 * are the model check. Kappa is sampled at the
 * arc positions, alpha at the junctions (its value just after each junction),
 * accumulated from the first junction of the window so the result does not
 * depend on where the profile starts. Needs 3 points on each side. */
int tr_profile_measure_jump(const tr_arc_profile *p, tr_jump_quantity q, double at, double w, double W,
                            tr_jump *out, tr_error *err);

/* One side of tr_profile_measure_jump on its own, for kappa: the
 * extrapolation to `at` of the curvature on the left (side 0) or right
 * (side 1) of it, neighbours averaged in pairs, for a level whose other side
 * is known or is no fit's business. quadratic = 1: the jumps' fits (a
 * quadratic over [w, 2W - w], a line over [w, W] when the quadratic has too
 * few points); 0: the line alone, for a level read right beside a boundary
 * (the clasp's Gehring piece rising into its kink, clasp_anatomy.h, where a
 * quadratic over a few coarse arcs overshoots). Distances are periodic on a
 * closed profile, plain on an open one. *value and its standard error *se;
 * TR_EGEOMETRY when fewer than 3 points (after pairing) fall on the side. */
int tr_profile_kappa_side(const tr_arc_profile *p, double at, int side, double w, double W, int quadratic,
                          double *value, double *se, tr_error *err);

#endif
