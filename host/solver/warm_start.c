/* This file contains the warm start: the first multipliers, and how much of the tension they leave unbalanced. */
#include "solver/newton_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/vec3.h"

/* The multipliers that best balance the tension at y: with every edge's
 * multiplier at -1 (unit tension), least squares min |t - J^T lambda| over
 * the inequality rows within the warm band of their bound (relative), t the
 * tension's force sum grad |e|, by conjugate gradients on the normal
 * equations J J^T lambda = J t (products with J and J^T only: J J^T itself
 * fills in where many struts share vertices), then clipped at 0. A refined
 * or polished start has its contacts and MinRad stretches in place; with
 * multipliers that already hold the tension, the first passes do not let
 * the rope shrink through them while the multipliers build up. The
 * tension they leave unbalanced, or the damped least squares' if less
 * (damped_multipliers), is warm_residual: whether the start is tight. */
#define WARM_BAND 1e-4
/* A knot converged at edge L and spline-refined to edge l leaves its
 * contacts up to the spline's sag between the coarse vertices apart,
 * ~L^2 / 8 at curvature 1: 8e-4 of the thickness for the N = 400 trefoil
 * refined to 2400, where a band of 1e-4 kept too few rows to hold the
 * tension (warm residual 1.0: read as loose, and the loose road ended at
 * 34.27 in 4688 steps), while with 5e-4 the solve took 247 steps, 9.5 s, to
 * 32.7430932 (the converged N = 2400 value is 32.7430930). So a start
 * that the band WARM_BAND reads as loose is tried again with the band
 * WARM_BAND_SAG l^2 (a refinement by up to ~6 at l; at N >= 9600 this is
 * under WARM_BAND), capped at WARM_BAND_MAX so that a loose coarse
 * start's rows do not count as contacts (tr_newton_i_warm_multipliers). */
#define WARM_BAND_SAG 10.0
#define WARM_BAND_MAX 2e-3

/* out = J^T v (nx entries) for J stored by rows (rowp, col, val), nr rows */
static void rows_transpose_times(const size_t *rowp, const size_t *col, const double *val, size_t nr,
                                 const double *v, size_t nx, double *out)
{
    memset(out, 0, nx * sizeof *out);
    for (size_t i = 0; i < nr; i++)
        for (size_t k = rowp[i]; k < rowp[i + 1]; k++)
            out[col[k]] += val[k] * v[i];
}

/* |t - w|^2: the tension the multipliers' forces w leave unbalanced */
static double unbalanced2(const double *t, const double *w, size_t nx)
{
    double r = 0.0;
    for (size_t k = 0; k < nx; k++)
        r += (t[k] - w[k]) * (t[k] - w[k]);
    return r;
}

/* out = J v for J stored by rows (rowp, col, val), nr rows */
static void rows_times(const size_t *rowp, const size_t *col, const double *val, size_t nr, const double *v,
                       double *out)
{
    for (size_t i = 0; i < nr; i++) {
        double a = 0.0;
        for (size_t k = rowp[i]; k < rowp[i + 1]; k++)
            a += val[k] * v[col[k]];
        out[i] = a;
    }
}
/* The second opinion on how tight the start is. The conjugate gradients'
 * clipped residual grows with N on the same tight shape (the N = 2400
 * trefoil spline-refined: 0.30 at 9600, 0.58 at 19 200, 0.99 at 38 400,
 * which read as loose and sent 38 400 down the loose road: at the
 * thickness scale its struts fell out of the list and the rope shrank
 * through itself): J J^T is a chain's matrix, its condition grows like N^2,
 * and 500 steps resolve less of it as N grows.
 *
 * Here lam = argmin |t - J^T lam|^2 + delta |lam|^2, solved through the
 * columns' side: lam = J (J^T J + delta I)^-1 t. J^T J is nx x nx with the
 * strut Hessian's pattern (a factor like one Newton step's), where J J^T,
 * rows sharing vertices, fills in many times over (3.7 GB and 45 s at
 * N = 9600). The damping matters: there are more rows than coordinates
 * (11 per vertex at N = 9600), so undamped least squares balance any
 * tension with multipliers that pull as hard as they push, and clipped they
 * left 3.5 to 37 times the tension unbalanced. Over delta = 1e-12 ... 3e-2
 * of J^T J's largest diagonal the clipped residual was least at 1e-3, and
 * there flat in N: 0.079, 0.086 and 0.116 at 9600, 19 200 and 38 400, 0.069
 * on a converged N = 2600 trefoil; the spline-refined N = 400 trefoil at
 * 800 (a start the solver cannot take as tight) stays at 1.06. The
 * multipliers the solve starts with stay the conjugate gradients': from
 * these the N = 9600 solve took 255 steps against 225 to the same length,
 * and at 38 400 it went no faster. */
#define WARM_DAMPING 1e-3
#define WARM_ITERS 500
static int damped_multipliers(solver *s, const size_t *rowp, const size_t *col, const double *val, size_t nr,
                              size_t nx, const double *t, double *lam, tr_error *err)
{
    cholmod_common *cm = &s->cm;
    size_t nz = rowp[nr];
    /* J^T in compressed columns is J by rows: column i of J^T is row i */
    cholmod_sparse *Jt = cholmod_l_allocate_sparse(nx, nr, nz, 0, 1, 0, CHOLMOD_REAL, cm);
    cholmod_factor *L = NULL;
    cholmod_dense *b = NULL, *x = NULL;
    int rc = TR_OK;
    if (!Jt) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (warm start)");
        goto done;
    }
    SuiteSparse_long *cp = Jt->p, *ri = Jt->i;
    double *vx = Jt->x;
    for (size_t i = 0; i <= nr; i++)
        cp[i] = (SuiteSparse_long)rowp[i];
    for (size_t k = 0; k < nz; k++) {
        ri[k] = (SuiteSparse_long)col[k];
        vx[k] = val[k];
    }
    /* the largest diagonal of J^T J */
    double dmax = 0.0, *diag = calloc(nx, sizeof *diag);
    if (!diag) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (warm start)");
        goto done;
    }
    for (size_t k = 0; k < nz; k++)
        diag[col[k]] += val[k] * val[k];
    for (size_t k = 0; k < nx; k++)
        dmax = fmax(dmax, diag[k]);
    free(diag);
    /* CHOLMOD factors A A^T + beta I of an unsymmetric A: here J^T J */
    L = cholmod_l_analyze(Jt, cm);
    double beta[2] = {WARM_DAMPING * dmax, 0.0};
    b = cholmod_l_allocate_dense(nx, 1, nx, CHOLMOD_REAL, cm);
    if (!L || !b) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (warm start)");
        goto done;
    }
    memcpy(b->x, t, nx * sizeof *t);
    if (!cholmod_l_factorize_p(Jt, beta, NULL, 0, L, cm) || cm->status != CHOLMOD_OK) {
        rc = tr_fail(err, cm->status == CHOLMOD_OUT_OF_MEMORY ? TR_ENOMEM : TR_EGEOMETRY,
                     "CHOLMOD could not factor the warm start's normal equations (status %d)", cm->status);
        goto done;
    }
    x = cholmod_l_solve(CHOLMOD_A, L, b, cm);
    if (!x) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (warm start)");
        goto done;
    }
    rows_times(rowp, col, val, nr, x->x, lam);
done:
    cholmod_l_free_dense(&x, cm);
    cholmod_l_free_dense(&b, cm);
    cholmod_l_free_factor(&L, cm);
    cholmod_l_free_sparse(&Jt, cm);
    return rc;
}

/* The warm start at y with the rows within band of their bound, as this
 * file's first comment says: J by rows over those rows, the conjugate
 * gradients, the clipped residual and the damped least squares' second
 * bound on it. */
static int warm_multipliers_band(solver *s, const double *y, double band, tr_error *err)
{
    size_t nv = s->nv, nx = 3 * nv;
    const double *x = y, *l = y + nx;
    size_t cap = nv + s->nsp;
    /* J row by row: up to 12 entries each */
    size_t *col = malloc(12 * (cap + 1) * sizeof *col), *rowp = malloc((cap + 2) * sizeof *rowp);
    size_t *row_of = malloc((cap + 1) * sizeof *row_of);
    double *val = malloc(12 * (cap + 1) * sizeof *val);
    double *t = calloc(nx, sizeof *t), *w = malloc(nx * sizeof *w);
    double *lam = NULL, *r = NULL, *pd = NULL, *q = NULL;
    int rc = TR_OK;
    if (!col || !rowp || !row_of || !val || !t || !w) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (warm start)");
        goto done;
    }
    size_t nr = 0, nz = 0;
    rowp[0] = 0;
    for (size_t i = 0; i < cap; i++)
        row_of[i] = NONE;
    for (size_t i = 0; i < nv; i++) {
        double c, dc, d2c, wv[3];
        if (!tr_newton_i_minrad_row(s, x, l, i, wv, &c, &dc, &d2c))
            continue;
        size_t ip = s->prev[i], in = s->next[i];
        int k = s->comp[i];
        if ((c - v3_dot(wv, wv)) / c > band)
            continue;
        static const double v[3] = {1.0, -2.0, 1.0};
        size_t vx[3] = {ip, i, in};
        for (int j = 0; j < 3; j++)
            for (int d = 0; d < 3; d++) {
                col[nz] = 3 * vx[j] + (size_t)d;
                val[nz++] = -2.0 * v[j] * wv[d] / s->scale_m[k];
            }
        row_of[i] = nr;
        rowp[++nr] = nz;
    }
    for (size_t qq = 0; qq < s->nsp; qq++) {
        double gr[12], d;
        size_t idx[12];
        int m = tr_newton_i_strut_derivs(s, x, s->sp[qq].a, s->sp[qq].b, &d, gr, NULL, idx);
        if ((d - 2.0) / 2.0 > band)
            continue;
        for (int j = 0; j < m; j++) {
            col[nz] = idx[j];
            val[nz++] = gr[j];
        }
        row_of[nv + qq] = nr;
        rowp[++nr] = nz;
    }
    /* held coordinates take no part */
    for (size_t k = 0; k < nz; k++)
        if (tr_newton_i_is_fixed(s, col[k]))
            val[k] = 0.0;
    for (size_t a = 0; a < nv; a++) {
        size_t b2 = s->next[a];
        if (b2 == NONE)
            continue;
        double u[3];
        v3_sub(u, x + 3 * b2, x + 3 * a);
        double el = v3_norm(u);
        for (int d = 0; d < 3; d++) {
            t[3 * a + (size_t)d] -= u[d] / el;
            t[3 * b2 + (size_t)d] += u[d] / el;
        }
    }
    for (int k = 0; k < s->nfixed; k++)
        t[s->fixed[k]] = 0.0;
    /* a constrained vertex takes part with its allowed motions only (the
     * rows' entries come in triples, a vertex's x, y, z) */
    for (size_t k = 0; s->ncv > 0 && k + 2 < nz; k += 3)
        if (tr_newton_i_vertex_cst(s, col[k] / 3))
            tr_constraint_project_motion(tr_newton_i_vertex_cst(s, col[k] / 3), val + k);
    tr_newton_i_project_allowed(s, t);
    if (nr == 0)
        goto done;
    lam = calloc(nr, sizeof *lam);
    r = malloc(nr * sizeof *r);
    pd = malloc(nr * sizeof *pd);
    q = malloc(nr * sizeof *q);
    if (!lam || !r || !pd || !q) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (warm start)");
        goto done;
    }
    /* r = J t - J J^T lambda, lambda = 0 */
    double rr = 0.0;
    rows_times(rowp, col, val, nr, t, r);
    for (size_t i = 0; i < nr; i++) {
        pd[i] = r[i];
        rr += r[i] * r[i];
    }
    double rr0 = rr;
    for (int it = 0; it < WARM_ITERS && rr > 1e-20 * rr0 && !(s->p->stop && *s->p->stop); it++) {
        rows_transpose_times(rowp, col, val, nr, pd, nx, w);
        rows_times(rowp, col, val, nr, w, q);
        double pq = 0.0;
        for (size_t i = 0; i < nr; i++)
            pq += pd[i] * q[i];
        if (!(pq > 0.0))
            break;
        double al = rr / pq, rr1 = 0.0;
        for (size_t i = 0; i < nr; i++) {
            lam[i] += al * pd[i];
            r[i] -= al * q[i];
            rr1 += r[i] * r[i];
        }
        for (size_t i = 0; i < nr; i++)
            pd[i] = r[i] + rr1 / rr * pd[i];
        rr = rr1;
    }
    /* how much of the tension the clipped multipliers leave unbalanced */
    for (size_t i = 0; i < nr; i++)
        lam[i] = fmax(0.0, lam[i]);
    rows_transpose_times(rowp, col, val, nr, lam, nx, w);
    double tt = 0.0;
    for (size_t k = 0; k < nx; k++)
        tt += t[k] * t[k];
    double res = unbalanced2(t, w, nx);
    s->start_residual = tt > 0.0 ? sqrt(res / tt) : 0.0;
    /* the damped least squares' clipped multipliers: a second bound on the
     * tension nonnegative multipliers can hold */
    if (tt > 0.0) {
        double *lt = malloc(nr * sizeof *lt);
        if (!lt) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory (warm start)");
            goto done;
        }
        if ((rc = damped_multipliers(s, rowp, col, val, nr, nx, t, lt, err))) {
            free(lt);
            goto done;
        }
        for (size_t i = 0; i < nr; i++)
            lt[i] = fmax(0.0, lt[i]);
        rows_transpose_times(rowp, col, val, nr, lt, nx, w);
        res = fmin(res, unbalanced2(t, w, nx));
        free(lt);
    }
    s->warm_residual = tt > 0.0 ? sqrt(res / tt) : 0.0;
    for (size_t i = 0; i < nv; i++)
        s->lam_m[i] = row_of[i] != NONE ? fmax(0.0, lam[row_of[i]]) : 0.0;
    for (size_t qq = 0; qq < s->nsp; qq++)
        s->sp[qq].lam = row_of[nv + qq] != NONE ? fmax(0.0, lam[row_of[nv + qq]]) : 0.0;
done:
    free(col), free(rowp), free(row_of), free(val), free(t), free(w);
    free(lam), free(r), free(pd), free(q);
    return rc;
}

/* The band WARM_BAND first, the sag's (WARM_BAND_SAG l^2) only where that
 * reads the start as loose: with the sag's band always, rows up to 1.9e-3
 * from their bound took multipliers on the N = 2400 trefoil (no refined
 * start: its contacts are at 2 to 1e-9), and the solve settled 2.0e-7
 * higher in 316 steps instead of 235
 * (bench/notes/2026-11-25-time-per-step-vs-n.md). */
int tr_newton_i_warm_multipliers(solver *s, const double *y, tr_error *err)
{
    double sag = fmin(WARM_BAND_MAX, WARM_BAND_SAG * s->l0min * s->l0min);
    int rc = warm_multipliers_band(s, y, WARM_BAND, err);
    if (rc || s->warm_residual < TIGHT_RESIDUAL || !(sag > WARM_BAND) || (s->p->stop && *s->p->stop))
        return rc;
    return warm_multipliers_band(s, y, sag, err);
}
