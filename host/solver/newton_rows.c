/* This file contains the rows of the augmented Lagrangian (edges, MinRad, struts): its value, gradient and Hessian. */
#include "solver/newton_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/clock.h"
#include "util/vec3.h"

/* c(l) = 4 l^4 / (4 + l^2) and its first two derivatives in l */
static void minrad_c(double l, double *c, double *dc, double *d2c)
{
    double u = l * l, q = 4.0 + u;
    double dcdu = (32.0 * u + 4.0 * u * u) / (q * q);
    *c = 4.0 * u * u / q;
    *dc = dcdu * 2.0 * l;
    *d2c = 128.0 / (q * q * q) * 4.0 * u + 2.0 * dcdu;
}

/* The MinRad row's pieces at vertex i: w = x_{i+1} - 2 x_i + x_{i-1} and
 * c(l_k) with its derivatives; 0 at an end of an open rope (no row). */
int tr_newton_i_minrad_row(const solver *s, const double *x, const double *l, size_t i, double w[3],
                           double *c, double *dc, double *d2c)
{
    return tr_newton_i_minrad_row_lo(s, x, NULL, l, i, w, c, dc, d2c);
}

int tr_newton_i_minrad_row_lo(const solver *s, const double *x, const double *xlo, const double *l, size_t i,
                              double w[3], double *c, double *dc, double *d2c)
{
    size_t ip = s->prev[i], in = s->next[i];
    if (ip == NONE || in == NONE)
        return 0;
    minrad_c(l[s->comp[i]], c, dc, d2c);
    /* as the difference of the two edges: each edge is exact where its
     * end points' coordinates are within a factor 2 of each other
     * (Sterbenz), so w carries rounding of eps l0 only, where
     * x_{i+1} - 2 x_i + x_{i-1} carried eps R from its first sum, the
     * same size as the coordinates' own rounding and of the row's noise
     * floor (newton.c, viol_tol) */
    for (int d = 0; d < 3; d++) {
        w[d] = (x[3 * in + d] - x[3 * i + d]) - (x[3 * i + d] - x[3 * ip + d]);
        if (xlo)
            w[d] += (xlo[3 * in + d] - xlo[3 * i + d]) - (xlo[3 * i + d] - xlo[3 * ip + d]);
    }
    return 1;
}

/* Appends v at (i, j) of the Hessian's upper triangle (the triplets grow
 * by doubling; s->oom when they cannot) */
void tr_newton_i_tri_push(solver *s, size_t i, size_t j, double v)
{
    if (s->nz == s->capz) {
        size_t nc = s->capz ? 2 * s->capz : 1 << 16;
        SuiteSparse_long *ti = realloc(s->ti, nc * sizeof *ti), *tj = ti ? realloc(s->tj, nc * sizeof *tj) : NULL;
        if (ti)
            s->ti = ti;
        if (tj)
            s->tj = tj;
        double *tx = tj ? realloc(s->tx, nc * sizeof *tx) : NULL;
        if (!tx) {
            s->oom = 1;
            return;
        }
        s->tx = tx;
        s->capz = nc;
    }
    if (i > j) {
        size_t k = i;
        i = j;
        j = k;
    }
    s->ti[s->nz] = (SuiteSparse_long)i;
    s->tj[s->nz] = (SuiteSparse_long)j;
    s->tx[s->nz] = v;
    s->nz++;
}

/* Adds cg gr gr^T + cH H (H m x m row major, or NULL) over the variables idx
 * (distinct), and -pi gr to the gradient. */
static void row_terms(solver *s, int m, const size_t *idx, const double *gr, const double *H, double cg,
                      double cH, double pi, double *grad, int hess)
{
    double gq[16], Hq[256];
    if (tr_newton_i_project_row(s, m, idx, gr, hess ? H : NULL, gq, Hq)) {
        gr = gq;
        H = hess && H ? Hq : NULL;
    }
    for (int a = 0; a < m; a++)
        grad[idx[a]] -= pi * gr[a];
    if (!hess)
        return;
    int held[16];
    for (int a = 0; a < m; a++)
        held[a] = idx[a] < 3 * s->nv && tr_newton_i_is_fixed(s, idx[a]);
    for (int a = 0; a < m; a++)
        for (int b = a; b < m; b++) {
            if (held[a] || held[b])
                continue;
            double v = cg * gr[a] * gr[b] + (H ? cH * H[a * m + b] : 0.0);
            if (v != 0.0)
                tr_newton_i_tri_push(s, idx[a], idx[b], v);
        }
}

/* Rows within this (relative) of their bound enter the Newton matrix with
 * their penalty term mu grad g grad g^T even while inactive (pi = 0): a
 * convex addition, so the step is still a descent direction, and it keeps
 * the first steps from a cold start (multipliers 0) from shrinking the rope
 * straight through its contacts, along the scaling mode that nothing else
 * stiffens while no row is active. The band narrows as mu grows (width
 * NEAR_ACTIVE mu0 / mu): the true L_A is flat along an inactive row, and
 * a spring of stiffness mu on every row within 1e-6 of its bound froze the
 * rows that had yet to close, so the solver settled 1.2e-6 above the
 * converged ropelength at N = 9600
 * (bench/notes/2026-11-25-converged-last-digits.md); at mu0 the band is as before. */
#define NEAR_ACTIVE 1e-6

/* The MinRad guard (s->guard > 0, where bends are taken back: newton.c).
 * An inactive MinRad row is not in the Newton matrix, yet it is quadratic in
 * a second difference w of size l0^2 kappa, so a step's vertex-scale
 * wiggles of a few l0^2 (1.8e-7 at N = 76 800), which the tension hardly
 * resists, bend a vertex at kappa 0.95 past 1; the bends were taken back in
 * 94 % of the first 50 steps at N = 38 400
 * (bench/notes/2026-11-27-n76800-end-game.md). So the
 * matrix sees each inactive row with 0 < g < g_s (g_s = l0^4 / S, the row
 * at kappa = 0) as the barrier -nu log g would: nu / g^2 grad g grad g^T -
 * nu / g hess g (positive semidefinite over the vertices, g being concave
 * in x; along the edge length l_k, where c(l) is convex, it can be
 * indefinite by O(lambda_bar), against the edges' n_k mu there), with nu = eta
 * lambda_bar g_s, lambda_bar the mean multiplier of the active MinRad rows.
 * The barrier's force nu / g would then equal an active row's at g = eta
 * g_s, so a row within eta of its bound is held by the model about as
 * firmly as an active one; below that g is taken as eta g_s (a row at
 * rounding from its bound would otherwise make the matrix singular). The
 * value and the gradient are L_A's own: the guard changes the path (a
 * change of the matrix that keeps it positive definite keeps the direction
 * one of descent, and the Levenberg shift stands behind that), not the
 * solution. eta = guard * band falls with the band as mu
 * grows, so the end game is Newton's on L_A again (at a fixed eta the
 * N = 38 400 trefoil settled 2e-7 long in 186 steps). Measured at N = 38 400
 * from the converged 19 200: 178 steps and 32.7429351298, against 263-310
 * and 32.7429351323-1406 without (bench/notes/2026-11-27-minrad-guard.md). */
static double minrad_guard_lambda(const solver *s)
{
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < s->nv; i++)
        if (s->lam_m[i] > 0.0) {
            sum += s->lam_m[i];
            n++;
        }
    return n ? sum / (double)n : 0.0;
}

/* The PHR term of an inequality row g >= 0: value; *pi = max(0, lam - mu g) */
static double ineq_term(double g, double lam, double mu, double *pi)
{
    if (lam - mu * g > 0.0) {
        *pi = lam - mu * g;
        return -lam * g + 0.5 * mu * g * g;
    }
    *pi = 0.0;
    return -lam * lam / (2.0 * mu);
}

/* L_A at y less its length term sum_k n_k l_k; with grad != NULL also the
 * gradient of the whole L_A, the multiplier estimates pi and (hess) the
 * Hessian's triplets. Sets viol, dmin, length, active. */
double tr_newton_i_al_eval(solver *s, const double *y, double *grad, int hess)
{
    return tr_newton_i_al_eval_lo(s, y, NULL, grad, hess);
}

double tr_newton_i_al_eval_lo(solver *s, const double *y, const double *ylo, double *grad, int hess)
{
    size_t nv = s->nv;
    const double *x = y, *l = y + 3 * nv;
    size_t wm = 0;
    double mu = s->mu, f = 0.0, ve = 0.0, vm = 0.0, vs = 0.0, dmin = INFINITY, len = 0.0;
    double tv = tr_clock_seconds();
    if (grad)
        memset(grad, 0, s->n * sizeof *grad);
    if (hess)
        s->nz = 0;
    /* the length sum_k n_k l_k is left out of the value (its gradient is
     * in): the line search adds its change from the change in l_k, exact,
     * where the difference of two sums of size 32.7 carries a rounding of
     * 7e-15 that hid the last decreases (minimise) */
    for (int k = 0; k < s->nc; k++)
        if (grad)
            grad[3 * nv + (size_t)k] += (double)s->ne[k];
    /* edges */
    for (size_t a = 0; a < nv; a++) {
        size_t b = s->next[a];
        if (b == NONE)
            continue;
        int k = s->comp[a];
        double u[3];
        v3_sub(u, x + 3 * b, x + 3 * a);
        for (int d = 0; ylo && d < 3; d++)
            u[d] += ylo[3 * b + (size_t)d] - ylo[3 * a + (size_t)d];
        double el = v3_norm(u);
        len += el;
        double h = el - l[k];
        double pi = s->lam_e[a] - mu * h;
        f += -s->lam_e[a] * h + 0.5 * mu * h * h;
        ve = fmax(ve, fabs(h) / s->l0[k]);
        if (!grad)
            continue;
        s->pi_e[a] = pi;
        for (int d = 0; d < 3; d++)
            u[d] /= el;
        size_t idx[7] = {3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2, 3 * nv + (size_t)k};
        double gr[7] = {-u[0], -u[1], -u[2], u[0], u[1], u[2], -1.0};
        double H[49];
        memset(H, 0, sizeof H);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) {
                double P = ((r == c) - u[r] * u[c]) / el;
                H[r * 7 + c] = H[(r + 3) * 7 + c + 3] = P;
                H[r * 7 + c + 3] = H[(r + 3) * 7 + c] = -P;
            }
        row_terms(s, 7, idx, gr, H, mu, -pi, pi, grad, hess);
    }
    /* MinRad */
    double eta = s->guard * s->band, lam_bar = hess && eta > 0.0 ? minrad_guard_lambda(s) : 0.0;
    for (size_t i = 0; i < nv; i++) {
        double c, dc, d2c, w[3];
        if (!tr_newton_i_minrad_row_lo(s, x, ylo, l, i, w, &c, &dc, &d2c))
            continue;
        size_t ip = s->prev[i], in = s->next[i];
        int k = s->comp[i];
        double w2 = v3_dot(w, w), S = s->scale_m[k];
        double g = (c - w2) / S, pi;
        f += ineq_term(g, s->lam_m[i], mu, &pi);
        double over = 0.5 * (w2 / c - 1.0);
        if (over > vm) {
            vm = over;
            wm = i;
        }
        if (!grad)
            continue;
        s->pi_m[i] = pi;
        int near = hess && g < s->band * NEAR_ACTIVE * s->l0[k] * s->l0[k];
        double guard_cg = 0.0, guard_cH = 0.0;
        if (pi == 0.0 && lam_bar > 0.0 && g > 0.0) {
            double l02 = s->l0[k] * s->l0[k], gs = l02 * l02 / S;
            if (g < gs) {
                double nu = eta * lam_bar * gs, ge = fmax(g, eta * gs);
                guard_cg = nu / (ge * ge);
                guard_cH = -nu / ge;
            }
        }
        if (pi == 0.0 && !near && guard_cg == 0.0)
            continue;
        static const double v[3] = {1.0, -2.0, 1.0};
        size_t vx[3] = {ip, i, in};
        size_t idx[10];
        double gr[10], H[100];
        memset(H, 0, sizeof H);
        for (int j = 0; j < 3; j++)
            for (int d = 0; d < 3; d++) {
                idx[3 * j + d] = 3 * vx[j] + (size_t)d;
                gr[3 * j + d] = -2.0 * v[j] * w[d] / S;
                for (int j2 = 0; j2 < 3; j2++)
                    H[(3 * j + d) * 10 + 3 * j2 + d] = -2.0 * v[j] * v[j2] / S;
            }
        idx[9] = 3 * nv + (size_t)k;
        gr[9] = dc / S;
        H[99] = d2c / S;
        /* a row within the band keeps its penalty term as well */
        row_terms(s, 10, idx, gr, H, (near || pi > 0.0 ? mu : 0.0) + guard_cg, -pi + guard_cH, pi, grad, hess);
    }
    /* struts */
    size_t active = 0;
    double tr = tr_clock_seconds();
    tr_strut_rows dev;
    int on_dev = s->p->backend && !s->dev_rc;
    if (on_dev) {
        int mode = !grad ? TR_ROWS_VALUE : hess ? TR_ROWS_HESS : TR_ROWS_GRAD;
        s->dev_rc = tr_solver_rows_eval(s->p->backend, &s->rows, x, nv, s->sp, s->nsp, s->next, mu, mode,
                                        hess ? s->band * NEAR_ACTIVE : -INFINITY, f, &dev, &s->dev_err);
        on_dev = !s->dev_rc;
        if (grad)
            s->t_rows += tr_clock_seconds() - tr;
    }
    /* the value as the backend sums it, here and at the line search's
     * points alike (backend.h); without the gradient also the closest pair
     * and so the worst strut violation (the largest 0.5 (2 - d) is at the
     * smallest d) */
    if (on_dev)
        f = dev.sum;
    if (on_dev && !grad) {
        dmin = fmin(dmin, dev.dmin);
        vs = fmax(vs, 0.5 * (2.0 - dev.dmin));
    }
    for (size_t r = 0; r < s->nsp && !(on_dev && !grad); r++) {
        size_t a = s->sp[r].a, b = s->sp[r].b;
        double d = on_dev ? dev.d[r] : tr_newton_i_pair_distance(s, x, a, b);
        dmin = fmin(dmin, d);
        double pi, term = ineq_term(d - 2.0, s->sp[r].lam, mu, &pi);
        if (!on_dev)
            f += term;
        vs = fmax(vs, 0.5 * (2.0 - d));
        if (!grad)
            continue;
        s->pi_s[r] = pi;
        if (pi == 0.0 && !(hess && d - 2.0 < s->band * NEAR_ACTIVE))
            continue;
        active += pi > 0.0;
        double gr[12], H[144], dd;
        const double *pg = gr, *pH = H;
        size_t idx[12];
        int m;
        /* the backend's block, or (not selected there: its rounding put
         * the row on the other side of the test) this one */
        if (on_dev && dev.sel[r] >= 0) {
            m = tr_newton_i_strut_index(s, a, b, idx);
            pg = dev.g + 12 * (size_t)dev.sel[r];
            pH = hess ? dev.h + 144 * (size_t)dev.sel[r] : NULL;
        } else
            m = tr_newton_i_strut_derivs(s, x, a, b, &dd, gr, hess ? H : NULL, idx);
        row_terms(s, m, idx, pg, hess ? pH : NULL, mu, -pi, pi, grad, hess);
    }
    if (!grad)
        s->t_value += tr_clock_seconds() - tv;
    if (grad)
        for (int k = 0; k < s->nfixed; k++)
            grad[s->fixed[k]] = 0.0;
    /* a constrained vertex's forbidden motions: I - P_i on its diagonal
     * block (the rows above have none there), so dir_i has none of them */
    for (size_t q = 0; hess && q < s->ncv; q++) {
        double P[9];
        tr_newton_i_allowed_projector(tr_newton_i_vertex_cst(s, s->cv[q]), P);
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++) {
                double v = (r == c) - P[3 * r + c];
                if (v != 0.0)
                    tr_newton_i_tri_push(s, 3 * s->cv[q] + (size_t)r, 3 * s->cv[q] + (size_t)c, v);
            }
    }
    s->viol = fmax(ve, fmax(vm, vs));
    s->viol_kind[0] = ve;
    s->viol_kind[1] = vm;
    s->viol_kind[2] = vs;
    s->worst_m = wm;
    s->dmin = dmin;
    s->length = len;
    if (grad)
        s->active = active;
    return f;
}
