/* This file contains the refinement's resampler: equal arclength, then a Fourier low-pass for closed components
 * (refine_lowpass.h). */
#include "engine/refine_lowpass.h"

#include "engine/refine_arcs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/vec3.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Positions at equal arclength (m points) along component k, linear
 * interpolation; closed: m points starting at vertex 0, open: ends kept:
 * the Fourier series needs samples equally spaced in arclength. Not
 * curve/polyline.h's point_at: that one is for closed polygons only and sums
 * the arclength compensated; this plain sum is what every refined level has
 * been computed with, and the other would move its coordinates in the last
 * bits. */
static int linear_resample(const tr_curve *c, int k, size_t m, double *y)
{
    size_t s = c->start[k], n = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
    double *cum = malloc((ne + 1) * sizeof *cum);
    if (!cum)
        return TR_ENOMEM;
    cum[0] = 0.0;
    for (size_t j = 0; j < ne; j++)
        cum[j + 1] = cum[j] + sqrt(v3_dist2(c->x + 3 * (s + j), c->x + 3 * (s + (j + 1) % n)));
    double L = cum[ne];
    size_t seg = 0;
    size_t denom = c->closed[k] ? m : m - 1;
    for (size_t i = 0; i < m; i++) {
        double t = L * (double)i / (double)denom;
        while (seg + 1 < ne && cum[seg + 1] <= t)
            seg++;
        const double *a = c->x + 3 * (s + seg), *b = c->x + 3 * (s + (seg + 1) % n);
        double len = cum[seg + 1] - cum[seg];
        double f = len > 0 ? (t - cum[seg]) / len : 0.0;
        if (f > 1.0)
            f = 1.0;
        for (int d = 0; d < 3; d++)
            y[3 * i + d] = a[d] + f * (b[d] - a[d]);
    }
    if (!c->closed[k])
        memcpy(y + 3 * (m - 1), c->x + 3 * (s + n - 1), 3 * sizeof *y);
    free(cum);
    return TR_OK;
}

int tr_refine_lowpass(const tr_curve *in, size_t n, double cut, double taper_from, tr_curve *out,
                       tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (n < 4)
        return tr_fail(err, TR_EINVAL, "cannot resample to %zu vertices", n);
    size_t *nv = malloc((size_t)in->ncomp * sizeof *nv);
    if (!nv)
        return tr_fail(err, TR_ENOMEM, "out of memory resampling");
    for (int k = 0; k < in->ncomp; k++)
        nv[k] = n;
    int rc = tr_curve_alloc(out, in->ncomp, nv, in->closed, err);
    free(nv);
    if (rc)
        return rc;
    for (int k = 0; k < in->ncomp; k++) {
        size_t nold = tr_comp_nv(in, k);
        double *y = out->x + 3 * out->start[k];
        if (!in->closed[k]) {
            if ((rc = tr_refine_arcs_open(in, k, n, y, err)) != TR_OK) {
                tr_curve_free(out);
                return rc;
            }
            continue;
        }
        /* uniform samples of the old curve, then a truncated Fourier series */
        double *u = malloc(3 * nold * sizeof *u);
        size_t nm = nold / 2 + 1;
        double *re = calloc(3 * nm, sizeof *re), *im = calloc(3 * nm, sizeof *im);
        if (!u || !re || !im || linear_resample(in, k, nold, u) != TR_OK) {
            free(u);
            free(re);
            free(im);
            tr_curve_free(out);
            return tr_fail(err, TR_ENOMEM, "out of memory resampling");
        }
        double kc = cut * (double)(nold / 2), k0 = taper_from * kc;
        for (size_t q = 0; q < nm; q++) {
            double w = 1.0;
            if ((double)q >= kc)
                w = 0.0;
            else if ((double)q > k0)
                w = 0.5 * (1.0 + cos(M_PI * ((double)q - k0) / (kc - k0)));
            if (w == 0.0)
                continue;
            for (size_t i = 0; i < nold; i++) {
                double ang = 2.0 * M_PI * (double)((q * i) % nold) / (double)nold;
                double cs = cos(ang), sn = sin(ang);
                for (int d = 0; d < 3; d++) {
                    re[3 * q + d] += u[3 * i + d] * cs;
                    im[3 * q + d] -= u[3 * i + d] * sn;
                }
            }
            /* weight, normalisation, and the doubling of the conjugate half */
            double f = w / (double)nold * ((q == 0 || (2 * q == nold)) ? 1.0 : 2.0);
            for (int d = 0; d < 3; d++) {
                re[3 * q + d] *= f;
                im[3 * q + d] *= f;
            }
        }
        for (size_t j = 0; j < n; j++) {
            double p[3] = {0, 0, 0};
            for (size_t q = 0; q < nm; q++) {
                if (re[3 * q] == 0.0 && im[3 * q] == 0.0 && re[3 * q + 1] == 0.0 && im[3 * q + 1] == 0.0 &&
                    re[3 * q + 2] == 0.0 && im[3 * q + 2] == 0.0)
                    continue;
                double ang = 2.0 * M_PI * (double)q * (double)j / (double)n;
                double cs = cos(ang), sn = sin(ang);
                for (int d = 0; d < 3; d++)
                    p[d] += re[3 * q + d] * cs - im[3 * q + d] * sn;
            }
            memcpy(y + 3 * j, p, sizeof p);
        }
        free(u);
        free(re);
        free(im);
    }
    /* end-vertex constraints of open components */
    for (int k = 0; k < in->ncomp; k++) {
        if (in->closed[k] || !in->vcst)
            continue;
        size_t ends_old[2] = {in->start[k], in->start[k + 1] - 1};
        size_t ends_new[2] = {out->start[k], out->start[k + 1] - 1};
        for (int e = 0; e < 2; e++) {
            int ci = in->vcst[ends_old[e]];
            if (ci < 0)
                continue;
            int idx = -1;
            for (int q = 0; q < out->ncst; q++)
                if (out->cst[q].id == in->cst[ci].id)
                    idx = q;
            if (idx < 0) {
                idx = tr_curve_add_constraint(out, &in->cst[ci], err);
                if (idx < 0) {
                    tr_curve_free(out);
                    return idx;
                }
            }
            out->vcst[ends_new[e]] = idx;
        }
    }
    return TR_OK;
}
