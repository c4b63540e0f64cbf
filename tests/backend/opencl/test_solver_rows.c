/* This file contains the test of the backends' strut_rows (backend.h): the
 * second-order solver's strut rows. The reference against the body it is
 * specified by (kernels/segment_distance.h tr_strut_row_derivs and
 * tr_phr_ineq_term), to the bit; the OpenCL backend against the reference,
 * on the simple clasp, a trefoil and the Hopf link (every pair of edges that
 * share no vertex, or the closest of them) and on hand-made pairs: parallel
 * and nearly parallel segments (the Hessian's parallel branch on both sides
 * of its threshold) and closest points at an end of one or both. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/backend.h"
#include "curve/generate.h"
#include "segment_distance.h"
#include "testlib.h"

typedef struct rows_case {
    const char *name;
    size_t nv, np;
    double *x, *lam;
    size_t *quad;
    double mu, dist, band;
} rows_case;

static void case_free(rows_case *k)
{
    free(k->x);
    free(k->lam);
    free(k->quad);
}

typedef struct pair_d {
    size_t a, b;
    double d;
} pair_d;

static int by_d(const void *p, const void *q)
{
    double a = ((const pair_d *)p)->d, b = ((const pair_d *)q)->d;
    return (a > b) - (a < b);
}

static int by_ab(const void *p, const void *q)
{
    const pair_d *a = p, *b = q;
    if (a->a != b->a)
        return (a->a > b->a) - (a->a < b->a);
    return (a->b > b->b) - (a->b < b->b);
}

/* Hand-made pairs, four vertices each, appended after the curve's:
 * parallel (the closest points where q starts), nearly parallel below and
 * above the Hessian's threshold (sin^2 1e-11 and 1e-9; the strands cross
 * in projection, so both closest points are interior), a crossing, closest points at one end (s = 1)
 * and at an end of both (s = 1, t = 0). */
#define SPECIAL 6
static const double special[SPECIAL][12] = {
    {0, 0, 0, 1, 0, 0, 0.3, 2, 0, 1.3, 2, 0},
    {0, 0, 0, 1, 0, 0, 0.3, 2, -1.6e-6, 1.3, 2, 1.6e-6},
    {0, 0, 0, 1, 0, 0, 0.3, 2, -1.6e-5, 1.3, 2, 1.6e-5},
    {0, 0, 0, 1, 0, 0, 0.4, -0.5, 2.01, 0.6, 0.5, 1.99},
    {0, 0, 0, 1, 0, 0, 1.4, 0.5, 1.9, 1.5, -0.5, 2.1},
    {0, 0, 0, 1, 0, 0, 2.2, 0, 0.5, 3, 1, 0.5},
};

/* Every pair of edges of c sharing no vertex (the closest maxp of them when
 * more), then the hand-made pairs; multipliers of every kind (0, small, and
 * large on the hand-made pairs, so they are selected); the bound at the
 * median distance (the lower third's top of the closest maxp), so that
 * both sides of the selection occur. */
static int make_case(const char *name, const tr_curve *c, size_t maxp, rows_case *k)
{
    memset(k, 0, sizeof *k);
    k->name = name;
    size_t nv = c->nv, cap = nv * nv / 2 + 1, n = 0;
    size_t *next = malloc(nv * sizeof *next);
    pair_d *pd = malloc(cap * sizeof *pd);
    if (!next || !pd)
        return 1;
    for (int q = 0; q < c->ncomp; q++)
        for (size_t i = c->start[q]; i < c->start[q + 1]; i++)
            next[i] = i + 1 < c->start[q + 1] ? i + 1 : (c->closed[q] ? c->start[q] : SIZE_MAX);
    for (size_t a = 0; a < nv; a++)
        for (size_t b = a + 1; b < nv; b++) {
            if (next[a] == SIZE_MAX || next[b] == SIZE_MAX || next[a] == b || next[b] == a)
                continue;
            double s, t;
            double d = tr_segment_distance(c->x + 3 * a, c->x + 3 * next[a], c->x + 3 * b, c->x + 3 * next[b], &s, &t);
            pd[n++] = (pair_d){a, b, d};
        }
    qsort(pd, n, sizeof *pd, by_d);
    double median = pd[n / 2].d;
    if (n > maxp)
        n = maxp;
    qsort(pd, n, sizeof *pd, by_ab);
    k->nv = nv + 4 * SPECIAL;
    k->np = n + SPECIAL;
    k->x = malloc(3 * k->nv * sizeof *k->x);
    k->lam = malloc(k->np * sizeof *k->lam);
    k->quad = malloc(4 * k->np * sizeof *k->quad);
    if (!k->x || !k->lam || !k->quad)
        return 1;
    memcpy(k->x, c->x, 3 * nv * sizeof *k->x);
    for (size_t p = 0; p < n; p++) {
        size_t *q = k->quad + 4 * p;
        q[0] = pd[p].a, q[1] = next[pd[p].a], q[2] = pd[p].b, q[3] = next[pd[p].b];
        k->lam[p] = p % 4 == 0 ? 0.0 : 0.05 * (double)(1 + p % 5);
    }
    for (size_t j = 0; j < SPECIAL; j++) {
        memcpy(k->x + 3 * (nv + 4 * j), special[j], 12 * sizeof(double));
        for (size_t v = 0; v < 4; v++)
            k->quad[4 * (n + j) + v] = nv + 4 * j + v;
        k->lam[n + j] = 1e6;
    }
    k->mu = 100.0;
    k->dist = n ? (n < maxp ? median : pd[n / 3].d) : 2.0;
    k->band = 1e-4 * k->dist;
    free(next);
    free(pd);
    return 0;
}

static void gather(const rows_case *k, size_t p, double *x12)
{
    for (int j = 0; j < 4; j++)
        for (int c = 0; c < 3; c++)
            x12[3 * j + c] = k->x[3 * k->quad[4 * p + (size_t)j] + (size_t)c];
}

static tr_strut_rows args(const rows_case *k, int mode)
{
    tr_strut_rows r = {.mode = mode, .nv = k->nv, .np = k->np, .x = k->x, .quad = k->quad, .lam = k->lam,
                       .mu = k->mu, .dist = k->dist, .band = mode == TR_ROWS_HESS ? k->band : -INFINITY,
                       .sum0 = 123.25};
    return r;
}

/* The reference against the body, to the bit. */
static void check_reference(const tr_backend *b, const rows_case *k)
{
    tr_error err;
    tr_strut_rows v = args(k, TR_ROWS_VALUE);
    REQUIRE_OK(b->ops->strut_rows(b->state, &v, &err));
    double f = v.sum0, dmin = INFINITY;
    for (size_t p = 0; p < k->np; p++) {
        double x12[12], pi;
        gather(k, p, x12);
        double d = tr_strut_row_derivs(x12, NULL, NULL, 0, 0);
        dmin = fmin(dmin, d);
        f += tr_phr_ineq_term(d - k->dist, k->lam[p], k->mu, &pi);
    }
    CHECK(v.sum == f);
    CHECK(v.dmin == dmin);
    for (int mode = TR_ROWS_GRAD; mode <= TR_ROWS_HESS; mode++) {
        tr_strut_rows r = args(k, mode);
        REQUIRE_OK(b->ops->strut_rows(b->state, &r, &err));
        size_t sel = 0, bad = 0;
        for (size_t p = 0; p < k->np; p++) {
            double x12[12], g[12], h[144], pi;
            gather(k, p, x12);
            double d = tr_strut_row_derivs(x12, g, h, 1, 1);
            tr_phr_ineq_term(d - k->dist, k->lam[p], k->mu, &pi);
            int want = pi > 0.0 || d - k->dist < r.band;
            bad += r.d[p] != d || (r.sel[p] >= 0) != want;
            if (!want || r.sel[p] < 0)
                continue;
            bad += r.sel[p] != (int)sel;
            bad += memcmp(r.g + 12 * sel, g, sizeof g) != 0;
            if (mode == TR_ROWS_HESS)
                bad += memcmp(r.h + 144 * sel, h, sizeof h) != 0;
            sel++;
        }
        CHECK(bad == 0);
        CHECK(r.nsel == sel);
        CHECK(r.sum == f && r.dmin == dmin);
        if (!(sel >= SPECIAL && sel < k->np))
            printf("%s mode %d: %zu of %zu selected\n", k->name, mode, sel, k->np);
        CHECK(sel >= SPECIAL && sel < k->np); /* both sides of the selection */
    }
}

/* largest |a - b| over n entries, relative to the largest |b| (or 1) */
static double rel_diff(const double *a, const double *b, size_t n)
{
    double m = 0.0, s = 1e-300;
    for (size_t i = 0; i < n; i++) {
        m = fmax(m, fabs(a[i] - b[i]));
        s = fmax(s, fabs(b[i]));
        if (!isfinite(a[i]))
            return INFINITY;
    }
    return m / s;
}

/* The OpenCL backend against the reference. */
static void check_opencl(const tr_backend *ref, const tr_backend *cl, const rows_case *k)
{
    tr_error err;
    tr_strut_rows vr = args(k, TR_ROWS_VALUE), vc = vr;
    REQUIRE_OK(ref->ops->strut_rows(ref->state, &vr, &err));
    REQUIRE_OK(cl->ops->strut_rows(cl->state, &vc, &err));
    /* the sum against the sum of the terms' sizes: the device folds them in another order */
    double scale = fabs(vr.sum0);
    for (size_t p = 0; p < k->np; p++) {
        double x12[12], pi;
        gather(k, p, x12);
        scale += fabs(tr_phr_ineq_term(tr_strut_row_derivs(x12, NULL, NULL, 0, 0) - k->dist, k->lam[p], k->mu, &pi));
    }
    CHECK_NEAR(vc.sum, vr.sum, 1e-13 * scale);
    CHECK_NEAR(vc.dmin, vr.dmin, 1e-15 * vr.dmin);
    double worst_d = 0.0, worst_g = 0.0, worst_h = 0.0;
    for (int mode = TR_ROWS_HESS; mode >= TR_ROWS_GRAD; mode--) {
        tr_strut_rows rr = args(k, mode), rc = rr;
        REQUIRE_OK(ref->ops->strut_rows(ref->state, &rr, &err));
        REQUIRE_OK(cl->ops->strut_rows(cl->state, &rc, &err));
        CHECK(rc.nsel == rr.nsel);
        /* the value the same sum as at a line-search point, to the bit */
        CHECK(rc.sum == vc.sum && rc.dmin == vc.dmin);
        CHECK(rr.sum == vr.sum);
        worst_d = fmax(worst_d, rel_diff(rc.d, rr.d, k->np));
        size_t same = 0;
        for (size_t p = 0; p < k->np; p++) {
            same += rc.sel[p] == rr.sel[p];
            if (rc.sel[p] < 0 || rc.sel[p] != rr.sel[p] || (size_t)rc.sel[p] >= rr.nsel)
                continue;
            size_t q = (size_t)rc.sel[p];
            worst_g = fmax(worst_g, rel_diff(rc.g + 12 * q, rr.g + 12 * q, 12));
            if (mode == TR_ROWS_HESS)
                worst_h = fmax(worst_h, rel_diff(rc.h + 144 * q, rr.h + 144 * q, 144));
        }
        CHECK(same == k->np);
        CHECK(mode == TR_ROWS_HESS ? rc.h != NULL : rc.h == NULL);
    }
    printf("%s: %zu pairs, device against reference: d %.1e, gradients %.1e, Hessians %.1e (relative, per block)\n",
           k->name, k->np, worst_d, worst_g, worst_h);
    CHECK(worst_d <= 1e-14);
    CHECK(worst_g <= 1e-12);
    CHECK(worst_h <= 1e-12);
}

/* No pairs: the value is sum0, nothing selected. */
static void check_empty(const tr_backend *b, const rows_case *k)
{
    tr_error err;
    tr_strut_rows r = args(k, TR_ROWS_VALUE);
    r.np = 0;
    REQUIRE_OK(b->ops->strut_rows(b->state, &r, &err));
    CHECK(r.sum == r.sum0 && isinf(r.dmin));
    r.mode = TR_ROWS_HESS;
    REQUIRE_OK(b->ops->strut_rows(b->state, &r, &err));
    CHECK(r.nsel == 0);
    /* a vertex index outside the positions is refused by the device */
    if (!b->ops->serial) {
        tr_strut_rows bad = args(k, TR_ROWS_VALUE);
        size_t q[4] = {0, 1, 2, k->nv};
        bad.np = 1;
        bad.quad = q;
        CHECK(b->ops->strut_rows(b->state, &bad, &err) == TR_EINVAL);
    }
}

/* The hand-made pairs are what they say. */
static void check_special(void)
{
    double st[SPECIAL][2];
    for (int j = 0; j < SPECIAL; j++) {
        const double *x = special[j];
        tr_segment_distance(x, x + 3, x + 6, x + 9, &st[j][0], &st[j][1]);
    }
    CHECK(st[0][0] > 0.0 && st[0][0] < 1.0 && st[0][1] == 0.0);
    CHECK(st[1][0] > 0.0 && st[1][0] < 1.0 && st[1][1] > 0.0 && st[1][1] < 1.0);
    CHECK(st[2][0] > 0.0 && st[2][0] < 1.0 && st[2][1] > 0.0 && st[2][1] < 1.0);
    CHECK(st[3][0] > 0.0 && st[3][0] < 1.0 && st[3][1] > 0.0 && st[3][1] < 1.0);
    CHECK(st[4][0] == 1.0 && st[4][1] > 0.0 && st[4][1] < 1.0);
    CHECK(st[5][0] == 1.0 && st[5][1] == 0.0);
}

int main(void)
{
    const int small = tr_test_small();
    tr_error err;
    check_special();
    tr_curve c[3];
    const char *names[3] = {"clasp", "trefoil", "hopf"};
    size_t n = small ? 64 : 160; /* T(2,3) takes at least 62 */
    if (tr_make_clasp(&c[0], n / 2, 4.0, &err) || tr_make_torus(&c[1], 2, 3, n, &err) ||
        tr_make_hopf(&c[2], n / 2, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    tr_backend ref, cl;
    if (tr_backend_open_device("reference", &c[1], 0, &ref, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    int have_cl = tr_backend_open_device("opencl", &c[1], 0, &cl, &err) == TR_OK;
    if (!have_cl)
        printf("no usable OpenCL device (%s): the device checks are skipped\n", err.msg);
    /* the largest case first, then smaller ones on the same buffers */
    size_t maxp[3] = {small ? 400 : 6000, small ? 300 : 3000, small ? 200 : 1000};
    for (int i = 0; i < 3; i++) {
        rows_case k;
        if (make_case(names[i], &c[i], maxp[i], &k)) {
            fprintf(stderr, "out of memory\n");
            return 1;
        }
        check_reference(&ref, &k);
        if (have_cl)
            check_opencl(&ref, &cl, &k);
        if (i == 2) {
            check_empty(&ref, &k);
            if (have_cl)
                check_empty(&cl, &k);
        }
        case_free(&k);
        tr_curve_free(&c[i]);
    }
    tr_backend_close(&ref);
    if (have_cl)
        tr_backend_close(&cl);
    return tr_test_finish("test_solver_rows");
}
