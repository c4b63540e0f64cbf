/* The polish stage: a final tightening of a nearly tight rope by direct
 * minimisation, which reaches the fine-level optimum that the engine's
 * projected-gradient steps stall short of
 * (bench/notes/2026-11-22-tighten-before-polish.md). It runs serially on
 * the host, on a downloaded curve: the
 * backends never see it.
 *
 * Problem (rope radius 1, thickness-1 units): minimise the polygon length
 * subject to
 *   struts   d(a, b) >= 2 for every edge pair not excluded by index (the
 *            exact segment distance of kernels/segment_distance.h; candidate pairs within
 *            2 + skin from the neighbour search, rebuilt before any vertex
 *            has moved skin/4 since; exclusion gap ceil(pi / ebar) per
 *            component as the engine's, backend.h);
 *   MinRad   Rawdon's min(|p|,|q|) / (2 tan(theta/2)) >= 1 at every vertex
 *            with two edges, as two smooth rows |p| >= 2 tan(theta/2) and
 *            |q| >= 2 tan(theta/2) (scaled by the start edge length so the
 *            gradients are O(1));
 *   edges    |e_a| = L_k / n_k, every edge of component k equal to the mean.
 * Method: augmented Lagrangian (Powell-Hestenes-Rockafellar; Nocedal &
 * Wright 17.4) with L-BFGS inner solves (lbfgs.h), multiplier updates after
 * each inner solve and a tenfold penalty increase when the worst violation
 * did not fall by 4; the whole run is restarted from its result with the
 * first penalty until two restarts in a row no longer shorten the rope
 * (max_restarts).
 *
 * Never a different knot (the engine's argument, engine.h): every L-BFGS
 * iteration moves each vertex at most max_move along a straight line; after
 * each one the shortest listed non-local distance must stay above 4 max_move
 * (so no listed pair can have crossed), the pair list is rebuilt before the
 * motion since it was built reaches skin/4 (so an unlisted pair, which was
 * >= 2 + skin apart, is still >= 2), and MinRad must stay >= 0.9 (excluded
 * pairs lie within arclength ~pi on a curve of curvature <= 1/0.9, which
 * cannot meet itself there). A run that breaks a guard is abandoned and the
 * input is kept. The result is accepted only if the oracle's ropelength
 * (thickness.h) went down; it is then rescaled to thickness exactly 1 by
 * the smaller of the oracle's thickness and min(MinRad, shortest non-local
 * segment distance / 2), so it satisfies every constraint exactly.
 *
 * Curves with vertex constraints (clasp ends on planes) cannot be rescaled
 * (the ends would leave their planes): the constrained vertices move only
 * within their constraint (projected gradients, snapped at the end), the
 * curve must come in at thickness 1 (within 1e-3; else skipped = 1) and the
 * result is accepted, unscaled, if it is shorter (length / thickness) and
 * at thickness 1 within 1e-6. */
#ifndef TR_POLISH_H
#define TR_POLISH_H

#include <signal.h>
#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"

typedef struct tr_polish_params {
    double time_limit; /* seconds of wall time (0: until converged or max_outer) */
    int max_outer;     /* augmented-Lagrangian rounds */
    int max_inner;     /* L-BFGS iterations per round */
    double skin;       /* pair list cutoff 2 + skin */
    double max_move;   /* per-vertex cap on one L-BFGS iteration (<= skin/8) */
    double viol_tol;   /* stop when the worst relative violation is below this */
    double mu0;        /* first penalty */
    double mu_max;
    int lbfgs_m;
    /* Runs from a fresh penalty, each from the last one's result, until two
     * runs in a row shorten the rope by no more than restart_tol (relative);
     * 1: one run. */
    int max_restarts;
    double restart_tol;
    /* > 0: no further restart once an accepted run measures a ropelength at
     * or below this (a user's --target; 0: none). */
    double target;
    /* Optional observer of every accepted iterate (tests check the guards
     * independently with it); x has 3 nv entries in thickness-1 units. */
    void (*observe)(void *user, const double *x, size_t nv);
    void *user;
    /* Raised by a signal handler (may be NULL): stop as at the time limit
     * (the result so far is still checked and kept if shorter). */
    volatile sig_atomic_t *stop;
} tr_polish_params;

void tr_polish_params_default(tr_polish_params *p);

typedef struct tr_polish_stats {
    int skipped;        /* constrained vertices below thickness 1: nothing done */
    int accepted;       /* the curve was replaced */
    int outer, inner_iters, evals, rebuilds; /* summed over the runs */
    int restarts;       /* augmented-Lagrangian runs made */
    double ropelength_before, ropelength_after; /* oracle, before / after (after = before if not accepted) */
    double max_viol;    /* worst relative violation at the end of the minimisation */
    double edge_dev;    /* max relative edge deviation of the result */
    double seconds;
    const char *why_rejected; /* static text, NULL if accepted or skipped */
} tr_polish_stats;

/* Polishes c in place (only if accepted; the result is at thickness 1). */
int tr_polish(tr_curve *c, const tr_polish_params *p, tr_polish_stats *st, tr_error *err);

#endif
