/* This file contains the clasp's symmetry and congruence, compared from the tip
 * (clasp_compare.h). */
#include "analysis/clasp_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The boundaries compared, as distances from the tip of a half. */
enum { B_ES, B_S_END, B_G_START, B_G_END, B_K_START, NB };
static const char *const boundary_names[NB] = {"E|S", "end of S", "start of G", "end of G", "start of K"};

static void boundaries(const tr_clasp_half *h, double *t, double *terr)
{
    const tr_clasp_piece *pc = h->piece;
    t[B_ES] = h->length - pc[TR_CLASP_E].to, terr[B_ES] = pc[TR_CLASP_E].to_err;
    t[B_S_END] = h->length - pc[TR_CLASP_S].to, terr[B_S_END] = pc[TR_CLASP_S].to_err;
    t[B_G_START] = h->length - pc[TR_CLASP_G].from, terr[B_G_START] = pc[TR_CLASP_G].from_err;
    t[B_G_END] = h->length - pc[TR_CLASP_G].to, terr[B_G_END] = pc[TR_CLASP_G].to_err;
    t[B_K_START] = h->length - pc[TR_CLASP_K].from, terr[B_K_START] = pc[TR_CLASP_K].from_err;
}

static void compare_boundaries(const tr_clasp_half *a, const tr_clasp_half *b, tr_clasp_match *m)
{
    double ta[NB], ea[NB], tb[NB], eb[NB];
    boundaries(a, ta, ea);
    boundaries(b, tb, eb);
    for (int q = 0; q < NB; q++) {
        double d = fabs(ta[q] - tb[q]);
        if (!(d <= m->boundary_diff)) {
            m->boundary_diff = d;
            m->boundary_err = hypot(ea[q], eb[q]);
            m->boundary = boundary_names[q];
        }
    }
}

/* A half's curvature against distance from the tip, neighbours averaged in
 * pairs, in increasing distance: t[0..*cnt). */
static int half_samples(const tr_arc_profile *p, const tr_clasp_rope *r, int h, double **t, double **k, size_t *cnt)
{
    size_t n = p->n, c = 0;
    *t = malloc(n * sizeof **t);
    *k = malloc(n * sizeof **k);
    if (!*t || !*k) {
        free(*t), free(*k);
        *t = *k = NULL;
        return TR_ENOMEM;
    }
    for (size_t j = 0; j + 1 < n; j++) {
        /* from the tip outward: half 0 runs down from the tip, half 1 up */
        size_t a = h ? j : n - 2 - j, b = a + 1;
        double la = p->pos[a] - r->tip, lb = p->pos[b] - r->tip;
        if (h ? la < 0 : lb > 0) /* both arcs on this half's side */
            continue;
        (*t)[c] = fabs(0.5 * (la + lb));
        (*k)[c] = 0.5 * (p->kappa[a] + p->kappa[b]);
        c++;
    }
    *cnt = c;
    return TR_OK;
}

static double interp(const double *t, const double *k, size_t n, double x)
{
    if (n == 0)
        return NAN;
    if (x <= t[0])
        return k[0];
    size_t lo = 0, hi = n - 1;
    if (x >= t[hi])
        return k[hi];
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (t[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    double f = (x - t[lo]) / (t[hi] - t[lo]);
    return k[lo] + f * (k[hi] - k[lo]);
}

/* Half ha of rope a against half hb of rope b; accumulates into m. */
static int compare_profiles(const tr_arc_profile *pa, const tr_clasp_rope *a, int ha, const tr_arc_profile *pb,
                            const tr_clasp_rope *b, int hb, tr_clasp_match *m, double *sum2, size_t *cnt,
                            tr_error *err)
{
    double *ta, *ka, *tb, *kb;
    size_t na, nb;
    if (half_samples(pa, a, ha, &ta, &ka, &na) != TR_OK)
        return tr_fail(err, TR_ENOMEM, "out of memory comparing the clasp's halves");
    if (half_samples(pb, b, hb, &tb, &kb, &nb) != TR_OK) {
        free(ta), free(ka);
        return tr_fail(err, TR_ENOMEM, "out of memory comparing the clasp's halves");
    }
    /* up to the shorter half's last pair, two edges short of its free end */
    double span = fmin(a->half[ha].length, b->half[hb].length) - 2.0 * fmax(a->e, b->e);
    m->span = fmin(m->span, span);
    for (size_t i = 0; i < na; i++) {
        if (ta[i] > span)
            break;
        double d = fabs(ka[i] - interp(tb, kb, nb, ta[i]));
        if (!(d <= m->kappa_max_diff))
            m->kappa_max_diff = d, m->kappa_max_at = ta[i];
        *sum2 += d * d;
        (*cnt)++;
    }
    free(ta), free(ka), free(tb), free(kb);
    return TR_OK;
}

static void match_init(tr_clasp_match *m)
{
    memset(m, 0, sizeof *m);
    m->boundary = boundary_names[0];
    m->span = INFINITY;
}

int tr_clasp_symmetry(const tr_arc_profile *p, const tr_clasp_rope *r, tr_clasp_match *out, tr_error *err)
{
    match_init(out);
    if (!r->found)
        return tr_fail(err, TR_EINVAL, "no clasp anatomy to compare: %s", r->why);
    compare_boundaries(&r->half[0], &r->half[1], out);
    double sum2 = 0.0;
    size_t cnt = 0;
    int rc = compare_profiles(p, r, 0, p, r, 1, out, &sum2, &cnt, err);
    out->kappa_rms_diff = cnt ? sqrt(sum2 / (double)cnt) : NAN;
    out->length_diff = fabs(r->half[0].length - r->half[1].length);
    return rc;
}

int tr_clasp_congruence(const tr_arc_profile *pa, const tr_clasp_rope *a, const tr_arc_profile *pb,
                        const tr_clasp_rope *b, tr_clasp_match *out, tr_error *err)
{
    match_init(out);
    if (!a->found || !b->found)
        return tr_fail(err, TR_EINVAL, "no clasp anatomy to compare: %s", a->found ? b->why : a->why);
    double sum2 = 0.0;
    size_t cnt = 0;
    for (int h = 0; h < 2; h++) {
        compare_boundaries(&a->half[h], &b->half[h], out);
        int rc = compare_profiles(pa, a, h, pb, b, h, out, &sum2, &cnt, err);
        if (rc != TR_OK)
            return rc;
    }
    out->kappa_rms_diff = cnt ? sqrt(sum2 / (double)cnt) : NAN;
    out->length_diff = fabs(a->L - b->L);
    return TR_OK;
}
