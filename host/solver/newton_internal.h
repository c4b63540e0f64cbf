/* This file contains the Newton solver's private state and what its files share (newton.c and its parts). */
#ifndef TR_NEWTON_INTERNAL_H
#define TR_NEWTON_INTERNAL_H

/* Only host/solver includes this header: the solver struct and the
 * functions declared here (prefix tr_newton_i_) are the solver's own, split
 * over files by responsibility. */

#include <cholmod.h>
#include <stddef.h>
#include <stdint.h>

#include "curve/curve.h"
#include "geometry/neighbour_search.h"
#include "geometry/struts.h"
#include "oracle/thickness.h"
#include "solver/newton.h"
#include "util/clock.h"
#include "solver/solver_rows.h"
#include "util/error.h"

/* no vertex: the neighbour past an open rope's end */
#define NONE SIZE_MAX

typedef tr_strut_pair strut_row;

typedef struct solver {
    tr_curve w; /* topology; x = the positions at the last list build */
    const tr_newton_params *p;
    tr_deadline first_bound; /* the time limit and stop flag of the first list build */
    size_t nv, n; /* vertices, variables (3 nv + ncomp) */
    int nc;
    size_t *next, *prev;
    int *comp;
    size_t *ne; /* edges per component */
    int *gap;
    double *l0, *scale_m; /* start edge, S l0^2 per component (MinRad rows) */
    double l0min;
    double mu;
    /* the near-active band's width, relative to NEAR_ACTIVE: mu0 / mu */
    double band;
    /* the shortest iterate the oracle has seen at a multiplier update (its
     * ropelength at thickness 1): the last is not always the best (the
     * peer drifted away from its best at N = 19 200) */
    tr_curve probe;
    double *best_y, best_rl;
    double best_viol_edge, best_thickness; /* the best's edge violation and thickness */
    int best_restored;                     /* the best is a restoration's result */
    double *restored; /* scratch: the iterate restored (restore.c) */
    /* The iterate's low parts (curve.h), 3 nv, or NULL: the positions are
     * y + ylo. A vertex held in doubles alone is known to eps R, so a
     * MinRad row (a second difference of size l0^2) would carry rounding
     * of eps R / l0^2 of itself (1e-8 a vertex at N = 200 640) and the
     * iterate would settle with its worst rows that far over; with the low
     * parts the rows are evaluated from edges exact to eps l0, and a step
     * far below the step between doubles at the coordinates still moves
     * the vertex. ytlo: the line search's trial's; best_lo, restored_lo:
     * best_y's and restored's. */
    double *ylo, *ytlo, *best_lo, *restored_lo;
    double t_ckpt; /* when the last checkpoint went out (or the solve began) */
    double t_state; /* when the last state went out (or the solve began) */
    tr_newton_state out; /* the state handed to p->state (newton_state.c fills it) */
    double warm_residual; /* |t - J^T lambda| / |t| after the warm start; 1 without one */
    double start_residual; /* the same for the multipliers the solve starts with (1 without) */
    double *lam_e, *lam_m, *pi_e, *pi_m; /* per edge (by first vertex) / vertex */
    double *pi_s;
    strut_row *sp;
    size_t nsp;
    tr_nsearch ns;
    /* the Hessian's upper triangle as triplets */
    size_t nz, capz;
    SuiteSparse_long *ti, *tj;
    double *tx;
    int oom;
    /* the symbolic factor of the last pattern, kept while the Hessian's
     * compressed pattern stays (newton_dir) */
    cholmod_factor *L;
    SuiteSparse_long *pat_p, *pat_i; /* the last analysed Hessian's compressed pattern */
    size_t pat_nz;
    /* gauge: 6 coordinates held, so that no rigid motion is left in the
     * Hessian's null space (a Levenberg shift there would also damp the
     * knot's soft global modes, which Newton must see) */
    size_t fixed[6];
    int nfixed;
    /* the vertices with a constraint (clasp ends), in order */
    size_t *cv, ncv;
    /* results of the last evaluation */
    double viol, dmin, length;
    double viol_kind[3]; /* viol by kind of row: edges, MinRad, struts */
    size_t worst_m;      /* the vertex of the worst MinRad violation */
    double max_bend;     /* the step's curvature cap (p->max_bend on a tight start, else none) */
    double guard;        /* the MinRad guard's weight (p->minrad_guard where bends are taken back, else 0) */
    int bend_cap;        /* the cap cuts the whole step (a constrained rope); else bends are taken back (newton.c) */
    size_t active;
    cholmod_common cm;
    /* the strut rows by p->backend (solver_rows.h): the list as it takes
     * it; its first failure (the rows are then evaluated here, and the
     * minimisation returns the error); time in its calls for the Newton
     * matrix and in the line search's evaluations */
    tr_solver_rows rows;
    int dev_rc;
    tr_error dev_err;
    double t_rows, t_value;
} solver;

/* ---- vertex constraints (vertex_constraints.c) ---- */

/* the constraint vertex v is held to, or NULL */
const tr_constraint *tr_newton_i_vertex_cst(const solver *s, size_t v);
/* P (3 x 3, symmetric): the projector onto the motions k allows */
void tr_newton_i_allowed_projector(const tr_constraint *k, double P[9]);
/* v (3 nv + ncomp) with every constrained vertex's part on its allowed motions */
void tr_newton_i_project_allowed(const solver *s, double *v);
/* a row's gradient and Hessian on the allowed motions; 0 when the row
 * touches no constrained vertex */
int tr_newton_i_project_row(const solver *s, int m, const size_t *idx, const double *gr, const double *H,
                            double *gq, double *Hq);

/* ---- the gauge (gauge.c) ---- */

/* Is coordinate i one the gauge holds? Here, inline, rather than in gauge.c:
 * the Hessian's assembly asks it of every entry of every row. */
static inline int tr_newton_i_is_fixed(const solver *s, size_t i)
{
    for (int k = 0; k < s->nfixed; k++)
        if (s->fixed[k] == i)
            return 1;
    return 0;
}

/* holds the coordinates that fix the rigid motions (s->fixed, s->nfixed);
 * with vertex constraints only the free ones */
void tr_newton_i_set_gauge(solver *s);

/* ---- the augmented Lagrangian's rows (newton_rows.c) ---- */

/* the MinRad row's pieces at vertex i (w, c and its derivatives); 0 at an
 * end of an open rope (no row) */
int tr_newton_i_minrad_row(const solver *s, const double *x, const double *l, size_t i, double w[3],
                           double *c, double *dc, double *d2c);
/* the same at x + xlo (xlo: the positions' low parts, curve.h; NULL none) */
int tr_newton_i_minrad_row_lo(const solver *s, const double *x, const double *xlo, const double *l, size_t i,
                              double w[3], double *c, double *dc, double *d2c);
/* appends v at (i, j) of the Hessian's upper triangle */
void tr_newton_i_tri_push(solver *s, size_t i, size_t j, double v);
/* L_A at y less its length term; with grad its gradient and the multiplier
 * estimates, with hess the Hessian's triplets; sets viol, dmin, length,
 * active */
double tr_newton_i_al_eval(solver *s, const double *y, double *grad, int hess);
/* the same at the positions y + ylo (ylo: 3 nv low parts, curve.h, or
 * NULL): the edge and MinRad rows from them, the struts from y alone (a
 * strut's distance of 2 carries rounding of eps R, not eps R / l0^2, either way) */
double tr_newton_i_al_eval_lo(solver *s, const double *y, const double *ylo, double *grad, int hess);

/* ---- the Newton direction (newton.c) ---- */

/* dir = -(H + shift I)^-1 grad, H the Hessian al_eval last assembled, with
 * the smallest shift from *lm up that factors (*lm: the shift used) */
int tr_newton_i_dir(solver *s, const double *grad, double *dir, double *lm, tr_newton_stats *st, tr_error *err);

/* ---- the restoration (restore.c) ---- */

/* y moved onto the rows it violates by a small correction (the proximal
 * penalty projection of restore.c), until the clock passes deadline or a
 * stop is asked for; *viol the violation left (as al_eval measures it),
 * *viol_edge its edges' part. A constrained vertex moves along its
 * constraint only (the rows' projection, as in a Newton step); with exact
 * rows (low parts) a clasp's few rows over at its tip are closed by it
 * instead of being charged as length / thickness. */
int tr_newton_i_restore(solver *s, double *y, double deadline, double *viol, double *viol_edge, tr_error *err);
/* the same on the positions y + ylo (ylo: 3 nv low parts, curve.h, which
 * the correction moves; NULL: tr_newton_i_restore) */
int tr_newton_i_restore_lo(solver *s, double *y, double *ylo, double deadline, double *viol, double *viol_edge,
                           tr_error *err);
/* yt = y + alpha dir over the n variables; the first n3 (positions) with
 * low parts when ylo is not NULL: the sum's rounding goes into ytlo
 * (two-sum), so that a step below the step between doubles still moves
 * the vertex */
void tr_newton_i_add_step(size_t n3, size_t n, const double *y, const double *ylo, double alpha, const double *dir,
                          double *yt, double *ytlo);

/* ---- the strut list (strut_list.c) ---- */

/* rebuilds the strut list at y, carrying the multipliers of kept pairs */
int tr_newton_i_rebuild(solver *s, const double *y, const tr_deadline *bound, tr_error *err);

/* ---- the contact model (contact_model.c) ---- */

/* the distance strut row (a, b) holds at 2, at positions x: the segment
 * distance of edges a and b, or (vertex_contacts) that of vertices a, b */
double tr_newton_i_pair_distance(const solver *s, const double *x, size_t a, size_t b);
/* the row's coordinates (12 for edges, 6 for vertices) in idx; returns
 * their number */
int tr_newton_i_strut_index(const solver *s, size_t a, size_t b, size_t *idx);
/* the same with *d the distance, g its gradient and h (may be NULL) its
 * Hessian (m x m, row major) on idx's coordinates; returns m */
int tr_newton_i_strut_derivs(const solver *s, const double *x, size_t a, size_t b, double *d, double *g,
                             double *h, size_t *idx);
/* c's thickness in the contact model: the oracle's (thickness.h), and with
 * vertex_contacts its thickness, ropelength and dcsd replaced by the vertex
 * model's (vertex_thickness.h) */
int tr_newton_i_model_thickness(const tr_newton_params *p, const tr_curve *c, const tr_thickness_opts *opts,
                                tr_thickness *th, tr_error *err);

/* ---- the resumable state (newton_state.c) ---- */

/* the minimisation loop's own variables (newton.c minimise): with the
 * solver's, what a resumed run needs */
typedef struct tr_newton_loop {
    double omega, prev_viol, lm, prev_len, viol_tol;
    int iter, outer, inner, settled, last_full, moved, stuck, inner_done;
} tr_newton_loop;

/* s->out filled from the solver at iterate y and the loop's variables
 * (steps, seconds: the runs' so far) */
int tr_newton_i_state_fill(solver *s, const double *y, const tr_newton_loop *lp, long steps, double seconds,
                           tr_error *err);
/* The solver set up from state r (solver_init done on a curve of r's
 * shape): the scales, the gauge, the strut list rebuilt where r's was and
 * r's multipliers carried to it (with warm: the warm start's instead), the
 * best iterate; y (s->n) the iterate, *lp the loop's variables */
int tr_newton_i_state_apply(solver *s, const tr_newton_state *r, int warm, double *y, tr_newton_loop *lp,
                            tr_error *err);
/* the component's exclusion gaps from s->l0 (as solver_init sets them) */
void tr_newton_i_set_gaps(solver *s);

/* ---- a coarser level's multipliers (prolong.c) ---- */

/* s->lam_e, s->lam_m, the listed struts' multipliers and s->mu from the
 * state r of a solve of the curve s's was refined from, at iterate y */
int tr_newton_i_prolong(solver *s, const tr_newton_state *r, const double *y, tr_error *err);

/* ---- the warm start (warm_start.c) ---- */

/* the first multipliers (s->lam_m, s->sp[].lam) that best balance the unit
 * tension at y, and s->warm_residual, the share they leave unbalanced */
int tr_newton_i_warm_multipliers(solver *s, const double *y, tr_error *err);
/* A start is tight when its warm multipliers balance all but this of the
 * tension (newton.c has why) */
#define TIGHT_RESIDUAL 0.7

#endif
