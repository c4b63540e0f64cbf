/* The second-order solver for the fine levels: Newton's method on an
 * augmented Lagrangian of "minimise length at thickness 1", with the sparse
 * Hessian factored by CHOLMOD.
 *
 * Problem (rope radius 1), variables the vertices x and one edge length l_k
 * per component k:
 *   minimise   sum_k n_k l_k                      (n_k edges of component k)
 *   edges      h_a = |x_{a+1} - x_a| - l_k = 0     every edge a of component k
 *   MinRad     g_i = (c(l_k) - |x_{i+1} - 2 x_i + x_{i-1}|^2) / (S l0_k^2) >= 0
 *              at every vertex with two edges; c(l) = 4 l^4 / (4 + l^2), so
 *              with equal edges g_i >= 0 is exactly Rawdon's MinRad >= 1
 *              (|x_{i+1} - 2x_i + x_{i-1}| = 2 l sin(theta/2) and
 *              MinRad = l / (2 tan(theta/2))); l0_k is the start edge, so
 *              every row's gradient is O(1 / S); S = 4, or 0.1 for a tight
 *              start whose MinRad overshoots (newton.c, MINRAD_ROW_SCALE_*);
 *   struts     d(a, b) - 2 >= 0 for every listed edge pair, d the exact
 *              segment distance (or, in SP-FEM's vertex model, the
 *              distance of the edges' first vertices: vertex_contacts) (strut_hessian.h: closest points recomputed
 *              at every evaluation, so the rope cannot slip between frozen
 *              sample points); the list holds every pair beyond the
 *              exclusion gap ceil(pi / l) within 2 + skin (neighbour_search.h),
 *              rebuilt before any vertex has moved skin / 4 since.
 *
 * Method (Nocedal & Wright 17.4, Powell-Hestenes-Rockafellar): for fixed
 * multipliers lambda and penalty mu the augmented Lagrangian
 *   L_A = f - sum lambda_e h + mu/2 sum h^2 + sum_ineq psi(g, lambda, mu),
 *   psi = -lambda g + mu/2 g^2 if lambda - mu g > 0, else -lambda^2 / (2 mu),
 * is minimised by Newton steps: the Hessian
 *   sum over rows with pi = lambda - mu c active of  mu grad c grad c^T - pi hess c
 * is sparse (the chain's 3x3 blocks, a 12 x 12 block per active strut, one
 * dense row per component for l_k) and factored by CHOLMOD (LL^T; when it is
 * not positive definite a multiple of I is added, Levenberg-Marquardt), the
 * step is capped so no vertex moves more than max_move (and, on a tight
 * start with poor first multipliers or a tight start in the vertex model
 * (newton.c), no vertex's curvature rises more than
 * max_bend above max(its own, 1): on a clasp by cutting the whole step, on
 * a closed knot by taking those vertices back along their bend, a curved
 * search path that a short enough step leaves straight; newton.c), and an
 * Armijo line search on L_A accepts it. A direction that is no descent (the factor of a
 * nearly singular matrix is inaccurate) or that would move a vertex more
 * than 4 max_move (a soft mode nothing holds yet: the whole rope shrinking
 * before any contact is active) is computed again with a 100 times larger
 * shift. When the inner gradient is small (or a full step predicts a decrease
 * below inner_decrement of the length, or after max_inner steps) the
 * multipliers are updated, lambda <- pi, and mu grows tenfold (up to
 * mu_max) if the violation did not fall by 4 in a solved pass (newton.c:
 * an unfinished pass says nothing about mu). Inactive rows near their
 * bound enter the Newton matrix in a band that narrows as mu grows
 * (newton_rows.c, NEAR_ACTIVE). It stops converged (violation and
 * unbalanced force below their tolerances) or settled (feasible, and the
 * length unchanged to 1e-11 over three updates: where many struts press on
 * one edge the discrete multipliers are far from unique and the unbalanced
 * force stalls while the length has stopped moving).
 *
 * Warm start: the first multipliers are those that best balance the unit
 * tension with the MinRad and strut rows near their bound (least squares by
 * conjugate gradients, clipped at 0), so a start whose contacts are in place
 * keeps them from the first step instead of shrinking through them while
 * the multipliers build up from 0. What they leave unbalanced says whether
 * the start is tight (under 0.7 of the tension's force): tight_only gives up
 * on a loose start at once, for the engine's first-order route. A refined
 * level may start from its coarser level's own multipliers instead
 * (coarse, prolong.c): the engine does so for a clasp, whose tip is held by
 * MinRad multipliers that the least squares' damping takes away.
 *
 * Unit: thickness 1, except for a tight start that a spline through a
 * converged polygon left with MinRad a little under its struts' half
 * distance (0.93 at N = 9600 from the N = 2400 trefoil): that one is scaled
 * to its struts, so only the few overshooting MinRad rows start violated,
 * and those rows are stiffened (S = 0.1) so the first passes take them back
 * instead of letting them go 40 % over while the rope shortens.
 *
 * Why it converges: each inner solve is a descent method with Newton steps
 * on a function that is C^1 with a piecewise smooth gradient (semismooth),
 * so it converges, and near a minimiser satisfying second-order sufficiency
 * the Hessian with mu large enough is positive definite and the steps are
 * full: quadratic inner convergence. The multiplier iteration converges
 * linearly with a rate that falls like 1/mu, and it needs no linear
 * independence of the active rows: a tight knot has many more touching
 * strut pairs than its vertices can independently feel, which stalls
 * methods that need LICQ (interior point without care, plain SQP).
 * Tension makes the chain's Hessian positive (-lambda_e hess|e| with the
 * tension lambda_e ~ -1 is +(I - u u^T)/|e|), curvature rows add positive
 * terms; only the strut rows' -pi hess d is negative, and it is O(edge)
 * against the tension's O(1/edge), so the Levenberg term is rarely needed
 * except along the rigid motions (translations and rotations leave every
 * term unchanged, so the gradient has no part along them).
 *
 * Never a different knot: as the polish stage (polish.h) argues: each step
 * moves a vertex at most max_move <= skin / 8, the list is rebuilt before
 * any vertex has moved skin / 4 since its build (a pair left out was
 * >= 2 + skin apart and is still >= 2), and a step after which a listed
 * pair is closer than 1 is cut back.
 *
 * The result is accepted if the thickness oracle (thickness.h) says it is
 * shorter, after rescaling it to thickness exactly 1. The candidates are
 * the best iterate the passes met and the last one, each also restored
 * (restore.c: moved onto its rows by a small correction, since the
 * rescaling charges a violation of a few rows to the whole length); a
 * checkpoint is the best so far, restored likewise. A state
 * (tr_newton_state) is what a stopped run needs to go on: the iterate as
 * the loop holds it, neither restored nor rescaled, with everything else
 * the loop carries from one step to the next.
 *
 * Vertex constraints (clasp ends on planes, lines, fixed points) are
 * eliminated: each row's gradient and Hessian are taken on the motions the
 * constraint allows (P_i), I - P_i fills the vertex's diagonal block, so
 * every step keeps the vertex on its set (vertex_constraints.c says why
 * not equality rows). Only the rigid motions the constraints leave free
 * are held as gauge (gauge.c; the clasp: translations within its parallel
 * planes and the rotation about their normal). Open components have no wrap edge and
 * MinRad rows only where a vertex has two edges. A constrained curve is not
 * rescaled (its planes stay): its ropelength is its length at thickness 1,
 * the result is kept within 1e-6 of thickness 1, and a start below
 * thickness 0.85 is refused (skipped = 1). */
#ifndef TR_NEWTON_H
#define TR_NEWTON_H

#include <signal.h>
#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"

typedef struct tr_newton_progress {
    int iter, outer;
    double length;    /* sum of the edges */
    double viol;      /* worst relative violation (edge / l, MinRad, strut (2 - d) / 2) */
    double viol_edge, viol_minrad, viol_strut; /* the same by kind of row */
    double stat;      /* |grad L_A|_inf / l0: unbalanced force relative to the tension */
    double mu, lm;    /* penalty (times l0), Levenberg shift used (0 if none) */
    double step;      /* accepted step fraction */
    size_t struts, active; /* listed pairs, active strut rows */
    size_t worst_minrad;   /* the vertex of the worst MinRad violation */
    double seconds;
} tr_newton_progress;

struct tr_backend;

/* The solver's state between two Newton steps: what a run that was
 * stopped needs to go on where it was (newton_state.c reads and writes it).
 * The variables as the solver holds them (not rescaled: a rescaled iterate
 * charges its rows' violation to its whole length), the augmented
 * Lagrangian's multipliers and penalty, the positions the strut list was
 * built at (the list is rebuilt there, so it is the same list, and its
 * multipliers are carried pair by pair), the scales the start fixed (the
 * start edge l0, the MinRad rows' scale, the gauge, the bend cap) and the
 * minimisation loop's counters. A run resumed from the state of a run that
 * stopped at a step boundary takes the same steps as the run that did not
 * stop (tests/solver/test_newton_state.c). */
typedef struct tr_newton_state {
    size_t nv;    /* vertices */
    int ncomp;    /* components */
    size_t *comp_nv; /* vertices per component (the curve's shape, checked on resume) */
    double *y;    /* 3 nv positions, then one edge length per component: the iterate, in the solver's unit */
    double *build;        /* 3 nv: the positions of the strut list's last build */
    double *lam_e, *lam_m; /* nv each: edge (by first vertex) and MinRad multipliers */
    size_t nstrut;        /* listed strut pairs with a nonzero multiplier */
    size_t *strut_a, *strut_b;
    double *strut_lam;
    double *l0, *scale_m; /* per component: the start edge, the MinRad rows' scale S l0^2 */
    size_t fixed[6];      /* the gauge's held coordinates */
    int nfixed;
    double mu, band, max_bend, guard, viol_tol, warm_residual;
    int bend_cap;
    /* the loop's: the inner tolerance, the violation at the last update,
     * the Levenberg shift to try first, the length at the last update */
    double omega, prev_viol, lm, prev_len;
    int iter, outer, inner, settled, last_full, moved, stuck, inner_done;
    /* the shortest iterate the oracle measured (has_best: there is one) */
    int has_best, best_restored;
    double *best_y; /* 3 nv + ncomp */
    double best_rl, best_viol_edge, best_thickness;
    /* the iterate's and the best's low parts (3 nv each; newton_internal.h
     * ylo), or NULL (a state of file version 1) */
    int has_lo;
    double *ylo, *best_lo;
    /* the runs so far, together: Newton steps and seconds (for the log) */
    long steps;
    double seconds;
} tr_newton_state;

void tr_newton_state_free(tr_newton_state *s);
/* Writes s to path atomically (a temporary file beside it, renamed over
 * path: a reader sees the old state or the new, never half of one). */
int tr_newton_state_write(const char *path, const tr_newton_state *s, tr_error *err);
/* Reads a state tr_newton_state_write wrote into s (overwritten: free a
 * state it held first; tr_newton_state_free frees this one); a file that
 * is not one, or is cut short, is an error naming the file and the byte,
 * and leaves s empty. */
int tr_newton_state_read(const char *path, tr_newton_state *s, tr_error *err);
/* 1 when path is a file that begins as tr_newton_state_write's do (its
 * magic line), else 0 (absent, unreadable, or another file): what a caller
 * that writes states beside its own files checks before writing over one. */
int tr_newton_state_is_file(const char *path);

typedef struct tr_newton_params {
    double time_limit; /* seconds (0: none) */
    int max_iter;      /* Newton steps */
    int max_inner;     /* Newton steps between multiplier updates */
    double skin;       /* strut list cutoff 2 + skin */
    double max_move;   /* per-vertex cap on one step (<= skin / 8) */
    double max_bend;   /* per-vertex bound on one step's bend (|w| / l0^2; newton.c): a clasp's step changes
                        * none by more, a closed knot's raises none more above max(its own, 1) */
    double mu0;        /* first penalty, in units of 1 / l0 */
    double mu_max;     /* largest penalty, likewise */
    double mu_late;    /* ... raised to this once the rows are within late_viol and stall at mu_max (newton.c;
                        * 0, the default: never) */
    double late_viol;  /* the violation at or below which mu_max may rise to mu_late */
    double viol_tol;   /* converged: worst relative violation below this ... */
    double stat_tol;   /* ... and relative unbalanced force below this */
    double inner_decrement; /* a pass ends after a full step predicting less decrease than this x length */
    double minrad_guard; /* where bends are taken back, the Newton matrix sees the inactive MinRad rows near
                          * their bound as a barrier would, with this weight times the band (newton_rows.c);
                          * 0: not at all */
    int warm_start;    /* first multipliers by least squares (warm_start.c); 0: cold */
    /* The contact model (contact_model.c): 0 Rawdon's, strut rows on the
     * segment distance of edge pairs, the result judged by the thickness
     * oracle; 1 SP-FEM's, strut rows |x_a - x_b| >= 2 on vertex pairs at
     * least K = ceil(pi / l) apart along a component, the result judged by
     * the vertex oracle (oracle/vertex_thickness.h). The vertex model takes
     * closed components only and evaluates its rows here (backend ignored). */
    int vertex_contacts;
    int tight_only;    /* give up at once (not accepted) unless the warm start finds the start tight */
    volatile sig_atomic_t *stop; /* raised by a signal handler: stop as at the time limit */
    /* NULL: every row evaluated here. Else the strut rows (the distances, the
     * Newton matrix's 12 x 12 blocks, the line search's sums) by this
     * backend's strut_rows (backend.h), the open backend of the run; the
     * reference takes the same steps to the bit */
    const struct tr_backend *backend;
    void (*progress)(void *user, const tr_newton_progress *p); /* every step (may be NULL) */
    void *user;
    /* Long runs: every checkpoint_every seconds (0: never) the shortest
     * iterate so far, rescaled to thickness 1 by the oracle (a curve the
     * run could end with), goes to checkpoint; its error is the caller's
     * to weigh (it does not stop the solve). */
    double checkpoint_every;
    int (*checkpoint)(void *user, const tr_curve *best, tr_error *err);
    /* Resumable runs: every state_every seconds (0: never), and when the
     * loop stops unfinished (time limit, stop flag, max_iter), the solver's
     * state, whatever its violation, goes to state (at a step boundary; the
     * state is the solver's, valid during the call only); its error is the
     * caller's to weigh (it does not stop the solve). */
    double state_every;
    int (*state)(void *user, const tr_newton_state *s, tr_error *err);
    /* Not NULL: the solve goes on from this state (of a run on a curve of
     * the same shape: vertices per component) instead of from the curve's
     * positions; the curve gives the topology, its constraints and the
     * ropelength a result must beat. max_iter bounds the loop's iterations
     * from the first run's start (a resumed run's count goes on), as it
     * bounds the run that did not stop; time_limit counts this run's
     * seconds. */
    const tr_newton_state *resume;
    /* with resume: the multipliers from the warm start (warm_start.c) at the
     * resumed iterate instead of the state's (measuring which works) */
    int resume_warm;
    /* Not NULL (and no resume): the state a solve of the curve this one was
     * refined from ended with (the same components, as many vertices or
     * fewer: the
     * engine's refinement, which keeps each component's first vertex): its
     * multipliers, carried along arclength and rescaled to the finer edges
     * (prolong.c), replace the warm start's; the first penalty is mu0, or
     * coarse_mu where that is > 0 (in units of 1 / l0) */
    const tr_newton_state *coarse;
    double coarse_mu;
    /* Not NULL: a solve that converged or settled leaves its state here
     * (what was there freed first; tr_newton_state_free frees it): what the
     * level refined from it starts from, as coarse */
    tr_newton_state *end_state;
} tr_newton_params;

void tr_newton_params_default(tr_newton_params *p);

typedef struct tr_newton_stats {
    int skipped;  /* constrained vertices and a start below thickness 0.85: not run */
    int loose;    /* tight_only, and the start was not tight: not run */
    int accepted; /* the curve was replaced */
    int converged;
    int settled;  /* stopped: feasible and the length unchanged (1e-12) over three updates */
    int iters, outer, factorizations, analyses, rebuilds;
    double ropelength_before, ropelength_after;
    double max_viol, stat;
    double warm_residual; /* the tension the warm start's multipliers leave unbalanced (relative) */
    int coarse;   /* the start's multipliers were the coarse state's (params coarse) */
    size_t struts, active;
    /* where the time went */
    double t_eval, t_factor, t_solve, t_search, t_rebuild, seconds;
    double t_analyze; /* of t_factor: CHOLMOD's symbolic analyses */
    /* with a backend: of t_eval, the strut rows' evaluation (the backend's
     * call, transfers included); the line search's evaluations (part of
     * t_search, which also holds the factorisations it asks for) */
    double t_rows, t_value;
    /* the memory the factorisations took, at their largest: the Hessian's
     * triplets (24 bytes each), its compressed entries (duplicates summed;
     * 12 bytes each, and 8 for the pattern kept to skip analyses) and the
     * factor's entries */
    size_t hess_triplets, hess_entries, factor_entries;
    const char *why_rejected; /* static text */
} tr_newton_stats;

/* Tightens c in place (only if accepted; the result is at thickness 1). */
int tr_newton(tr_curve *c, const tr_newton_params *p, tr_newton_stats *st, tr_error *err);

/* Moves a nearly feasible c (closed components, no vertex constraints) onto
 * its rows by a small correction instead of a rescaling (restore.c: the
 * proximal penalty projection on the solver's rows, at c's own scale) and
 * replaces c by the result at thickness 1 where the oracle measures it
 * shorter than c rescaled. *before, *after: the worst row's violation
 * (relative) before and after. tr_newton does the same to its iterates
 * at each checkpoint and at its end. */
int tr_newton_restore(tr_curve *c, const tr_newton_params *p, double *before, double *after, tr_error *err);

#endif
