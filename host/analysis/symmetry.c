/* This file contains the rotational symmetry of a closed knot: threefold and twofold axes and
 * the arclength origin (symmetry.h). */
#include "analysis/symmetry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/polyline.h"
#include "util/vec3.h"

#define TR_PI 3.14159265358979323846

const char *tr_symmetry_name(tr_symmetry_kind k)
{
    switch (k) {
    case TR_SYM_D3:
        return "D3";
    case TR_SYM_C3:
        return "C3";
    case TR_SYM_C2:
        return "C2";
    default:
        return "none";
    }
}

typedef struct c2_ctx {
    const double *x;
    size_t n;
    const double *s;
    size_t K;       /* pairs used in a refined fit */
    double *a, *b;  /* 3K scratch */
    const double *c;
} c2_ctx;

/* Best rotation for the reversal l -> 2 lc - l, from K pairs spread over half the curve. */
static void c2_fit(c2_ctx *ctx, double lc, tr_rotation *r)
{
    double L = ctx->s[ctx->n];
    for (size_t k = 0; k < ctx->K; k++) {
        double d = ((double)k + 0.5) * 0.5 * L / (double)ctx->K;
        tr_polyline_point_at(ctx->x, ctx->n, ctx->s, lc + d, ctx->a + 3 * k);
        tr_polyline_point_at(ctx->x, ctx->n, ctx->s, lc - d, ctx->b + 3 * k);
    }
    tr_rotation_fit(ctx->a, ctx->b, ctx->K, ctx->c, r);
}

/* Golden-section search for the residual minimum on [lo, hi]. */
static double c2_refine(c2_ctx *ctx, double lo, double hi, tr_rotation *best)
{
    const double g = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    tr_rotation r1, r2;
    c2_fit(ctx, x1, &r1);
    c2_fit(ctx, x2, &r2);
    double L = ctx->s[ctx->n];
    for (int it = 0; it < 200 && hi - lo > 1e-14 * L; it++) {
        if (r1.rms < r2.rms) {
            hi = x2;
            x2 = x1, r2 = r1;
            x1 = hi - g * (hi - lo);
            c2_fit(ctx, x1, &r1);
        } else {
            lo = x1;
            x1 = x2, r1 = r2;
            x2 = lo + g * (hi - lo);
            c2_fit(ctx, x2, &r2);
        }
    }
    double lc = 0.5 * (lo + hi);
    c2_fit(ctx, lc, best);
    return lc;
}

static int by_l(const void *a, const void *b)
{
    double x = ((const tr_twofold *)a)->l, y = ((const tr_twofold *)b)->l;
    return (x > y) - (x < y);
}

int tr_symmetry_find(const double *x, size_t n, const tr_symmetry_opts *opts, tr_symmetry *out,
                     tr_error *err)
{
    memset(out, 0, sizeof *out);
    out->origin = NAN;
    out->twofold_rms_best = INFINITY;
    if (n < 6)
        return tr_fail(err, TR_EINVAL, "symmetry analysis needs at least 6 vertices");
    double tol = opts && opts->tol > 0 ? opts->tol : 1e-3;
    size_t M = opts && opts->samples ? opts->samples : 6 * ((n + 5) / 6);
    if (!(opts && opts->samples)) {
        if (M < 600)
            M = 600;
        if (M > 3000)
            M = 3000;
    }
    M = 6 * ((M + 5) / 6);
    double *s = malloc((n + 1) * sizeof *s);
    double *p = malloc(3 * M * sizeof *p);
    double *a = malloc(3 * M * sizeof *a), *b = malloc(3 * M * sizeof *b);
    double *rms = malloc(2 * M * sizeof *rms), *ang = malloc(2 * M * sizeof *ang);
    if (!s || !p || !a || !b || !rms || !ang) {
        free(s), free(p), free(a), free(b), free(rms), free(ang);
        return tr_fail(err, TR_ENOMEM, "out of memory for the symmetry analysis");
    }
    tr_polyline_arclength(x, n, s);
    double L = s[n];
    out->L = L;
    out->tol = tol;
    /* Arclength-weighted centroid: every D3 element fixes it. */
    double c[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        const double *u = x + 3 * i, *v = x + 3 * ((i + 1) % n);
        double e = s[i + 1] - s[i];
        for (int d = 0; d < 3; d++)
            c[d] += 0.5 * e * (u[d] + v[d]);
    }
    for (int d = 0; d < 3; d++)
        out->centroid[d] = c[d] / L;
    for (size_t j = 0; j < M; j++)
        tr_polyline_point_at(x, n, s, (double)j * L / (double)M, p + 3 * j);
    double g = 0.0;
    for (size_t j = 0; j < M; j++)
        g += v3_dist2(p + 3 * j, out->centroid);
    out->rg = sqrt(g / (double)M);
    double thr = tol * out->rg;

    /* Threefold: sample j -> sample j + M/3 is l -> l + L/3. */
    for (size_t j = 0; j < M; j++)
        memcpy(b + 3 * j, p + 3 * ((j + M / 3) % M), 3 * sizeof *b);
    tr_rotation_fit(p, b, M, out->centroid, &out->c3);
    out->has_c3 = out->c3.rms < thr && fabs(out->c3.angle - 2.0 * TR_PI / 3.0) < 0.05;

    /* Twofold: scan reversal centres on the half-sample grid lc = j L/(2M),
     * i.e. centre j/2 in sample units, pairing samples centre + d and
     * centre - d (d = k + 1/2 for odd j, k + 1 for even j). */
    size_t Kc = M / 2;
    for (size_t j = 0; j < 2 * M; j++) {
        size_t hi0 = j % 2 ? (j + 1) / 2 : j / 2 + 1;
        size_t lo0 = j % 2 ? j / 2 : (j / 2 + M - 1) % M;
        for (size_t k = 0; k < Kc; k++) {
            memcpy(a + 3 * k, p + 3 * ((hi0 + k) % M), 3 * sizeof *a);
            memcpy(b + 3 * k, p + 3 * ((lo0 + M - k) % M), 3 * sizeof *b);
        }
        tr_rotation r;
        tr_rotation_fit(a, b, Kc, out->centroid, &r);
        rms[j] = r.rms;
        ang[j] = r.angle;
    }
    /* Candidates: local minima of the residual whose rotation is near a half
     * turn; refine the best few (a D3 knot has 6, each axis meeting the curve
     * twice), keep those below the threshold. */
    enum { NCAND = 24 };
    size_t cand[NCAND], nc = 0;
    for (size_t j = 0; j < 2 * M; j++) {
        double prev = rms[(j + 2 * M - 1) % (2 * M)], next = rms[(j + 1) % (2 * M)];
        if (!(rms[j] <= prev && rms[j] < next) || fabs(ang[j] - TR_PI) > 0.2)
            continue;
        if (nc < NCAND) {
            cand[nc++] = j;
        } else {
            size_t worst = 0;
            for (size_t i = 1; i < nc; i++)
                if (rms[cand[i]] > rms[cand[worst]])
                    worst = i;
            if (rms[j] < rms[cand[worst]])
                cand[worst] = j;
        }
    }
    c2_ctx ctx = {x, n, s, M / 2, a, b, out->centroid};
    size_t nt = 0;
    for (size_t ci = 0; ci < nc && nt < TR_MAX_TWOFOLD; ci++) {
        size_t j = cand[ci];
        double lc0 = (double)j * 0.5 * L / (double)M, h = 0.5 * L / (double)M;
        tr_rotation r;
        double lc = c2_refine(&ctx, lc0 - h, lc0 + h, &r);
        if (fabs(r.angle - TR_PI) < 0.05 && r.rms < out->twofold_rms_best)
            out->twofold_rms_best = r.rms;
        if (!(r.rms < thr && fabs(r.angle - TR_PI) < 0.05))
            continue;
        tr_twofold *t = &out->twofold[nt++];
        t->l = tr_wrap(lc, L);
        t->angle = r.angle;
        t->rms = r.rms;
        double q[3], u[3];
        tr_polyline_point_at(x, n, s, lc, q);
        v3_sub(u, q, out->centroid);
        double sgn = v3_dot(u, r.axis) >= 0 ? 1.0 : -1.0;
        v3_scale(t->axis, sgn, r.axis);
        out->twofold_rms_max = fmax(out->twofold_rms_max, r.rms);
    }
    out->n_twofold = nt;
    qsort(out->twofold, nt, sizeof *out->twofold, by_l);
    int perp = 0;
    for (size_t i = 0; i < nt; i++)
        if (fabs(v3_dot(out->twofold[i].axis, out->c3.axis)) < 0.05)
            perp++;
    if (out->has_c3 && perp > 0)
        out->verdict = TR_SYM_D3;
    else if (out->has_c3)
        out->verdict = TR_SYM_C3;
    else if (nt > 0)
        out->verdict = TR_SYM_C2;
    else
        out->verdict = TR_SYM_NONE;
    free(s), free(p), free(a), free(b), free(rms), free(ang);
    return TR_OK;
}

void tr_symmetry_choose_origin(tr_symmetry *s, const tr_arc_profile *p)
{
    if (s->n_twofold == 0) {
        s->origin = 0.0;
        return;
    }
    double win = s->L / 60.0, best = -1.0;
    size_t bi = 0;
    for (size_t i = 0; i < s->n_twofold; i++) {
        double sum = 0.0, wsum = 0.0;
        for (size_t k = 0; k < p->n; k++)
            if (fabs(tr_wrap_signed(p->pos[k] - s->twofold[i].l, p->L)) <= win) {
                sum += p->kappa[k] * p->dl[k];
                wsum += p->dl[k];
            }
        double score = wsum > 0 ? sum / wsum : 0.0;
        if (score > best * (1.0 + 1e-9)) {
            best = score;
            bi = i;
        }
    }
    s->origin = s->twofold[bi].l;
}

double tr_symmetry_from_origin(const tr_symmetry *s, double l)
{
    return tr_wrap(l - (isnan(s->origin) ? 0.0 : s->origin), s->L);
}

double tr_symmetry_reduce(double l, double L, int *sector)
{
    double six = L / 6.0;
    l = tr_wrap(l, L);
    int k = (int)floor(l / six);
    if (k > 5)
        k = 5;
    if (k < 0)
        k = 0;
    double r = (k % 2 == 0) ? l - k * six : (k + 1) * six - l;
    if (r >= six)
        r = nextafter(six, 0.0);
    if (r < 0)
        r = 0.0;
    if (sector)
        *sector = k;
    return r;
}
