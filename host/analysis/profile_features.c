/* This file contains the features read off a curvature/torsion profile: kappa = 1 plateaus and
 * one-sided jump fits (profile_features.h). */
#include "analysis/profile_features.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/polyline.h"

int tr_profile_find_plateaus(const tr_arc_profile *p, double level, size_t min_arcs, tr_plateau **out,
                             size_t *nout, tr_error *err)
{
    *out = NULL;
    *nout = 0;
    size_t n = p->n, start = n;
    if (min_arcs < 1)
        min_arcs = 1;
    /* Start scanning just after an arc below the level, so no run is split by index 0. */
    for (size_t k = 0; k < n; k++)
        if (!(p->kappa[k] >= level)) {
            start = (k + 1) % n;
            break;
        }
    tr_plateau *pl = malloc((n / 2 + 1) * sizeof *pl);
    if (!pl)
        return tr_fail(err, TR_ENOMEM, "out of memory for plateaus");
    size_t np = 0;
    if (start == n) {
        pl[np++] = (tr_plateau){0, n - 1, tr_wrap(p->pos[0] - 0.5 * p->dl[0], p->L),
                                tr_wrap(p->pos[n - 1] + 0.5 * p->dl[n - 1], p->L)};
    } else {
        size_t j = 0;
        while (j < n) {
            size_t k = (start + j) % n;
            if (!(p->kappa[k] >= level)) {
                j++;
                continue;
            }
            size_t len = 0;
            while (j + len < n && p->kappa[(start + j + len) % n] >= level)
                len++;
            if (len >= min_arcs) {
                size_t a = k, b = (start + j + len - 1) % n;
                pl[np++] = (tr_plateau){a, b, tr_wrap(p->pos[a] - 0.5 * p->dl[a], p->L),
                                        tr_wrap(p->pos[b] + 0.5 * p->dl[b], p->L)};
            }
            j += len;
        }
    }
    *out = pl;
    *nout = np;
    return TR_OK;
}

int tr_profile_find_plateaus_margin(const tr_arc_profile *p, double core_level, double edge_level,
                                    size_t min_core, tr_plateau **out, size_t *nout, tr_error *err)
{
    if (edge_level > core_level)
        edge_level = core_level;
    if (min_core < 1)
        min_core = 1;
    tr_plateau *runs;
    size_t nr;
    int rc = tr_profile_find_plateaus(p, edge_level, 1, &runs, &nr, err);
    if (rc != TR_OK)
        return rc;
    size_t keep = 0;
    for (size_t i = 0; i < nr; i++) {
        size_t core = 0;
        for (size_t k = runs[i].first;; k = (k + 1) % p->n) {
            if (p->kappa[k] >= core_level)
                core++;
            if (k == runs[i].last)
                break;
        }
        if (core >= min_core)
            runs[keep++] = runs[i];
    }
    *out = runs;
    *nout = keep;
    return TR_OK;
}

/* Least squares y = c0 + c1 x (+ c2 x^2 when deg = 2); returns c0 and its
 * standard error. Normal equations are fine here: x is centred on the
 * extrapolation point and spans at most a few hundredths. */
static int fit_intercept(const double *x, const double *y, size_t n, int deg, double *c0,
                         double *se)
{
    int m = deg + 1;
    if ((int)n < m + 1)
        return -1;
    double A[3][4] = {{0}};
    double sx = 0.0; /* scale x to O(1) for conditioning */
    for (size_t i = 0; i < n; i++)
        sx = fmax(sx, fabs(x[i]));
    if (!(sx > 0))
        return -1;
    for (size_t i = 0; i < n; i++) {
        double u = x[i] / sx, pw[3] = {1.0, u, u * u};
        for (int r = 0; r < m; r++) {
            for (int c = 0; c < m; c++)
                A[r][c] += pw[r] * pw[c];
            A[r][3] += pw[r] * y[i];
        }
    }
    /* Invert the small SPD matrix by Gauss-Jordan (need (A^-1)_00 for the error). */
    double M[3][6] = {{0}};
    for (int r = 0; r < m; r++) {
        for (int c = 0; c < m; c++)
            M[r][c] = A[r][c];
        M[r][3 + r] = 1.0;
    }
    for (int c = 0; c < m; c++) {
        int piv = c;
        for (int r = c + 1; r < m; r++)
            if (fabs(M[r][c]) > fabs(M[piv][c]))
                piv = r;
        if (fabs(M[piv][c]) < 1e-300)
            return -1;
        if (piv != c)
            for (int k = 0; k < 6; k++) {
                double tmp = M[c][k];
                M[c][k] = M[piv][k];
                M[piv][k] = tmp;
            }
        double d = M[c][c];
        for (int k = 0; k < 6; k++)
            M[c][k] /= d;
        for (int r = 0; r < m; r++)
            if (r != c) {
                double g = M[r][c];
                for (int k = 0; k < 6; k++)
                    M[r][k] -= g * M[c][k];
            }
    }
    double coef[3] = {0, 0, 0};
    for (int r = 0; r < m; r++)
        for (int c = 0; c < m; c++)
            coef[r] += M[r][3 + c] * A[c][3];
    double rss = 0.0;
    for (size_t i = 0; i < n; i++) {
        double u = x[i] / sx, r = y[i] - (coef[0] + coef[1] * u + (m > 2 ? coef[2] * u * u : 0.0));
        rss += r * r;
    }
    double s2 = (int)n > m ? rss / (double)((int)n - m) : 0.0;
    *c0 = coef[0];
    *se = sqrt(s2 * M[0][3]);
    return 0;
}

typedef struct sample {
    double dx, y;
} sample;

static int by_dx(const void *a, const void *b)
{
    double da = ((const sample *)a)->dx, db = ((const sample *)b)->dx;
    return (da > db) - (da < db);
}

/* The samples of one side (0: left, 1: right) with w <= |dx| <= Wfit into
 * x, y, neighbours averaged in pairs: a tight polygon's curvature and torsion
 * alternate from vertex to vertex (kappa by +-0.05 after l2, phi by +-0.1
 * rad, so alpha zigzags by as much as the jumps measured) where its contacts
 * alternate between two strands' vertices; a period-2 wave averages out of
 * each pair, a line is left unchanged. Returns the count. */
static size_t side_samples(const sample *s, size_t ns, int side, double w, double Wfit, double *x,
                           double *y)
{
    size_t m = 0;
    for (size_t i = 0; i < ns; i++) {
        double d = side ? s[i].dx : -s[i].dx;
        if (d >= w && d <= Wfit) {
            x[m] = s[i].dx;
            y[m] = s[i].y;
            m++;
        }
    }
    if (m >= 2) {
        for (size_t i = 0; i + 1 < m; i++) {
            x[i] = 0.5 * (x[i] + x[i + 1]);
            y[i] = 0.5 * (y[i] + y[i + 1]);
        }
        m--;
    }
    return m;
}

int tr_profile_measure_jump(const tr_arc_profile *p, tr_jump_quantity q, double at, double w, double W,
                            tr_jump *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    out->at = at;
    if (!(w >= 0) || !(W > w) || W > 0.25 * p->L)
        return tr_fail(err, TR_EINVAL, "jump window needs 0 <= w < W < L/4 (w=%g, W=%g)", w, W);
    /* the quadratics run over twice the window: over [w, W] a quadratic's
     * extrapolation carries the points' noise several times over (an
     * unconverged N = 9600 trefoil: Delta kappa_1 0.18 +- 0.013 by
     * quadratics on [w, W], 0.262 +- 0.009 on [w, 2W - w]) */
    double W2 = fmin(w + 2.0 * (W - w), 0.25 * p->L);
    size_t n = p->n, ns = 0;
    sample *s = malloc(n * sizeof *s);
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
    if (!s || !x || !y) {
        free(s), free(x), free(y);
        return tr_fail(err, TR_ENOMEM, "out of memory for a jump fit");
    }
    const double *where = q == TR_JUMP_KAPPA ? p->pos : p->jpos;
    for (size_t k = 0; k < n; k++) {
        double dx = tr_wrap_signed(where[k] - at, p->L);
        if (fabs(dx) <= W2)
            s[ns++] = (sample){dx, q == TR_JUMP_KAPPA ? p->kappa[k] : p->phi[k]};
    }
    qsort(s, ns, sizeof *s, by_dx);
    if (q == TR_JUMP_ALPHA) /* alpha just after each junction, from the window's start */
        for (size_t i = 1; i < ns; i++)
            s[i].y += s[i - 1].y;
    double c[2][2], se[2][2];
    size_t cnt[2] = {0, 0};
    int bad = 0, have_quad[2] = {0, 0};
    for (int side = 0; side < 2; side++) {
        size_t m = side_samples(s, ns, side, w, W, x, y);
        cnt[side] = m;
        if (fit_intercept(x, y, m, 1, &c[side][0], &se[side][0]) != 0) {
            bad = 1;
            break;
        }
        m = side_samples(s, ns, side, w, W2, x, y);
        have_quad[side] = m >= 5 && fit_intercept(x, y, m, 2, &c[side][1], &se[side][1]) == 0;
    }
    free(s), free(x), free(y);
    out->nleft = cnt[0];
    out->nright = cnt[1];
    if (bad)
        return tr_fail(err, TR_EGEOMETRY,
                       "too few points for a jump fit at %.6g (%zu left, %zu right in w=%g..W=%g)",
                       at, cnt[0], cnt[1], w, W);
    /* The quadratics over [w, 2W - w] are the estimate, the lines over
     * [w, W] the model check: on a converged profile kappa is curved just
     * outside the plateau and a line leans with its window (the N = 9600
     * trefoil's Delta kappa_1: 0.265, 0.275, 0.281, 0.297 for W - w = 0.015,
     * 0.02, 0.03, 0.05) where the quadratic stays (0.266, 0.268, 0.271 for
     * 2W - 2w = 0.03, 0.05, 0.06). A side with too few points for a
     * quadratic falls back to the line, model error 0. */
    int quad = have_quad[0] && have_quad[1];
    int k = quad ? 1 : 0;
    out->left = c[0][k];
    out->right = c[1][k];
    out->jump = c[1][k] - c[0][k];
    double stat = hypot(se[0][k], se[1][k]);
    double model = quad ? fabs((c[1][0] - c[0][0]) - out->jump) : 0.0;
    out->err = hypot(stat, model);
    return TR_OK;
}

int tr_profile_kappa_side(const tr_arc_profile *p, double at, int side, double w, double W, int quadratic,
                          double *value, double *se, tr_error *err)
{
    *value = NAN, *se = NAN;
    double half = p->closed ? 0.25 * p->L : p->L;
    if (!(w >= 0) || !(W > w) || W > half)
        return tr_fail(err, TR_EINVAL, "side fit window needs 0 <= w < W%s (w=%g, W=%g)",
                       p->closed ? " < L/4" : " < L", w, W);
    double W2 = fmin(w + 2.0 * (W - w), half);
    size_t n = p->n, ns = 0;
    sample *s = malloc(n * sizeof *s);
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
    if (!s || !x || !y) {
        free(s), free(x), free(y);
        return tr_fail(err, TR_ENOMEM, "out of memory for a side fit");
    }
    for (size_t k = 0; k < n; k++) {
        double dx = p->closed ? tr_wrap_signed(p->pos[k] - at, p->L) : p->pos[k] - at;
        if (fabs(dx) <= W2)
            s[ns++] = (sample){dx, p->kappa[k]};
    }
    qsort(s, ns, sizeof *s, by_dx);
    size_t m = quadratic ? side_samples(s, ns, side, w, W2, x, y) : 0;
    int ok = m >= 5 && fit_intercept(x, y, m, 2, value, se) == 0;
    if (!ok) {
        m = side_samples(s, ns, side, w, W, x, y);
        ok = fit_intercept(x, y, m, 1, value, se) == 0;
    }
    free(s), free(x), free(y);
    if (!ok)
        return tr_fail(err, TR_EGEOMETRY, "too few points for a side fit at %.6g (%zu %s in w=%g..W=%g)", at, m,
                       side ? "right" : "left", w, W);
    return TR_OK;
}
