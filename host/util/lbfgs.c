/* This file contains limited-memory BFGS with a per-step cap and a weak-Wolfe line search
 * (lbfgs.h). */
#include "util/lbfgs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void tr_lbfgs_params_default(tr_lbfgs_params *p)
{
    p->m = 10;
    p->max_iter = 1000;
    p->gtol = 1e-8;
    p->ftol = 0.0;
    p->max_move = INFINITY;
    p->group = 1;
    p->max_ls = 40;
}

static double dot(size_t n, const double *a, const double *b)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

static double max_abs(size_t n, const double *a)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(a[i]));
    return m;
}

/* Largest group norm of d. */
static double max_group(size_t n, int group, const double *d)
{
    double m = 0.0;
    for (size_t i = 0; i + (size_t)group <= n; i += (size_t)group) {
        double s = 0.0;
        for (int k = 0; k < group; k++)
            s += d[i + (size_t)k] * d[i + (size_t)k];
        m = fmax(m, s);
    }
    return sqrt(m);
}

int tr_lbfgs_minimize(size_t n, double *x, const tr_lbfgs_params *p, tr_lbfgs_fn fn, tr_lbfgs_iter_fn iter,
                      void *ctx, tr_lbfgs_result *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    int m = p->m > 0 ? p->m : 1, group = p->group > 0 ? p->group : 1;
    double *buf = malloc((size_t)(2 * m + 5) * n * sizeof *buf);
    double *rho = malloc((size_t)(2 * m) * sizeof *rho);
    if (!buf || !rho) {
        free(buf);
        free(rho);
        return tr_fail(err, TR_ENOMEM, "out of memory (l-bfgs, %zu variables)", n);
    }
    double *S = buf, *Y = S + (size_t)m * n, *g = Y + (size_t)m * n, *d = g + n, *xt = d + n, *gt = xt + n,
           *q = gt + n, *alpha = rho + m;
    int stored = 0, head = 0; /* ring buffer: newest pair at (head - 1) mod m */
    double f = fn(ctx, x, g);
    out->evals = 1;
    out->reason = TR_LBFGS_MAX_ITER;
    for (int it = 0; it < p->max_iter; it++) {
        if (max_abs(n, g) <= p->gtol) {
            out->reason = TR_LBFGS_GTOL;
            break;
        }
        /* two-loop recursion: d = -H g */
        memcpy(q, g, n * sizeof *q);
        for (int k = 0; k < stored; k++) {
            int j = (head - 1 - k + 2 * m) % m;
            alpha[j] = rho[j] * dot(n, S + (size_t)j * n, q);
            for (size_t i = 0; i < n; i++)
                q[i] -= alpha[j] * Y[(size_t)j * n + i];
        }
        double gamma = 1.0;
        if (stored) {
            int j = (head - 1 + m) % m;
            gamma = dot(n, S + (size_t)j * n, Y + (size_t)j * n) / dot(n, Y + (size_t)j * n, Y + (size_t)j * n);
        }
        for (size_t i = 0; i < n; i++)
            q[i] *= gamma;
        for (int k = stored - 1; k >= 0; k--) {
            int j = (head - 1 - k + 2 * m) % m;
            double b = rho[j] * dot(n, Y + (size_t)j * n, q);
            for (size_t i = 0; i < n; i++)
                q[i] += (alpha[j] - b) * S[(size_t)j * n + i];
        }
        for (size_t i = 0; i < n; i++)
            d[i] = -q[i];
        double gd = dot(n, g, d);
        if (!(gd < 0.0)) { /* not a descent direction (rounding): restart along -g */
            stored = 0;
            for (size_t i = 0; i < n; i++)
                d[i] = -g[i];
            gd = dot(n, g, d);
        }
        /* the first step has no curvature information: scale it to the cap */
        double dm = max_group(n, group, d);
        double tmax = isfinite(p->max_move) && dm > 0 ? p->max_move / dm : INFINITY;
        double t = fmin(stored ? 1.0 : 1.0 / fmax(1.0, sqrt(dot(n, g, g))), tmax);
        /* weak Wolfe bisection: Armijo c1 = 1e-4, curvature c2 = 0.9 */
        double lo = 0.0, hi = INFINITY, ft = f;
        int ok = 0;
        for (int ls = 0; ls < p->max_ls; ls++) {
            for (size_t i = 0; i < n; i++)
                xt[i] = x[i] + t * d[i];
            ft = fn(ctx, xt, gt);
            out->evals++;
            if (!(ft <= f + 1e-4 * t * gd)) {
                hi = t;
            } else if (dot(n, gt, d) < 0.9 * gd && t < tmax) {
                lo = t;
            } else {
                ok = 1;
                break;
            }
            t = isfinite(hi) ? 0.5 * (lo + hi) : fmin(2.0 * t, tmax);
        }
        if (!ok && lo > 0.0) { /* Armijo holds at lo: take it */
            t = lo;
            for (size_t i = 0; i < n; i++)
                xt[i] = x[i] + t * d[i];
            ft = fn(ctx, xt, gt);
            out->evals++;
            ok = ft <= f;
        }
        if (!ok) {
            out->reason = TR_LBFGS_LINE_SEARCH;
            break;
        }
        /* store s = xt - x, y = gt - g when the curvature is positive */
        double *s = S + (size_t)head * n, *y = Y + (size_t)head * n;
        for (size_t i = 0; i < n; i++) {
            s[i] = xt[i] - x[i];
            y[i] = gt[i] - g[i];
        }
        double sy = dot(n, s, y);
        if (sy > 1e-16 * sqrt(dot(n, s, s) * dot(n, y, y))) {
            rho[head] = 1.0 / sy;
            head = (head + 1) % m;
            if (stored < m)
                stored++;
        }
        double df = f - ft;
        memcpy(x, xt, n * sizeof *x);
        memcpy(g, gt, n * sizeof *g);
        f = ft;
        out->iters = it + 1;
        if (iter && iter(ctx, x, f, g, it)) {
            out->reason = TR_LBFGS_STOPPED;
            break;
        }
        if (df <= p->ftol * (1.0 + fabs(f))) {
            out->reason = TR_LBFGS_FTOL;
            break;
        }
    }
    out->f = f;
    out->gmax = max_abs(n, g);
    free(buf);
    free(rho);
    return TR_OK;
}
