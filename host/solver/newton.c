/* This file contains the second-order solver: Newton steps on the augmented
 * Lagrangian of the ideal-knot problem, factored by CHOLMOD (newton.h has
 * the formulation and why it converges). Its parts, each in its own file
 * (newton_internal.h): the rows (newton_rows.c), the strut list
 * (strut_list.c), the warm start (warm_start.c), the gauge (gauge.c) and
 * the vertex constraints (vertex_constraints.c); here the entry, the
 * solver's set-up, the Newton direction and the minimisation loop. */
#include "solver/newton.h"

#include <cholmod.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/neighbour_search.h"
#include "geometry/struts.h"
#include "solver/bend.h"
#include "solver/newton_internal.h"
#include "solver/solver_rows.h"
#include "oracle/thickness.h"
#include "util/clock.h"
#include "util/vec3.h"

/* a step after which a listed pair is closer than this is cut back */
#define GUARD_DIST 1.0
/* the smallest MinRad relative to the struts' half distance at which the
 * start is scaled to its struts (tr_newton; from 1 - 1e-4 down: closer,
 * the two scales are the same start) */
#define MINRAD_SLACK 0.85

void tr_newton_params_default(tr_newton_params *p)
{
    memset(p, 0, sizeof *p);
    p->max_iter = 5000;
    p->max_inner = 15;
    p->skin = 0.08;
    p->max_move = p->skin / 8;
    p->max_bend = 0.05;
    p->mu0 = 10.0;
    p->warm_start = 1;
    p->mu_max = 1e5;
    /* off by default: at 38 400 it fired at 6e-8 over, the rows then
     * jumped to 1e-4 and the rung settled in 360 steps against the
     * default's 186, 3.1e-9 shorter; measured at 76 800 next (newton_run
     * NEWTON_MU_LATE=1e7) */
    p->mu_late = 0.0;
    p->late_viol = 5e-7;
    p->inner_decrement = 1e-11;
    p->minrad_guard = 0.1;
    p->viol_tol = 1e-11;
    p->stat_tol = 1e-7;
}

/* ---- the rows' scale (the rows: newton_rows.c) ---- */

/* A MinRad row is (c(l) - |w|^2) / (S l0^2): its gradient is then
 * ~ kappa / S, and a multiplier lambda ~ l0 (the tension it holds) leaves a
 * violation lambda / mu at the penalty's balance, which relative to the
 * row's own size c ~ l0^4 is ~ 4 S^2 / (mu l0) (the struts' rows, d - 2,
 * are already in units of thickness). At S = 4 a first penalty of 10 / l0
 * lets MinRad rows go 40 % over while the rope shortens: from a tight start
 * (a converged knot refined) the passes that take them back cost 90 s at
 * N = 9600; at S = 0.1 the same balance is 2.5e-4, for a Newton matrix 400
 * times stiffer along those rows. Only there: from a loose start the
 * stiff rows stall the steps (a wobbled circle's 32-gon did not reach the
 * regular one in 4000 steps), and from a tight start without the overshoot
 * (the N = 2400 trefoil as the engine leaves it) they settle 2e-7 longer.
 * So S = 0.1 when the start was scaled to its struts (tr_newton) and the
 * warm start's multipliers balance all but TIGHT_RESIDUAL of the tension
 * (bench/notes/2026-11-25-converged-last-digits.md): a wobbled circle leaves all of
 * it (1.0), the N = 2400 trefoil spline-refined to 9600 0.19, to 19 200
 * 0.21, to 38 400 0.29 (warm_start.c). */
#define MINRAD_ROW_SCALE_LOOSE 4.0
#define MINRAD_ROW_SCALE_TIGHT 0.1

/* ---- the Newton step ---- */

/* Factors the assembled Hessian (plus the smallest Levenberg shift that
 * makes it positive definite) and solves H dir = -grad. *lm: the shift
 * tried first on entry, the one used on return. */
int tr_newton_i_dir(solver *s, const double *grad, double *dir, double *lm, tr_newton_stats *st, tr_error *err)
{
    double t0 = tr_clock_seconds();
    cholmod_common *cm = &s->cm;
    double dmax = 0.0;
    for (size_t k = 0; k < s->nz; k++)
        if (s->ti[k] == s->tj[k])
            dmax = fmax(dmax, fabs(s->tx[k]));
    /* every diagonal present, so the shift reaches every variable; the
     * triplets are CHOLMOD's without a copy */
    size_t nz = s->nz;
    for (size_t k = 0; k < s->n; k++)
        tr_newton_i_tri_push(s, k, k, tr_newton_i_is_fixed(s, k) ? 1.0 : 0.0);
    if (s->oom) {
        s->nz = nz;
        return tr_fail(err, TR_ENOMEM, "out of memory (Hessian, %zu entries)", nz);
    }
    cholmod_triplet T = {.nrow = s->n, .ncol = s->n, .nzmax = s->capz, .nnz = s->nz, .i = s->ti, .j = s->tj,
                         .x = s->tx, .stype = 1, .itype = CHOLMOD_LONG, .xtype = CHOLMOD_REAL,
                         .dtype = CHOLMOD_DOUBLE};
    cholmod_sparse *A = cholmod_l_triplet_to_sparse(&T, T.nnz, cm);
    size_t full = s->nz;
    s->nz = nz;
    if (!A)
        return tr_fail(err, TR_ENOMEM, "out of memory (Hessian)");
    /* the last analysis holds while the compressed pattern is the same (it
     * is kept, not the triplets': duplicates summed, it is about a quarter
     * of their size, and the triplets are most of the solver's memory) */
    const SuiteSparse_long *Ap = A->p, *Ai = A->i;
    size_t annz = (size_t)Ap[s->n];
    int same = s->L && s->pat_nz == annz && !memcmp(s->pat_p, Ap, (s->n + 1) * sizeof *Ap) &&
               !memcmp(s->pat_i, Ai, annz * sizeof *Ai);
    int rc = TR_OK;
    if (!same) {
        cholmod_l_free_factor(&s->L, cm);
        double ta = tr_clock_seconds();
        s->L = cholmod_l_analyze(A, cm);
        st->t_analyze += tr_clock_seconds() - ta;
        if (!s->L) {
            rc = tr_fail(err, TR_ENOMEM, "CHOLMOD could not analyse the Hessian (status %d)", cm->status);
            goto done;
        }
        SuiteSparse_long *pi = realloc(s->pat_i, (annz ? annz : 1) * sizeof *pi),
                         *pp = pi ? realloc(s->pat_p, (s->n + 1) * sizeof *pp) : NULL;
        if (pi)
            s->pat_i = pi;
        if (pp) {
            s->pat_p = pp;
            memcpy(s->pat_p, Ap, (s->n + 1) * sizeof *pp);
            memcpy(s->pat_i, Ai, annz * sizeof *pi);
            s->pat_nz = annz;
        } else
            s->pat_nz = (size_t)-1; /* analysed again next time: slower, as correct */
        st->analyses++;
    }
    cholmod_factor *L = s->L;
    st->hess_triplets = st->hess_triplets > full ? st->hess_triplets : full;
    st->hess_entries = st->hess_entries > annz ? st->hess_entries : annz;
    /* rounding's share only: the gauge holds the rigid motions */
    double floor_shift = 1e-14 * dmax, shift = fmax(*lm, floor_shift);
    for (int tries = 0;; tries++) {
        double beta[2] = {shift, 0.0};
        int ok = cholmod_l_factorize_p(A, beta, NULL, 0, L, cm);
        st->factorizations++;
        if (ok && cm->status == CHOLMOD_OK)
            break;
        if (cm->status != CHOLMOD_NOT_POSDEF || tries > 30) {
            rc = tr_fail(err, TR_EGEOMETRY, "CHOLMOD could not factor the Hessian (status %d)", cm->status);
            goto done;
        }
        shift = fmax(shift * 10.0, 1e-8 * dmax);
    }
    *lm = shift;
    {
        size_t fe = L->is_super ? L->xsize : L->nzmax;
        st->factor_entries = st->factor_entries > fe ? st->factor_entries : fe;
    }
    double t1 = tr_clock_seconds();
    st->t_factor += t1 - t0;
    cholmod_dense *b = cholmod_l_allocate_dense(s->n, 1, s->n, CHOLMOD_REAL, cm);
    if (!b) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory");
        goto done;
    }
    double *bx = b->x;
    for (size_t k = 0; k < s->n; k++)
        bx[k] = -grad[k];
    cholmod_dense *xs = cholmod_l_solve(CHOLMOD_A, L, b, cm);
    cholmod_l_free_dense(&b, cm);
    if (!xs) {
        rc = tr_fail(err, TR_ENOMEM, "CHOLMOD solve failed (status %d)", cm->status);
        goto done;
    }
    memcpy(dir, xs->x, s->n * sizeof *dir);
    cholmod_l_free_dense(&xs, cm);
    /* the solve leaves a constrained vertex's forbidden part at rounding;
     * none at all, so the ends do not drift off their planes over the steps */
    tr_newton_i_project_allowed(s, dir);
    st->t_solve += tr_clock_seconds() - t1;
done:
    cholmod_l_free_sparse(&A, cm);
    return rc;
}

static void solver_free(solver *s)
{
    tr_nsearch_free(&s->ns);
    tr_curve_free(&s->w);
    free(s->next);
    free(s->prev);
    free(s->comp);
    free(s->ne);
    free(s->gap);
    free(s->l0);
    free(s->scale_m);
    free(s->lam_e);
    free(s->lam_m);
    free(s->pi_e);
    free(s->pi_m);
    free(s->pi_s);
    free(s->sp);
    free(s->ti);
    free(s->tj);
    free(s->tx);
    free(s->pat_i);
    free(s->pat_p);
    free(s->best_y);
    free(s->restored);
    free(s->ylo);
    free(s->ytlo);
    free(s->best_lo);
    free(s->restored_lo);
    free(s->cv);
    tr_curve_free(&s->probe);
    tr_newton_state_free(&s->out);
    tr_solver_rows_free(&s->rows);
    cholmod_l_free_factor(&s->L, &s->cm);
    cholmod_l_finish(&s->cm);
}

void tr_newton_i_set_gaps(solver *s)
{
    int nc = s->nc;
    for (int k = 0; k < nc; k++)
        s->gap[k] = tr_exclusion_gap(1.0, s->l0[k]);
    /* the vertex model's K is the vertex oracle's (vertex_thickness.h): one
     * for all components, from the mean edge of the whole curve, so that the
     * rows the solver holds are the pairs the oracle judges */
    if (s->p->vertex_contacts) {
        double len = 0.0;
        size_t edges = 0;
        for (int k = 0; k < nc; k++) {
            len += s->l0[k] * (double)s->ne[k];
            edges += s->ne[k];
        }
        for (int k = 0; k < nc; k++)
            s->gap[k] = tr_exclusion_gap(1.0, edges ? len / (double)edges : s->l0[k]);
    }
}

static int solver_init(solver *s, const tr_curve *cv, double scale, tr_error *err)
{
    int rc = tr_curve_copy(&s->w, cv, err);
    if (rc)
        return rc;
    /* the iterate is held in doubles; the end game gives the result its
     * low parts again (newton.h) */
    tr_curve_drop_lo(&s->w);
    for (size_t i = 0; i < 3 * s->w.nv; i++)
        s->w.x[i] *= scale;
    size_t nv = s->nv = s->w.nv;
    int nc = s->nc = s->w.ncomp;
    s->n = 3 * nv + (size_t)nc;
    s->next = malloc(nv * sizeof *s->next);
    s->prev = malloc(nv * sizeof *s->prev);
    s->comp = malloc(nv * sizeof *s->comp);
    s->ne = calloc((size_t)nc, sizeof *s->ne);
    s->gap = calloc((size_t)nc, sizeof *s->gap);
    s->l0 = calloc((size_t)nc, sizeof *s->l0);
    s->scale_m = calloc((size_t)nc, sizeof *s->scale_m);
    s->lam_e = calloc(nv, sizeof *s->lam_e);
    s->lam_m = calloc(nv, sizeof *s->lam_m);
    s->pi_e = calloc(nv, sizeof *s->pi_e);
    s->pi_m = calloc(nv, sizeof *s->pi_m);
    cholmod_l_start(&s->cm);
    s->cm.print = 0;
    s->cm.error_handler = NULL;
    if (!s->next || !s->prev || !s->comp || !s->ne || !s->gap || !s->l0 || !s->scale_m || !s->lam_e ||
        !s->lam_m || !s->pi_e || !s->pi_m)
        return tr_fail(err, TR_ENOMEM, "out of memory (Newton solver, %zu vertices)", nv);
    s->l0min = INFINITY;
    for (int k = 0; k < nc; k++) {
        size_t st = s->w.start[k], n = tr_comp_nv(&s->w, k);
        for (size_t j = 0; j < n; j++) {
            size_t i = st + j;
            s->comp[i] = k;
            s->next[i] = j + 1 < n ? i + 1 : (s->w.closed[k] ? st : NONE);
            s->prev[i] = j > 0 ? i - 1 : (s->w.closed[k] ? st + n - 1 : NONE);
            /* the tension: every edge's multiplier balances one unit of length */
            s->lam_e[i] = -1.0;
        }
        s->ne[k] = tr_comp_ne(&s->w, k);
        s->l0[k] = tr_comp_length(&s->w, k) / (double)s->ne[k];
        s->scale_m[k] = MINRAD_ROW_SCALE_LOOSE * s->l0[k] * s->l0[k];
        s->l0min = fmin(s->l0min, s->l0[k]);
    }
    tr_newton_i_set_gaps(s);
    for (size_t i = 0; i < nv; i++)
        s->ncv += tr_newton_i_vertex_cst(s, i) != NULL;
    s->cv = malloc((s->ncv ? s->ncv : 1) * sizeof *s->cv);
    if (!s->cv)
        return tr_fail(err, TR_ENOMEM, "out of memory (Newton solver)");
    s->ncv = 0;
    for (size_t i = 0; i < nv; i++)
        if (tr_newton_i_vertex_cst(s, i))
            s->cv[s->ncv++] = i;
    tr_newton_i_set_gauge(s);
    return tr_nsearch_build(&s->ns, &s->w, err);
}

/* The bend bound (bend.h). A step's change of a vertex's curvature, |dw| /
 * l0^2 (w the second difference x_{i+1} - 2 x_i + x_{i-1}, |w| = l0^2
 * kappa), matters because the MinRad rows the Newton matrix leaves out
 * (inactive) see only the model's tension, which resists a kink of angle phi by l0 phi^2 / 8 alone, so a
 * step's second differences must stay small against l0^2, a scale that
 * falls like 1 / N^2 (at N = 38 400 the first steps, 2.5e-3 long, took
 * MinRad's violation from 0.05 to 0.37, and the solve wandered for 1500
 * steps; capped at 0.05 it settled in 405). The cap is p->max_bend, on a
 * tight start whose start multipliers are poor only (CAUTIOUS_RESIDUAL).
 * On a clasp it cuts the whole step (tr_bend_max_change). On a closed knot
 * the vertices a step would bend past it are taken back one by one instead
 * (tr_bend_take_back): with the cap the whole step was cut to 0.1 to 0.3
 * of Newton's at N = 38 400, bound by the one vertex at the end of a MinRad
 * stretch (kappa 0.97 to 1) that the direction bent by 0.3, and that vertex
 * moved on along the rope one or two vertices a step for hundreds of
 * steps; with its bend taken back the rest of the rope takes its full
 * step, and the solve settled in 263 steps against 455
 * (bench/notes/2026-11-27-bend-take-back.md).
 * The Armijo test judges the point reached, and a short enough step takes
 * nothing back (every vertex's bound lies max_bend beyond where it is), so
 * the backtracking ends where a straight one would. */
/* The start multipliers (conjugate gradients, warm_start.c) leave 0.30 and
 * 0.58 of the tension unbalanced at N = 9600 and 19 200 from the N = 2400
 * trefoil, 0.99 at 38 400 from the converged 19 200. Below this the
 * curvature cap only slows the solve (9600: 375 steps against 225 at 0.05,
 * 300 at 0.1, 240 at 0.2); above it, it is what settled the 38 400 solve. */
#define CAUTIOUS_RESIDUAL 0.75

/* The largest vertex displacement of dir (3 nv entries). */
static double max_vertex_move(const double *dir, size_t nv)
{
    double m = 0.0;
    for (size_t i = 0; i < nv; i++)
        m = fmax(m, v3_dot(dir + 3 * i, dir + 3 * i));
    return sqrt(m);
}

static double stationarity(const solver *s, const double *grad)
{
    double m = 0.0;
    for (size_t i = 0; i < 3 * s->nv; i++)
        m = fmax(m, fabs(grad[i]));
    m /= s->l0min;
    for (int k = 0; k < s->nc; k++)
        m = fmax(m, fabs(grad[3 * s->nv + (size_t)k]) / (double)s->ne[k]);
    return m;
}

static void update_multipliers(solver *s)
{
    for (size_t i = 0; i < s->nv; i++) {
        if (s->next[i] != NONE)
            s->lam_e[i] = s->pi_e[i];
        s->lam_m[i] = s->pi_m[i];
    }
    for (size_t r = 0; r < s->nsp; r++)
        s->sp[r].lam = s->pi_s[r];
}

/* Measures y's ropelength (the oracle, scale free) and keeps y as the best
 * iterate if it is the shortest yet. Only near feasibility: further out the
 * rescaled curve is long anyway and the oracle's time would be wasted. */
#define BEST_VIOL 1e-3
/* the end's two restorations take up to a few factorizations each */
#define RESTORE_RESERVE 8.0

/* A constrained curve is not rescaled (its planes stay where they are), so
 * its ropelength is its length at thickness 1: the oracle's length /
 * thickness where it is a little under 1 (what that costs, honestly), its
 * length where it is loose (a loose clasp is as long as it is, and scaling
 * it down would take its ends off their planes). A result is taken within
 * CONSTRAINED_OUT_TOL of thickness 1, as the polish's (polish.c); a start
 * below CONSTRAINED_MIN_THICKNESS is refused (skipped = 1), as the
 * augmented Lagrangian would first have to push the strands apart by more
 * than the guard lets a step bring them together. */
#define CONSTRAINED_OUT_TOL 1e-6
#define CONSTRAINED_MIN_THICKNESS 0.85
static double constrained_ropelength(const tr_thickness *th) { return th->length / fmin(th->thickness, 1.0); }

static int has_constrained_vertex(const tr_curve *c)
{
    for (size_t i = 0; c->ncst > 0 && c->vcst && i < c->nv; i++)
        if (c->vcst[i] >= 0)
            return 1;
    return 0;
}

/* y's ropelength as the oracle measures it (*th), at thickness 1; at
 * y + ylo where ylo (low parts, curve.h) is not NULL */
static int measure_iterate_lo(solver *s, const double *y, const double *ylo, double *rl, tr_thickness *th,
                              tr_error *err)
{
    memcpy(s->probe.x, y, 3 * s->nv * sizeof *y);
    tr_curve_drop_lo(&s->probe);
    if (ylo) {
        int rc = tr_curve_want_lo(&s->probe, err);
        if (rc)
            return rc;
        memcpy(s->probe.lo, ylo, 3 * s->nv * sizeof *ylo);
    }
    int rc = tr_newton_i_model_thickness(s->p, &s->probe, NULL, th, err);
    if (rc)
        return rc;
    *rl = th->ropelength;
    if (s->ncv > 0)
        *rl = th->thickness >= 1.0 - CONSTRAINED_OUT_TOL ? constrained_ropelength(th) : INFINITY;
    if (!(th->thickness > 0))
        *rl = INFINITY;
    return TR_OK;
}

static int measure_iterate(solver *s, const double *y, double *rl, tr_thickness *th, tr_error *err)
{
    return measure_iterate_lo(s, y, NULL, rl, th, err);
}

/* The end game in extended precision. A vertex held in doubles is known
 * to eps R, so a MinRad row (a second difference of size l0^2) carries
 * rounding of eps R / l0^2 of itself: 1e-8 a vertex at N = 200 640, and
 * the restoration in doubles left the settled trefoil's worst row 1.9e-7
 * over, which the rescaling to thickness 1 charged as 5e-6 of its
 * ropelength (bench/notes/2026-11-29-n200640-settles.md). Restored once
 * more on y + ylo, the positions with low parts (curve.h), its rows are
 * evaluated from edges exact to eps l0 and the correction lands below the
 * step between doubles: the rows close to the restoration's own accuracy.
 * *ylo is the low parts where the oracle measures y + ylo shorter than y
 * (rl_y), else NULL; then *rl_out and *th_out (when not NULL) are that
 * measurement. */
static int extended_end(solver *s, double *y, const double *lo_in, double rl_y, double deadline, double **ylo,
                        double *rl_out, tr_thickness *th_out, tr_error *err)
{
    *ylo = NULL;
    if (LDBL_MANT_DIG <= DBL_MANT_DIG)
        return TR_OK;
    size_t n = s->n, n3 = 3 * s->nv;
    double *yx = malloc(n * sizeof *yx), *lo = calloc(n3, sizeof *lo);
    int rc = TR_OK;
    if (!yx || !lo) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (extended restoration)");
        goto done;
    }
    memcpy(yx, y, n * sizeof *y);
    if (lo_in)
        memcpy(lo, lo_in, n3 * sizeof *lo);
    double rv, rv_edge, rl;
    tr_thickness th;
    if ((rc = tr_newton_i_restore_lo(s, yx, lo, deadline, &rv, &rv_edge, err)) ||
        (rc = measure_iterate_lo(s, yx, lo, &rl, &th, err)))
        goto done;
    if (rl < rl_y) {
        memcpy(y, yx, n * sizeof *y);
        *ylo = lo;
        lo = NULL;
        if (rl_out)
            *rl_out = rl;
        if (th_out)
            *th_out = th;
    }
done:
    free(yx);
    free(lo);
    return rc;
}

static int ensure_best(solver *s, tr_error *err)
{
    if (!s->probe.x) {
        int rc = tr_curve_copy(&s->probe, &s->w, err);
        if (rc)
            return rc;
    }
    if (!s->best_y) {
        s->best_y = malloc(s->n * sizeof *s->best_y);
        s->restored = malloc(s->n * sizeof *s->restored);
        if (!s->best_y || !s->restored)
            return tr_fail(err, TR_ENOMEM, "out of memory (Newton solver)");
        /* no best yet: nothing in best_y is read until consider() has
         * put an iterate there (has_best) */
        s->best_rl = INFINITY;
        s->best_viol_edge = INFINITY;
    }
    /* the low parts' too, once the iterate has them (a best taken before
     * was a double iterate: its low parts are 0) */
    if (s->ylo && !s->best_lo) {
        s->best_lo = calloc(3 * s->nv, sizeof *s->best_lo);
        s->restored_lo = calloc(3 * s->nv, sizeof *s->restored_lo);
        if (!s->best_lo || !s->restored_lo)
            return tr_fail(err, TR_ENOMEM, "out of memory (Newton solver)");
    }
    return TR_OK;
}

/* Whether best_y holds an iterate. A constrained rope's iterates may all be
 * a little under thickness 1 (a refined clasp pressed through itself), and
 * then none is a best: best_y was once read all the same, uninitialised,
 * as the solver's result and its checkpoints (2 x 3200 and 2 x 6400 clasps
 * with short ends: a checkpoint of zeros, the result "passes through
 * itself", the run failed). */
static int has_best(const solver *s) { return s->best_y && isfinite(s->best_rl); }

/* cand (viol_edge: its edges' violation; restored: a restoration's
 * result) becomes the best if the oracle measures it shorter than the best
 * yet */
static int consider(solver *s, const double *cand, const double *candlo, double viol_edge, int restored,
                    tr_error *err)
{
    tr_thickness th;
    double rl;
    int rc = measure_iterate_lo(s, cand, candlo, &rl, &th, err);
    if (rc)
        return rc;
    if (isfinite(rl) && rl < s->best_rl) {
        s->best_rl = rl;
        s->best_viol_edge = viol_edge;
        s->best_thickness = th.thickness;
        s->best_restored = restored;
        memcpy(s->best_y, cand, s->n * sizeof *cand);
        if (s->best_lo) {
            if (candlo)
                memcpy(s->best_lo, candlo, 3 * s->nv * sizeof *candlo);
            else
                memset(s->best_lo, 0, 3 * s->nv * sizeof *s->best_lo);
        }
    }
    return TR_OK;
}

/* y restored onto its rows (restore.c) as a candidate for the best: it is
 * one wherever a row of y is over by more than rounding */
static int consider_restored(solver *s, const double *y, const double *ylo, double deadline, tr_error *err)
{
    double rv, rv_edge;
    memcpy(s->restored, y, s->n * sizeof *y);
    double *rlo = s->restored_lo;
    if (rlo) {
        if (ylo)
            memcpy(rlo, ylo, 3 * s->nv * sizeof *ylo);
        else
            memset(rlo, 0, 3 * s->nv * sizeof *rlo);
    }
    int rc = tr_newton_i_restore_lo(s, s->restored, rlo, deadline, &rv, &rv_edge, err);
    if (rc)
        return rc;
    return consider(s, s->restored, rlo, rv_edge, 1, err);
}

static int keep_best(solver *s, const double *y, double deadline, tr_error *err)
{
    if (!(s->viol < BEST_VIOL))
        return TR_OK;
    int rc = ensure_best(s, err);
    if (!rc)
        rc = consider(s, y, s->ylo, s->viol_kind[0], 0, err);
    const tr_newton_params *p = s->p;
    if (rc || !p->checkpoint || !(p->checkpoint_every > 0) || tr_clock_seconds() - s->t_ckpt < p->checkpoint_every)
        return rc;
    /* a checkpoint is due: the iterate restored (a few factorizations, so
     * only here and at the end, not at every pass) */
    if ((rc = consider_restored(s, y, s->ylo, deadline, err)))
        return rc;
    s->t_ckpt = tr_clock_seconds();
    /* a checkpoint is a valid rope (equal edges to 1e-6, as --resume
     * asks), so only a best whose edges are equal to 1e-7 goes out, at
     * thickness 1 (its MinRad and strut rows are met by the rescaling; a
     * constrained rope as it is, within CONSTRAINED_OUT_TOL of it, its
     * planes do not scale) */
    if (!has_best(s) || !(s->best_viol_edge <= 1e-7))
        return TR_OK;
    /* the best with its own low parts (probe's are the last measured
     * candidate's), scaled with them */
    memcpy(s->probe.x, s->best_y, 3 * s->nv * sizeof *s->best_y);
    tr_curve_drop_lo(&s->probe);
    if (s->best_lo && s->ncv == 0 && tr_curve_want_lo(&s->probe, &(tr_error){0}) == TR_OK)
        memcpy(s->probe.lo, s->best_lo, 3 * s->nv * sizeof *s->best_lo);
    if (s->ncv == 0 && s->probe.lo)
        tr_curve_scale_by(&s->probe, 1.0 / s->best_thickness);
    for (size_t i = 0; s->ncv == 0 && !s->probe.lo && i < 3 * s->nv; i++)
        s->probe.x[i] /= s->best_thickness;
    tr_error ce = {0};
    p->checkpoint(p->user, &s->probe, &ce);
    return TR_OK;
}

/* The largest vertex displacement since the strut list was built. */
static double moved_since_build(const solver *s, const double *y)
{
    double m = 0.0;
    for (size_t i = 0; i < s->nv; i++)
        m = fmax(m, v3_dist2(y + 3 * i, s->w.x + 3 * i));
    return sqrt(m);
}

/* Hands the solver's state at y and the loop's variables lp to p->state
 * (its error, or one filling it, does not stop the solve). */
static void give_state(solver *s, const double *y, const tr_newton_loop *lp, const tr_newton_stats *st, double t0)
{
    const tr_newton_params *p = s->p;
    s->t_state = tr_clock_seconds();
    long steps = st->iters + (p->resume ? p->resume->steps : 0);
    double seconds = s->t_state - t0 + (p->resume ? p->resume->seconds : 0.0);
    tr_error se = {0};
    if (tr_newton_i_state_fill(s, y, lp, steps, seconds, &se) == TR_OK)
        p->state(p->user, &s->out, &se);
}

/* p->end_state (its old content freed) the solver's state at y: moved
 * there from s->out, which a next fill allocates again. A failure leaves
 * it empty (the next level then starts as without it). */
static void keep_end_state(solver *s, const double *y, const tr_newton_loop *lp, const tr_newton_stats *st, double t0)
{
    const tr_newton_params *p = s->p;
    long steps = st->iters + (p->resume ? p->resume->steps : 0);
    double seconds = tr_clock_seconds() - t0 + (p->resume ? p->resume->seconds : 0.0);
    tr_error se = {0};
    tr_newton_state_free(p->end_state);
    memset(p->end_state, 0, sizeof *p->end_state);
    if (tr_newton_i_state_fill(s, y, lp, steps, seconds, &se) == TR_OK) {
        *p->end_state = s->out;
        memset(&s->out, 0, sizeof s->out);
    }
}

/* The minimisation itself, on y (3 nv + ncomp); resumed: the loop's
 * variables go on from *resumed (s->mu and s->band set from the state). */
static int minimise(solver *s, double *y, tr_newton_stats *st, double t0, const tr_newton_loop *resumed,
                    tr_error *err)
{
    const tr_newton_params *p = s->p;
    size_t n = s->n, nv = s->nv;
    double *grad = malloc(n * sizeof *grad), *dir = malloc(n * sizeof *dir), *yt = malloc(n * sizeof *yt);
    /* the gauge's vertices stay where they are when bends are taken back */
    unsigned char *held = calloc(nv ? nv : 1, 1);
    tr_bend_chain chain = {.nv = nv, .prev = s->prev, .next = s->next, .comp = s->comp, .l0 = s->l0, .held = held};
    /* the iterate's low parts (newton_internal.h ylo): a resumed state's,
     * else from zero (the start is the doubles it was given) */
    if (!s->ylo)
        s->ylo = calloc(3 * nv + 1, sizeof *s->ylo);
    free(s->ytlo);
    s->ytlo = calloc(3 * nv + 1, sizeof *s->ytlo);
    int rc = TR_OK;
    if (!grad || !dir || !yt || !held || !s->ylo || !s->ytlo) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (Newton solver)");
        goto done;
    }
    for (int k = 0; k < s->nfixed; k++)
        if (s->fixed[k] < 3 * nv)
            held[s->fixed[k] / 3] = 1;
    if (!resumed) {
        /* a coarse level's penalty (prolong.c), or the first */
        if (s->mu > 0.0)
            s->band = fmin(1.0, p->mu0 / (s->mu * s->l0min));
        else {
            s->mu = p->mu0 / s->l0min;
            s->band = 1.0;
        }
    }
    s->t_ckpt = s->t_state = t0;
    double deadline = p->time_limit > 0 ? t0 + p->time_limit : INFINITY;
    /* A MinRad row's second difference w ~ l0^2 kappa carries the rounding
     * of the edges it is formed from: eps l0 with the iterate's low parts
     * (ylo), so its relative violation is known to ~eps / l0 (2e-12 at
     * N = 200 640; the struts', from the doubles alone, to eps R), and
     * asking for less only drives mu up against rounding, and the
     * Levenberg shift that mu brings with it stalls the steps. In doubles
     * alone it was 16 eps R / l0^2 (R the coordinates' size: 1e-11 at
     * N = 9600, 5e-7 at 200 640), the floor this was before the low parts;
     * it stays where it is below 1e-9 (the small N's solves as they were),
     * and is 1e-9 above: asked for 1e-11, the 2 x 6400 clasp had its
     * length to 1e-10 at step 216 and then spent 800 more with its tip's
     * MinRad rows going between 1e-9 and 4e-8 over (2026-11-29). */
    double reach = 0.0;
    for (size_t i = 0; i < 3 * nv; i++)
        reach = fmax(reach, fabs(y[i]));
    double floor_doubles = fmin(16.0 * DBL_EPSILON * reach / (s->l0min * s->l0min), 1e-9);
    double viol_tol = fmax(fmax(p->viol_tol, floor_doubles), fmax(16.0 * DBL_EPSILON / s->l0min, 4.0 * DBL_EPSILON * reach));
    double omega = 1e-2, prev_viol = INFINITY, lm = 0.0, prev_len = INFINITY;
    int inner = 0, settled = 0, last_full = 0, moved = 0, stuck = 0, inner_done = 0;
    /* a resumed run's iterations go on counting from the stopped run's:
     * max_iter bounds them together, as it would have bounded the run that
     * did not stop */
    int it = 0;
    if (resumed) {
        omega = resumed->omega;
        prev_viol = resumed->prev_viol;
        lm = resumed->lm;
        prev_len = resumed->prev_len;
        viol_tol = resumed->viol_tol;
        inner = resumed->inner;
        settled = resumed->settled;
        last_full = resumed->last_full;
        moved = resumed->moved;
        stuck = resumed->stuck;
        inner_done = resumed->inner_done;
        st->outer = resumed->outer;
        it = resumed->iter;
    }
/* the loop's variables, for a state */
#define LOOP_NOW                                                                                                  \
    ((tr_newton_loop){.omega = omega, .prev_viol = prev_viol, .lm = lm, .prev_len = prev_len, .viol_tol = viol_tol, \
                      .iter = it, .outer = st->outer, .inner = inner, .settled = settled, .last_full = last_full,   \
                      .moved = moved, .stuck = stuck, .inner_done = inner_done})
    for (; it < p->max_iter; it++) {
        /* a time-limited run leaves the end's restorations (keep_best)
         * RESTORE_RESERVE mean steps of its time */
        double now = tr_clock_seconds();
        double reserve = st->iters ? RESTORE_RESERVE * (now - t0) / st->iters : 0.0;
        if ((p->time_limit > 0 && now - t0 > p->time_limit - fmin(reserve, 0.1 * p->time_limit)) ||
            (p->stop && *p->stop))
            break;
        /* a state between two steps: all a resumed run needs to take
         * this one's next */
        if (p->state && p->state_every > 0 && now - s->t_state >= p->state_every)
            give_state(s, y, &LOOP_NOW, st, t0);
        double te = tr_clock_seconds();
        s->oom = 0;
        double f = tr_newton_i_al_eval_lo(s, y, s->ylo, grad, 1);
        /* the line search's trial evaluations overwrite these */
        double len_y = s->length, viol_y = s->viol, vk[3] = {s->viol_kind[0], s->viol_kind[1], s->viol_kind[2]};
        size_t worst_m = s->worst_m;
        st->t_eval += tr_clock_seconds() - te;
        if (s->oom) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory (Hessian)");
            goto done;
        }
        if (s->dev_rc) {
            *err = s->dev_err;
            rc = s->dev_rc;
            goto done;
        }
        double stat = stationarity(s, grad);
        st->stat = stat;
        st->max_viol = s->viol;
        st->active = s->active;
        st->struts = s->nsp;
        if (stat <= omega || inner >= p->max_inner || inner_done) {
            inner_done = 0;
            if (s->viol <= viol_tol && stat <= p->stat_tol) {
                st->converged = 1;
                break;
            }
            /* Settled: feasible to viol_tol and the length unchanged to
             * 1e-11 over three multiplier updates. The unbalanced force can
             * stay O(l0) where a strand wraps a single edge of another
             * (many struts on one edge: the discrete problem's multipliers
             * are then not unique and the force the wrap puts on that edge
             * has no balance within MinRad), while the length no longer
             * moves: bench/notes/2026-11-25-converged-last-digits.md. */
            /* or no step accepted over three passes: the line search
             * finds no decrease left to resolve, and the multiplier
             * updates alone do not move the rope */
            stuck = moved ? 0 : stuck + 1;
            moved = 0;
            if (stuck >= 3 || (s->viol <= viol_tol && fabs(s->length - prev_len) <= 1e-11 * s->length)) {
                if (++settled >= 3 || stuck >= 3) {
                    st->settled = 1;
                    break;
                }
            } else
                settled = 0;
            prev_len = s->length;
            if ((rc = keep_best(s, y, deadline, err)))
                goto done;
            update_multipliers(s);
            /* mu grows only when the pass was solved (small gradient, or
             * the last step a full Newton step): after max_inner damped
             * steps a violation that did not fall says the inner solve is
             * unfinished, not that the penalty is too weak, and raising
             * mu then made the next passes stiffer still (at N = 9600 with
             * 8 or 12 steps per pass mu ran to its cap and the solve ended
             * 1e-5 long) */
            if (s->viol > 0.25 * prev_viol && s->viol > viol_tol && (stat <= omega || last_full))
                s->mu = fmin(10.0 * s->mu, p->mu_max / s->l0min);
            /* At the cap with the rope at its length, each update closes
             * the MinRad rows by a few per cent (N = 76 800: 4.4e-7 to
             * 1.7e-7 over in 160 steps), and there the passes mostly end
             * unsolved, so the rise above never fires; a cap of 1e7 / l0
             * from that state settled the level in 139 steps. Raised
             * earlier (rows 1e-6 .. 1e-5 over, or from the start at
             * 19 200) it stalled the line search, hence the violation's
             * bound: bench/notes/2026-11-30-penalty-cap.md. */
            else if (p->mu_late > p->mu_max && s->mu >= (1.0 - 1e-12) * p->mu_max / s->l0min &&
                     s->viol <= p->late_viol && s->viol > 0.25 * prev_viol && s->viol > viol_tol)
                s->mu = fmin(10.0 * s->mu, p->mu_late / s->l0min);
            s->band = fmin(1.0, p->mu0 / (s->mu * s->l0min));
            prev_viol = s->viol;
            omega = fmax(0.1 * omega, 0.1 * p->stat_tol);
            inner = 0;
            st->outer++;
            /* the strut list is re-selected between passes only where the
             * rope has moved a tenth of an edge since it was built: the
             * local minima it keeps do not move before that, and a rebuild
             * costs a few factorizations at N = 9600 */
            if (moved_since_build(s, y) > 0.1 * s->l0min) {
                double tr = tr_clock_seconds();
                if ((rc = tr_newton_i_rebuild(s, y, NULL, err)))
                    goto done;
                st->rebuilds++;
                st->t_rebuild += tr_clock_seconds() - tr;
            }
            continue;
        }
        /* Levenberg-Marquardt: a direction that is no descent (the
         * factor of a nearly singular matrix is inaccurate) or that would
         * move a vertex far beyond the cap (a soft mode, nothing holding
         * it yet) is computed again with a larger shift, in units of the
         * tension's stiffness 1 / l0 */
        double alpha = 0.0, ft = f, slope = 0.0, mv = 0.0, cap = 1.0;
        int ok = 0;
        double ts = tr_clock_seconds(), lm_in = lm;
        for (int lmtry = 0; lmtry < 6 && !ok; lmtry++) {
            if (lmtry > 0)
                lm = fmax(100.0 * lm, 1e-6 / s->l0min);
            if ((rc = tr_newton_i_dir(s, grad, dir, &lm, st, err)))
                goto done;
            mv = max_vertex_move(dir, nv);
            cap = 1.0;
            if (mv > p->max_move)
                cap = p->max_move / mv;
            double bend = isfinite(s->max_bend) && s->bend_cap ? tr_bend_max_change(&chain, dir) : 0.0;
            if (bend * cap > s->max_bend)
                cap = s->max_bend / bend;
            for (int k = 0; k < s->nc; k++) {
                double dl = fabs(dir[3 * nv + (size_t)k]);
                if (dl * cap > 0.1 * s->l0[k])
                    cap = 0.1 * s->l0[k] / dl;
            }
            if (mv > 4.0 * p->max_move && lmtry < 5)
                continue;
            slope = 0.0;
            for (size_t k = 0; k < n; k++)
                slope += grad[k] * dir[k];
            alpha = cap;
            for (int ls = 0; ls < 20 && slope < 0.0; ls++) {
                tr_newton_i_add_step(3 * nv, n, y, s->ylo, alpha, dir, yt, s->ytlo);
                if (isfinite(s->max_bend) && !s->bend_cap)
                    tr_bend_take_back(&chain, y, yt, s->max_bend);
                ft = tr_newton_i_al_eval_lo(s, yt, s->ytlo, NULL, 0);
                double dlen = 0.0;
                for (int k = 0; k < s->nc; k++)
                    dlen += (double)s->ne[k] * (yt[3 * nv + (size_t)k] - y[3 * nv + (size_t)k]);
                if (s->dmin > GUARD_DIST && (ft - f) + dlen <= 1e-4 * alpha * slope) {
                    ok = 1;
                    break;
                }
                alpha *= 0.5;
            }
        }
        st->t_search += tr_clock_seconds() - ts;
        st->iters++;
        inner++;
        if (p->progress) {
            tr_newton_progress pr = {.iter = it, .outer = st->outer, .length = len_y, .viol = viol_y,
                                     .viol_edge = vk[0], .viol_minrad = vk[1], .viol_strut = vk[2],
                                     .stat = stat, .mu = s->mu * s->l0min, .lm = lm, .step = ok ? alpha : 0.0,
                                     .struts = s->nsp, .active = s->active, .worst_minrad = worst_m,
                                     .seconds = tr_clock_seconds() - t0};
            p->progress(p->user, &pr);
        }
        /* next time, start from a tenth of the shift that worked; after
         * a failure from the shift tried first (the escalation found
         * nothing, and carried on it grew 1e12 per step until the
         * directions vanished) */
        lm = 0.1 * (ok ? lm : lm_in);
        if (!ok) {
            /* no descent along the Newton direction (rounding at the
             * bottom): the inner problem is as solved as it gets */
            inner = p->max_inner;
            last_full = 0;
            continue;
        }
        last_full = alpha == 1.0;
        /* A full Newton step whose predicted decrease (the Newton
         * decrement, -grad . dir) is below inner_decrement of the length
         * ends the pass: the inner problem is solved as far as the length
         * can tell. The unbalanced force alone cannot say so where many
         * struts press on one edge (it stayed at 1e-2 while full steps
         * moved vertices by 1e-11 with decrements of 1e-16), and every
         * pass then ran its max_inner steps: the N = 9600 trefoil from
         * the N = 2400 file took 225 steps, 93 with this; 2400 587 and
         * 247, 19 200 240 and 140
         * (bench/notes/2026-11-27-newton-decrement.md) */
        if (last_full && -slope <= p->inner_decrement * s->length)
            inner_done = 1;
        moved = 1;
        memcpy(y, yt, n * sizeof *y);
        memcpy(s->ylo, s->ytlo, 3 * nv * sizeof *y);
        /* the strut list is good while no vertex has moved skin / 4 */
        if (moved_since_build(s, y) > fmin(0.25 * p->skin, 0.5 * s->l0min)) {
            double tr = tr_clock_seconds();
            if ((rc = tr_newton_i_rebuild(s, y, NULL, err)))
                goto done;
            st->rebuilds++;
            st->t_rebuild += tr_clock_seconds() - tr;
        }
    }
    /* stopped unfinished (the time limit, a stop, max_iter): where it
     * stopped, before the end's restorations, which take the best */
    if (p->state && !st->converged && !st->settled)
        give_state(s, y, &LOOP_NOW, st, t0);
    /* a finished solve's state, for the level refined from it */
    if (p->end_state && (st->converged || st->settled))
        keep_end_state(s, y, &LOOP_NOW, st, t0);
#undef LOOP_NOW
done:
    free(grad);
    free(held);
    free(dir);
    free(yt);
    return rc;
}

/* The solver on cv scaled by 1 / unit, its strut list and (if asked) its
 * warm multipliers; *y the variables (3 nv positions, a length per
 * component). */
static int prepare(solver *s, const tr_curve *cv, double unit, double **y, tr_newton_stats *st, tr_error *err)
{
    int rc = solver_init(s, cv, 1.0 / unit, err);
    if (rc)
        return rc;
    *y = malloc(s->n * sizeof **y);
    if (!*y)
        return tr_fail(err, TR_ENOMEM, "out of memory (Newton solver)");
    memcpy(*y, s->w.x, 3 * s->nv * sizeof **y);
    for (int k = 0; k < s->nc; k++)
        (*y)[3 * s->nv + (size_t)k] = s->l0[k];
    double tr = tr_clock_seconds();
    if ((rc = tr_newton_i_rebuild(s, *y, &s->first_bound, err)))
        return rc;
    st->t_rebuild += tr_clock_seconds() - tr;
    s->warm_residual = s->start_residual = 1.0;
    /* a stop asked for, or the time limit passed, during the list's build:
     * the minimisation stops at once, so the warm start (a factorisation,
     * a quarter second at 2 x 10^5 vertices) would be time lost */
    if (tr_deadline_passed(&s->first_bound))
        return TR_OK;
    if (s->p->warm_start && (rc = tr_newton_i_warm_multipliers(s, *y, err)))
        return rc;
    return TR_OK;
}

/* The solver set up from p->resume's state on cv's topology
 * (newton_state.c), the best iterate of the stopped run among them; *y the
 * variables, *lp the loop's. */
static int resume_from_state(solver *s, const tr_curve *cv, double **y, tr_newton_loop *lp, tr_error *err)
{
    const tr_newton_state *r = s->p->resume;
    if (r->nv != cv->nv || r->ncomp != cv->ncomp)
        return tr_fail(err, TR_EINVAL, "newton: the state is of %zu vertices in %d components, the curve has %zu in %d",
                       r->nv, r->ncomp, cv->nv, cv->ncomp);
    int rc = solver_init(s, cv, 1.0, err);
    if (rc)
        return rc;
    *y = malloc(s->n * sizeof **y);
    if (!*y)
        return tr_fail(err, TR_ENOMEM, "out of memory (Newton solver)");
    if ((rc = tr_newton_i_state_apply(s, r, s->p->resume_warm, *y, lp, err)))
        return rc;
    if (r->has_best) {
        if ((rc = ensure_best(s, err)))
            return rc;
        memcpy(s->best_y, r->best_y, s->n * sizeof *s->best_y);
        if (s->best_lo && r->has_lo && r->best_lo)
            memcpy(s->best_lo, r->best_lo, 3 * s->nv * sizeof *s->best_lo);
        s->best_rl = r->best_rl;
        s->best_viol_edge = r->best_viol_edge;
        s->best_thickness = r->best_thickness;
        s->best_restored = r->best_restored;
    }
    return TR_OK;
}

/* The solver set up from cv's positions (its unit, its strut list, the
 * warm start's multipliers, the MinRad rows' scale and the bend cap); *y
 * the variables. *loose: tight_only, and the start is not tight (st says
 * why; nothing to solve). */
static int start_from_curve(solver *s, const tr_curve *cv, const tr_thickness *th0, int constrained, double **y,
                            tr_newton_stats *st, int *loose, tr_error *err)
{
    const tr_newton_params *prm = s->p;
    int rc;
    *loose = 0;
    /* The solver's unit: thickness 1, except where MinRad alone holds the
     * start below its struts by a little (a spline through a tight
     * polygon overshoots its curvature where the curvature jumps: MinRad
     * 0.93 at the N = 2400 trefoil spline-refined to 9600): scaling by
     * MinRad would leave every contact 7 % apart, to be closed first order
     * by Newton steps; at the struts' scale only those few MinRad rows
     * start violated, which the augmented Lagrangian restores locally. That
     * holds for a tight start only (the warm start says which): a loose one
     * started violated just has further to go (the wobbled 32-gon: 208
     * steps against 76). */
    double unit = th0->thickness;
    int overshoot = isfinite(th0->dcsd) && th0->minrad < (1.0 - 1e-4) * 0.5 * th0->dcsd &&
                    th0->minrad >= MINRAD_SLACK * 0.5 * th0->dcsd;
    if (overshoot)
        unit = 0.5 * th0->dcsd;
    /* a constrained curve stays at its scale: the overshooting MinRad rows
     * start violated and are stiffened all the same (below) */
    if (constrained)
        unit = 1.0;
    if ((rc = prepare(s, cv, unit, y, st, err)))
        return rc;
    if (overshoot && !constrained && !(s->warm_residual < TIGHT_RESIDUAL)) {
        solver_free(s);
        free(*y);
        *y = NULL;
        memset(s, 0, sizeof *s);
        s->p = prm;
        if ((rc = prepare(s, cv, th0->thickness, y, st, err)))
            return rc;
    }
    st->warm_residual = s->warm_residual;
    /* A constrained start pressed below thickness 1 (a tight clasp refined:
     * the spline or the low-pass bulges where strands touch, and the
     * planes forbid scaling it back) is not loose, whatever the warm start
     * makes of its violated rows (a residual of 1 to 12 at 2 x 200): it has
     * no room for first-order steps, which would only settle it longer. */
    int pressed = constrained && th0->thickness < 1.0 - CONSTRAINED_OUT_TOL;
    if (prm->tight_only && !pressed && !(prm->warm_start && s->warm_residual < TIGHT_RESIDUAL)) {
        st->loose = *loose = 1;
        st->why_rejected = "the start is not tight (its contacts do not hold the tension)";
        return TR_OK;
    }
    /* A pressed constrained start whose MinRad is what is violated (the
     * refinement overshoots where the curvature jumps, as a spline does;
     * MinRad 0.986 at the 2 x 400 clasp refined to 2 x 800) is the case
     * above, only not scaled: stiff MinRad rows, whatever the warm start
     * made of its violated rows. At the loose scale the rows went 69 % over
     * in the first passes there, mu reached its cap in eight passes and
     * 4445 steps ended unconverged (KKT 0.57); stiff, it settles in 120
     * steps, 1 s, 7e-5 shorter. Where MinRad is not violated (2 x 50
     * refined to 2 x 100: MinRad 1.18, struts 1.999) the stiff rows stall
     * the steps as from a loose start (4445 steps against 124). */
    int minrad_pressed = pressed && th0->minrad < 1.0 - CONSTRAINED_OUT_TOL;
    s->max_bend = INFINITY;
    /* A tight start in the vertex model (a knot tightened in Rawdon's,
     * which the warm start finds tight: the models differ by O(e^2)) is
     * none of the cases above, its MinRad at 1 and its vertices a little
     * over 2 apart, but its first full steps bend vertices past MinRad as
     * a refined start's do: with the vertex rows the rope relaxes where
     * strands touch, and the inactive MinRad rows there are not in the
     * Newton matrix. At N = 19 200 (the trefoil tightened in Rawdon's
     * model) MinRad went 34 % over in the first pass, and the solve
     * wandered at mu 1e4 with steps cut to 1/8 and MinRad 2 to 9 % over
     * for 300 steps (423 steps, 155 s); the bend taken back alone (its
     * bound is max(kappa, 1) + 0.05), with the guard or without, held
     * MinRad at 5 % over for as long: the stiff rows (S = 0.1) are what
     * takes the overshoot back. With the bend taken back and the guard
     * too: 91 steps, 57 s; 129, 146, 149 against 202, 112, 185 at 1600,
     * 4800, 9600 (stiff rows alone: 310, 126, 125 and 118 at 19 200), the
     * results within the spread of the model's nearby settled points
     * (4.5e-8 at 4800) (bench/notes/2026-11-28-vertex-tight-start.md).
     * A loose start (the wobbled 32-gon) is left as it was. */
    int vertex_tight = prm->vertex_contacts && s->warm_residual < TIGHT_RESIDUAL;
    /* A tight start in Rawdon's model that neither overshoots nor is
     * pressed, whose conjugate-gradient multipliers hold little of the
     * tension (start_residual above CAUTIOUS_RESIDUAL) though the damped
     * ones say it is tight: a solver's iterate rescaled to thickness 1, as
     * a run stopped without its state leaves it (newton_run's OUT.ckpt).
     * Restarted at the loose scale, its first steps took MinRad 20 to 30 %
     * over at N = 38 400 (the checkpoint at step 130 of the rung from the
     * converged 19 200, 32.7431246 as rescaled: 46 steps later 32.7429295
     * with MinRad 27 % over at mu 100); with the tight start's rule it
     * settled in 205 steps at 32.7429351282 (the unbroken rung:
     * 32.7429351290). Only there: at
     * 4800 and 9600 such restarts (start residuals 0.38, 0.37) took 158
     * and 140 steps at the loose scale, 214 and 71 with the rule, and the
     * N = 2400 file (0.11) 156 against 240 and 2.5e-8 longer
     * (bench/notes/2026-11-29-tight-restart.md). */
    int iterate_tight = !prm->vertex_contacts && !overshoot && !constrained && s->warm_residual < TIGHT_RESIDUAL &&
                        s->start_residual > CAUTIOUS_RESIDUAL;
    if ((overshoot && s->warm_residual < TIGHT_RESIDUAL) || minrad_pressed || vertex_tight || iterate_tight) {
        /* a tight start's steps are small: where the multipliers it
         * starts with hold less than a quarter of the tension, the
         * curvature cap holds them to the model (bend.h); a loose
         * start's steps may not be small */
        if (s->start_residual > CAUTIOUS_RESIDUAL || vertex_tight)
            s->max_bend = prm->max_bend;
        /* the guard goes with the bends taken back: both are for the
         * inactive MinRad rows the model does not see (newton_rows.c) */
        if (isfinite(s->max_bend) && !constrained)
            s->guard = prm->minrad_guard;
        /* a clasp keeps the cap on the whole step: without it a refined
         * clasp's first steps folded a straight end through itself, and
         * bends taken back one vertex at a time have not been tried there */
        s->bend_cap = constrained;
        /* the same rows, rescaled: the multipliers scale with them */
        double f = MINRAD_ROW_SCALE_TIGHT / MINRAD_ROW_SCALE_LOOSE;
        for (int k = 0; k < s->nc; k++)
            s->scale_m[k] *= f;
        for (size_t i = 0; i < s->nv; i++)
            s->lam_m[i] *= f;
    }
    /* a coarse level's multipliers, at the rows' final scale */
    /* a coarse state that is not of this curve's coarser level (another
     * curve, fewer components) is left out: the warm start's stay */
    if (prm->coarse) {
        tr_error e2;
        rc = tr_newton_i_prolong(s, prm->coarse, *y, &e2);
        if (rc && rc != TR_EINVAL) {
            *err = e2;
            return rc;
        }
        st->coarse = rc == TR_OK;
        rc = TR_OK;
    }
    return TR_OK;
}

int tr_newton(tr_curve *cv, const tr_newton_params *prm, tr_newton_stats *st, tr_error *err)
{
    tr_newton_params defp;
    if (!prm) {
        tr_newton_params_default(&defp);
        prm = &defp;
    }
    memset(st, 0, sizeof *st);
    double t0 = tr_clock_seconds();
    int constrained = has_constrained_vertex(cv);
    /* the vertex model's rows are evaluated here: a backend's strut rows
     * are segment rows (backend.h) */
    tr_newton_params vertex_prm;
    if (prm->vertex_contacts) {
        for (int k = 0; k < cv->ncomp; k++)
            if (!cv->closed[k])
                return tr_fail(err, TR_EINVAL, "newton: the vertex contact model takes closed components only");
        vertex_prm = *prm;
        vertex_prm.backend = NULL;
        prm = &vertex_prm;
    }
    if (!(prm->max_move > 0 && prm->max_move <= prm->skin / 8) || !(prm->max_bend > 0) || prm->max_iter < 1 ||
        prm->max_inner < 1)
        return tr_fail(err, TR_EINVAL, "newton: need 0 < max_move <= skin / 8, max_bend > 0 and at least one iteration");
    tr_thickness th0;
    /* the start's measure is within the time limit and the stop flag too
     * (seconds at 10^6 vertices and more), as the first list build is */
    tr_deadline start_bound = {.at = prm->time_limit > 0 ? t0 + prm->time_limit : 0, .stop = prm->stop};
    tr_thickness_opts start_opts = {.bound = &start_bound};
    int rc = tr_newton_i_model_thickness(prm, cv, &start_opts, &th0, err);
    if (rc)
        return rc;
    if (!(th0.thickness > 0) || !isfinite(th0.thickness))
        return tr_fail(err, TR_EGEOMETRY, "newton: the curve has no finite positive thickness");
    if (constrained && th0.thickness < CONSTRAINED_MIN_THICKNESS) {
        st->skipped = 1;
        st->why_rejected = "constrained vertices, and the start is too far below thickness 1";
        return TR_OK;
    }
    st->ropelength_before = st->ropelength_after = constrained ? constrained_ropelength(&th0) : th0.ropelength;
    solver s;
    memset(&s, 0, sizeof s);
    s.p = prm;
    /* the first list build is the solve's whole cost at an absurd N (10^7
     * vertices: N^2 pairs within the cutoff), before any step: it stops at
     * the time limit or a signal (strut_list.c) */
    s.first_bound = (tr_deadline){.at = prm->time_limit > 0 ? t0 + prm->time_limit : 0, .stop = prm->stop};
    double *y = NULL, *ylo = NULL; /* ylo: the result's low parts (extended_end) */
    tr_newton_loop resumed;
    if (prm->resume) {
        if ((rc = resume_from_state(&s, cv, &y, &resumed, err)))
            goto done;
        st->warm_residual = s.warm_residual;
    } else {
        int loose;
        if ((rc = start_from_curve(&s, cv, &th0, constrained, &y, st, &loose, err)) || loose)
            goto done;
    }
    if ((rc = minimise(&s, y, st, t0, prm->resume ? &resumed : NULL, err)))
        goto done;
    /* no step, and the bound past: the end's evaluations and measures (two
     * seconds at 2 x 10^5 vertices, not looking at the clock) would only
     * hand back the start, after the time limit; a small curve's end is
     * quick, and goes on as before (a cancelled solve still says why) */
    if (st->iters == 0 && !prm->resume && tr_deadline_passed_for(&s.first_bound, s.nv)) {
        rc = tr_fail(err, TR_EINTERRUPTED, "the solver's %zu vertices: %s before its first step", s.nv,
                     tr_deadline_passed(&s.first_bound) == 2 ? "stopped by a signal" : "the time limit came");
        goto done;
    }
    /* the last iterate, or the best one the passes met */
    tr_newton_i_al_eval_lo(&s, y, s.ylo, NULL, 0);
    double deadline = prm->time_limit > 0 ? t0 + prm->time_limit : INFINITY;
    double best_before = has_best(&s) ? s.best_rl : INFINITY;
    if (s.viol < BEST_VIOL) {
        if ((rc = ensure_best(&s, err)) || (rc = consider(&s, y, s.ylo, s.viol_kind[0], 0, err)) ||
            (rc = consider_restored(&s, y, s.ylo, deadline, err)))
            goto done;
    }
    if (has_best(&s)) {
        /* the best by the oracle may be an earlier iterate, further over,
         * or a restoration that a second round takes further: restored
         * (again), unless it is the last iterate as it was, restored above */
        if (!(s.best_rl < best_before && !s.best_restored)) {
            memcpy(y, s.best_y, s.n * sizeof *y);
            if ((rc = consider_restored(&s, y, s.best_lo, deadline, err)))
                goto done;
        }
        memcpy(y, s.best_y, s.n * sizeof *y);
        if (s.best_lo) {
            if (!(ylo = malloc(3 * s.nv * sizeof *ylo))) {
                rc = tr_fail(err, TR_ENOMEM, "out of memory (Newton solver)");
                goto done;
            }
            memcpy(ylo, s.best_lo, 3 * s.nv * sizeof *ylo);
        }
        /* and once more in extended precision (extended_end) */
        double *ext = NULL;
        if ((rc = extended_end(&s, y, ylo, s.best_rl, deadline, &ext, NULL, NULL, err)))
            goto done;
        if (ext) {
            free(ylo);
            ylo = ext;
        }
    }
    /* the oracle decides: rescale to thickness 1 (a constrained curve:
     * its vertices exactly on their constraints instead), keep if shorter */
    memcpy(s.w.x, y, 3 * s.nv * sizeof *y);
    if (ylo) {
        if ((rc = tr_curve_want_lo(&s.w, err)))
            goto done;
        memcpy(s.w.lo, ylo, 3 * s.nv * sizeof *ylo);
    }
    /* a constrained vertex exactly on its constraint: x projected, no low
     * part (x + lo would be off it by lo) */
    for (size_t q = 0; q < s.ncv; q++) {
        tr_constraint_project(tr_newton_i_vertex_cst(&s, s.cv[q]), s.w.x + 3 * s.cv[q]);
        if (s.w.lo)
            memset(s.w.lo + 3 * s.cv[q], 0, 3 * sizeof *s.w.lo);
    }
    tr_thickness th;
    if ((rc = tr_newton_i_model_thickness(prm, &s.w, NULL, &th, err)))
        goto done;
    if (!(th.thickness > 0) || !isfinite(th.thickness)) {
        st->why_rejected = "the result has no finite positive thickness";
        goto done;
    }
    if (!constrained) {
        if (s.w.lo)
            tr_curve_scale_by(&s.w, 1.0 / th.thickness);
        else
            for (size_t i = 0; i < 3 * s.nv; i++)
                s.w.x[i] /= th.thickness;
        if ((rc = tr_newton_i_model_thickness(prm, &s.w, NULL, &th, err)))
            goto done;
    }
    double rl = constrained ? constrained_ropelength(&th) : th.ropelength;
    /* the oracle's MinRad at a nearly straight vertex carries the rounding
     * of its turning angle, ~1e-16 / theta^2 relative (4e-12 at N = 4800):
     * the rescaled curve is at thickness 1 to that, and the ropelength
     * compared is scale free. At a kappa = 1 vertex theta = l0, so the
     * tolerance grows like 1 / l0^2: at N = 38 400 the rescaled curve read
     * MinRad 1 - 2.0e-10 (0.66 eps / l0^2), and a fixed 1e-10 rejected a
     * converged solve as "not shorter" */
    double rescaled_tol = fmax(1e-10, 4.0 * DBL_EPSILON / (s.l0min * s.l0min));
    if (!(rl < st->ropelength_before) || !(th.thickness >= 1.0 - (constrained ? CONSTRAINED_OUT_TOL : rescaled_tol))) {
        st->why_rejected = "the result is not shorter";
        goto done;
    }
    tr_curve_drop_lo(cv);
    /* the low parts' room first: a failure leaves cv as it was */
    if (s.w.lo && (rc = tr_curve_want_lo(cv, err)))
        goto done;
    memcpy(cv->x, s.w.x, 3 * s.nv * sizeof *y);
    if (s.w.lo)
        memcpy(cv->lo, s.w.lo, 3 * s.nv * sizeof *s.w.lo);
    st->accepted = 1;
    st->ropelength_after = rl;
done:
    st->seconds = tr_clock_seconds() - t0;
    st->t_rows = s.t_rows;
    st->t_value = s.t_value;
    free(y);
    free(ylo);
    solver_free(&s);
    return rc;
}

int tr_newton_restore(tr_curve *cv, const tr_newton_params *prm, double *before, double *after, tr_error *err)
{
    tr_newton_params p;
    if (prm)
        p = *prm;
    else
        tr_newton_params_default(&p);
    /* the rows as they stand: no multipliers to start with */
    p.warm_start = 0;
    if (p.vertex_contacts) {
        p.backend = NULL; /* a backend's strut rows are segment rows */
        for (int k = 0; k < cv->ncomp; k++)
            if (!cv->closed[k])
                return tr_fail(err, TR_EINVAL, "restore: the vertex contact model takes closed components only");
    }
    *before = *after = NAN;
    if (has_constrained_vertex(cv))
        return tr_fail(err, TR_EINVAL, "restore: a curve with constrained vertices keeps its planes (not restored)");
    tr_thickness th0;
    int rc = tr_newton_i_model_thickness(&p, cv, NULL, &th0, err);
    if (rc)
        return rc;
    if (!(th0.thickness > 0) || !isfinite(th0.thickness))
        return tr_fail(err, TR_EGEOMETRY, "restore: the curve has no finite positive thickness");
    solver s;
    memset(&s, 0, sizeof s);
    s.p = &p;
    double *y = NULL, *ylo = NULL;
    tr_newton_stats st;
    memset(&st, 0, sizeof st);
    if ((rc = prepare(&s, cv, 1.0, &y, &st, err)))
        goto done;
    s.max_bend = INFINITY;
    tr_newton_i_al_eval(&s, y, NULL, 0);
    *before = s.viol;
    double after_edge;
    if ((rc = ensure_best(&s, err)) || (rc = tr_newton_i_restore(&s, y, INFINITY, after, &after_edge, err)))
        goto done;
    tr_thickness th;
    double rl;
    if ((rc = measure_iterate(&s, y, &rl, &th, err)) ||
        (rc = extended_end(&s, y, NULL, rl, INFINITY, &ylo, &rl, &th, err)))
        goto done;
    if (ylo) {
        tr_newton_i_al_eval_lo(&s, y, ylo, NULL, 0);
        *after = s.viol;
    }
    /* kept where the oracle measures it shorter than the curve rescaled */
    if (rl < th0.ropelength) {
        tr_curve_drop_lo(cv);
        if (ylo && (rc = tr_curve_want_lo(cv, err)))
            goto done;
        memcpy(cv->x, y, 3 * s.nv * sizeof *y);
        if (ylo)
            memcpy(cv->lo, ylo, 3 * s.nv * sizeof *ylo);
        tr_curve_scale_by(cv, 1.0 / th.thickness);
    }
done:
    free(y);
    free(ylo);
    solver_free(&s);
    return rc;
}

