/* Weighted least-squares extrapolation to N -> infinity (extrapolate.h). */
#include "util/extrapolate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAXP 64 /* points a fit takes: a ladder of N is a handful */

int tr_extrap_fit_powers(const double *n, const double *l, const double *s, const int *use,
                         size_t npoints, const int *powers, int npowers, tr_extrap_fit *out)
{
    memset(out, 0, sizeof *out);
    int m = npowers + 1;
    out->nterms = m;
    if (m > TR_EXTRAP_MAX_TERMS || npoints > MAXP)
        return 1;
    double a[MAXP][TR_EXTRAP_MAX_TERMS], b[MAXP];
    size_t k = 0;
    for (size_t i = 0; i < npoints; i++) {
        if (use && !use[i])
            continue;
        if (!(s[i] > 0.0) || !(n[i] > 0.0) || !isfinite(l[i]))
            return 1;
        double w = 1.0 / s[i];
        a[k][0] = w;
        for (int j = 0; j < npowers; j++)
            a[k][j + 1] = w * pow(n[i], -(double)powers[j]);
        b[k] = w * l[i];
        k++;
    }
    out->npoints = k;
    if ((int)k < m)
        return 1;
    /* unit-norm columns */
    double scale[TR_EXTRAP_MAX_TERMS];
    for (int j = 0; j < m; j++) {
        double t = 0.0;
        for (size_t i = 0; i < k; i++)
            t += a[i][j] * a[i][j];
        scale[j] = sqrt(t);
        if (!(scale[j] > 0.0))
            return 1;
        for (size_t i = 0; i < k; i++)
            a[i][j] /= scale[j];
    }
    /* Householder QR, applied to b as it goes */
    double rdiag[TR_EXTRAP_MAX_TERMS];
    for (int j = 0; j < m; j++) {
        double norm = 0.0;
        for (size_t i = (size_t)j; i < k; i++)
            norm += a[i][j] * a[i][j];
        norm = sqrt(norm);
        if (!(norm > 1e-13)) /* the columns are dependent: the powers cannot be told apart */
            return 1;
        double alpha = a[j][j] > 0 ? -norm : norm;
        double v0 = a[j][j] - alpha;
        /* v = (v0, a[j+1..][j]); H = I - 2 v v^T / v^T v */
        double vtv = v0 * v0;
        for (size_t i = (size_t)j + 1; i < k; i++)
            vtv += a[i][j] * a[i][j];
        for (int c = j + 1; c < m; c++) {
            double d = v0 * a[j][c];
            for (size_t i = (size_t)j + 1; i < k; i++)
                d += a[i][j] * a[i][c];
            d *= 2.0 / vtv;
            a[j][c] -= d * v0;
            for (size_t i = (size_t)j + 1; i < k; i++)
                a[i][c] -= d * a[i][j];
        }
        double d = v0 * b[j];
        for (size_t i = (size_t)j + 1; i < k; i++)
            d += a[i][j] * b[i];
        d *= 2.0 / vtv;
        b[j] -= d * v0;
        for (size_t i = (size_t)j + 1; i < k; i++)
            b[i] -= d * a[i][j];
        rdiag[j] = alpha;
    }
    /* back substitution R x = Q^T b (R: rdiag on the diagonal, a above it) */
    double x[TR_EXTRAP_MAX_TERMS];
    for (int j = m - 1; j >= 0; j--) {
        double t = b[j];
        for (int c = j + 1; c < m; c++)
            t -= a[j][c] * x[c];
        x[j] = t / rdiag[j];
    }
    /* chi^2: the residual is the part of Q^T b below row m */
    double chi2 = 0.0;
    for (size_t i = (size_t)m; i < k; i++)
        chi2 += b[i] * b[i];
    /* covariance (R^T R)^-1 = Rinv Rinv^T, Rinv upper triangular */
    double rinv[TR_EXTRAP_MAX_TERMS][TR_EXTRAP_MAX_TERMS] = {{0}};
    for (int c = 0; c < m; c++) {
        rinv[c][c] = 1.0 / rdiag[c];
        for (int j = c - 1; j >= 0; j--) {
            double t = 0.0;
            for (int q = j + 1; q <= c; q++)
                t += a[j][q] * rinv[q][c];
            rinv[j][c] = -t / rdiag[j];
        }
    }
    for (int j = 0; j < m; j++) {
        double v = 0.0;
        for (int c = j; c < m; c++)
            v += rinv[j][c] * rinv[j][c];
        out->coef[j] = x[j] / scale[j];
        out->sigma[j] = sqrt(v) / scale[j];
    }
    out->chi2 = chi2;
    out->dof = (int)k - m;
    out->birge = out->dof > 0 ? sqrt(chi2 / out->dof) : 1.0;
    out->sigma_scaled = out->sigma[0] * (out->birge > 1.0 ? out->birge : 1.0);
    out->ok = 1;
    return 0;
}

int tr_extrap_report_make(const double *n, const double *l, const double *s, size_t npoints,
                          const int *powers, int npowers, tr_extrap_report *out)
{
    memset(out, 0, sizeof *out);
    out->loo_worst = -1;
    if (npowers < 1 || npowers > TR_EXTRAP_MAX_TERMS - 1 || npoints > MAXP)
        return 1;
    if (tr_extrap_fit_powers(n, l, s, NULL, npoints, powers, 1, &out->fit[0]))
        return 1;
    out->nfits = 1;
    for (int k = 1; k < npowers; k++) {
        if (tr_extrap_fit_powers(n, l, s, NULL, npoints, powers, k + 1, &out->fit[k]))
            break;
        out->nfits = k + 1;
    }
    int sel = 0;
    while (out->fit[sel].birge > 2.0 && sel + 1 < out->nfits && out->fit[sel + 1].dof >= 1)
        sel++;
    out->selected = sel;
    const tr_extrap_fit *f = &out->fit[sel];
    out->linf = f->coef[0];
    if (sel + 1 < out->nfits) {
        out->model_err = fabs(out->fit[sel + 1].coef[0] - out->linf);
        out->model_checked = 1;
    }
    double err2 = f->sigma_scaled * f->sigma_scaled + out->model_err * out->model_err;
    out->loo_min = out->loo_max = out->linf;
    if (npoints >= (size_t)f->nterms + 1) {
        int use[MAXP];
        double th[MAXP], mean = 0.0, worst = -1.0;
        size_t got = 0;
        for (size_t i = 0; i < npoints; i++) {
            for (size_t j = 0; j < npoints; j++)
                use[j] = j != i;
            tr_extrap_fit g;
            if (tr_extrap_fit_powers(n, l, s, use, npoints, powers, sel + 1, &g))
                continue;
            th[got++] = g.coef[0];
            mean += g.coef[0];
            if (g.coef[0] < out->loo_min)
                out->loo_min = g.coef[0];
            if (g.coef[0] > out->loo_max)
                out->loo_max = g.coef[0];
            double mv = fabs(g.coef[0] - out->linf);
            if (mv > worst) {
                worst = mv;
                out->loo_worst = (int)i;
            }
        }
        if (got == npoints) {
            mean /= (double)got;
            double v = 0.0;
            for (size_t i = 0; i < got; i++)
                v += (th[i] - mean) * (th[i] - mean);
            out->jackknife = sqrt(v * (double)(got - 1) / (double)got);
        }
    }
    out->total_err = sqrt(err2);
    if (out->jackknife > out->total_err)
        out->total_err = out->jackknife;
    return 0;
}
