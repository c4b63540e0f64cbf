/* This file contains the restoration: a nearly feasible iterate moved onto
 * its rows by a small correction, so that the oracle measures it without
 * the rescaling a violation costs.
 *
 * Why: the oracle's ropelength of a curve is its length over its thickness,
 * so an iterate whose worst MinRad row is 1e-7 over is charged 1e-7 of its
 * whole length (3.3e-6 on the trefoil), while the rows that are over are a
 * few, each held by a multiplier of the size of the tension a vertex
 * carries: moving those few vertices back costs about sum lambda_i |g_i|.
 * The end game of a large solve (N >= 76 800) spends hundreds of steps with
 * violations of 1e-7 to 1e-4 while its length is already below where the
 * rescaled iterate lands (bench/notes/2026-11-27-restoration.md).
 *
 * The correction is the proximal penalty projection
 *   min rho / 2 |y - y0|^2 + mu_r / 2 sum_rows min(0, g)^2 (edges: h^2),
 * the rows and their derivatives being the solver's own (al_eval with all
 * multipliers 0 and no length term), solved by the solver's Newton
 * direction (its Levenberg shift is the rho I) with an Armijo search. It is
 * strictly convex near y0 wherever the rows are smooth, its set of
 * violated rows changes finitely often (semismooth Newton: a few steps),
 * and at its solution a row is left over by rho |delta| / (mu_r |grad g|^2)
 * only, 1e-8 of the correction. Tried first, not kept: the minimal-norm
 * Gauss-Newton correction of the violated rows alone bent the neighbours
 * of a corrected strut past MinRad, and holding every near row as an
 * equality made the system overdetermined (3.3 rows per vertex against 3
 * coordinates) and the corrections diverge (at N = 2400, both). */
#include "solver/newton_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/clock.h"

/* Newton steps at most */
#define RESTORE_STEPS 12
/* the penalty's weight, in units of 1 / l0 (the tension's stiffness), against
 * the proximal weight rho = 1 / l0: rows 1e8 times stiffer than the
 * correction's cost */
#define RESTORE_PENALTY 1e8
/* The rows within this share of the solver's first band (newton_rows.c,
 * NEAR_ACTIVE) enter the matrix unviolated, so that the correction of a
 * row that is over does not push its neighbours over unseen (MinRad's rows
 * are in units of edge^2: without them a 7e-6 move took MinRad's violation
 * from 1e-5 to 0.09 at N = 2400). Narrow: such a row is a spring in the
 * model that the function does not have, so each step corrects only part
 * of the violation (the whole band: half, and the nudged 64-gon of
 * tests/solver/test_restore.c ended 6e-7 above its closed form after 12
 * steps; at 0.01 3e-11). */
#define RESTORE_BAND 0.01
/* done: the violation is at this share of the start's (or at viol_tol) */
#define RESTORE_SHARE 1e-6

typedef struct {
    double mu, band, guard, viol, dmin, length, vk[3];
    size_t worst_m, active;
} saved_state;

void tr_newton_i_add_step(size_t n3, size_t n, const double *y, const double *ylo, double alpha, const double *dir,
                          double *yt, double *ytlo)
{
    for (size_t i = 0; i < n; i++) {
        double a = alpha * dir[i];
        if (!ylo || i >= n3) {
            yt[i] = y[i] + a;
            continue;
        }
        double t = y[i] + a, bb = t - y[i], e = (y[i] - (t - bb)) + (a - bb), lo = ylo[i] + e;
        yt[i] = t + lo;
        ytlo[i] = lo - (yt[i] - t);
    }
}

int tr_newton_i_restore(solver *s, double *y, double deadline, double *viol, double *viol_edge, tr_error *err)
{
    return tr_newton_i_restore_lo(s, y, NULL, deadline, viol, viol_edge, err);
}

int tr_newton_i_restore_lo(solver *s, double *y, double *ylo, double deadline, double *viol, double *viol_edge,
                           tr_error *err)
{
    size_t nv = s->nv, n = s->n;
    *viol = s->viol;
    *viol_edge = s->viol_kind[0];
    saved_state sv = {s->mu, s->band, s->guard, s->viol, s->dmin, s->length, {s->viol_kind[0], s->viol_kind[1],
                      s->viol_kind[2]}, s->worst_m, s->active};
    /* the multipliers and their estimates, which the passes go on with */
    size_t nsave = 4 * nv + 2 * s->nsp;
    double *keep = malloc(nsave * sizeof *keep), *y0 = malloc(n * sizeof *y0), *grad = malloc(n * sizeof *grad),
           *dir = malloc(n * sizeof *dir), *yt = malloc(n * sizeof *yt);
    double *y0lo = ylo ? malloc(3 * nv * sizeof *y0lo) : NULL, *ytlo = ylo ? malloc(3 * nv * sizeof *ytlo) : NULL;
    int rc = TR_OK, kept = 0; /* kept: keep holds the multipliers */
    if (!keep || !y0 || !grad || !dir || !yt || (ylo && (!y0lo || !ytlo))) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (restoration)");
        goto done;
    }
    memcpy(keep, s->lam_e, nv * sizeof *keep);
    memcpy(keep + nv, s->lam_m, nv * sizeof *keep);
    memcpy(keep + 2 * nv, s->pi_e, nv * sizeof *keep);
    memcpy(keep + 3 * nv, s->pi_m, nv * sizeof *keep);
    for (size_t r = 0; r < s->nsp; r++) {
        keep[4 * nv + 2 * r] = s->sp[r].lam;
        keep[4 * nv + 2 * r + 1] = s->pi_s[r];
        s->sp[r].lam = 0.0;
    }
    kept = 1;
    memset(s->lam_e, 0, nv * sizeof *s->lam_e);
    memset(s->lam_m, 0, nv * sizeof *s->lam_m);
    s->mu = RESTORE_PENALTY / s->l0min;
    s->guard = 0.0;
    /* no row near its bound enters the matrix without being over */
    s->band = RESTORE_BAND;
    double rho = 1.0 / s->l0min;
    memcpy(y0, y, n * sizeof *y);
    if (ylo)
        memcpy(y0lo, ylo, 3 * nv * sizeof *ylo);
    tr_newton_stats st;
    memset(&st, 0, sizeof st);
    double v0 = INFINITY;
    for (int step = 0; step < RESTORE_STEPS; step++) {
        if (tr_clock_seconds() > deadline || (s->p->stop && *s->p->stop))
            break;
        double f = tr_newton_i_al_eval_lo(s, y, ylo, grad, 1), prox = 0.0;
        if (s->oom) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory (restoration)");
            goto done;
        }
        if (s->dev_rc) {
            *err = s->dev_err;
            rc = s->dev_rc;
            goto done;
        }
        if (step == 0)
            v0 = s->viol;
        *viol = s->viol;
        *viol_edge = s->viol_kind[0];
        if (s->viol <= RESTORE_SHARE * v0 || s->viol <= s->p->viol_tol)
            break;
        /* al_eval's gradient has the length's in it: not this objective's */
        for (int k = 0; k < s->nc; k++)
            grad[3 * nv + (size_t)k] -= (double)s->ne[k];
        for (size_t i = 0; i < n; i++) {
            double d = y[i] - y0[i] + (ylo && i < 3 * nv ? ylo[i] - y0lo[i] : 0.0);
            grad[i] += rho * d;
            prox += 0.5 * rho * d * d;
        }
        for (int k = 0; k < s->nfixed; k++)
            grad[s->fixed[k]] = 0.0;
        double lm = rho;
        if ((rc = tr_newton_i_dir(s, grad, dir, &lm, &st, err)))
            goto done;
        double slope = 0.0;
        for (size_t i = 0; i < n; i++)
            slope += grad[i] * dir[i];
        if (!(slope < 0.0))
            break;
        int ok = 0;
        for (double alpha = 1.0; alpha > 1e-6 && !ok; alpha *= 0.5) {
            double pt = 0.0;
            tr_newton_i_add_step(3 * nv, n, y, ylo, alpha, dir, yt, ytlo);
            for (size_t i = 0; i < n; i++) {
                double d = yt[i] - y0[i] + (ylo && i < 3 * nv ? ytlo[i] - y0lo[i] : 0.0);
                pt += 0.5 * rho * d * d;
            }
            double ft = tr_newton_i_al_eval_lo(s, yt, ytlo, NULL, 0);
            if ((ft + pt) - (f + prox) <= 1e-4 * alpha * slope)
                ok = 1;
        }
        if (!ok)
            break;
        memcpy(y, yt, n * sizeof *y);
        if (ylo)
            memcpy(ylo, ytlo, 3 * nv * sizeof *ylo);
    }
    tr_newton_i_al_eval_lo(s, y, ylo, NULL, 0);
    *viol = s->viol;
    *viol_edge = s->viol_kind[0];
done:
    if (kept) {
        memcpy(s->lam_e, keep, nv * sizeof *keep);
        memcpy(s->lam_m, keep + nv, nv * sizeof *keep);
        memcpy(s->pi_e, keep + 2 * nv, nv * sizeof *keep);
        memcpy(s->pi_m, keep + 3 * nv, nv * sizeof *keep);
        for (size_t r = 0; r < s->nsp; r++) {
            s->sp[r].lam = keep[4 * nv + 2 * r];
            s->pi_s[r] = keep[4 * nv + 2 * r + 1];
        }
    }
    s->mu = sv.mu;
    s->band = sv.band;
    s->guard = sv.guard;
    s->viol = sv.viol;
    s->dmin = sv.dmin;
    s->length = sv.length;
    memcpy(s->viol_kind, sv.vk, sizeof sv.vk);
    s->worst_m = sv.worst_m;
    s->active = sv.active;
    free(keep);
    free(y0);
    free(grad);
    free(dir);
    free(yt);
    free(y0lo);
    free(ytlo);
    return rc;
}
