/* This file contains the contacts of a tight knot and its contact functions sigma-(l), sigma+(l)
 * (contact_functions.h). */
#include "analysis/contact_functions.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/polyline.h"

int tr_contact_pairs_from_struts(const double *x, size_t n, size_t base, const tr_strut *s,
                                 size_t ns, double dist_max, tr_contact_pair **out, size_t *nout,
                                 tr_error *err)
{
    *out = NULL;
    *nout = 0;
    double *sl = malloc((n + 1) * sizeof *sl);
    tr_contact_pair *p = malloc((ns ? ns : 1) * sizeof *p);
    if (!sl || !p) {
        free(sl), free(p);
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu struts", ns);
    }
    tr_polyline_arclength(x, n, sl);
    size_t m = 0;
    for (size_t k = 0; k < ns; k++) {
        if (s[k].ei < base || s[k].ej < base || s[k].ei - base >= n || s[k].ej - base >= n ||
            !(s[k].dist <= dist_max))
            continue;
        size_t i = s[k].ei - base, j = s[k].ej - base;
        p[m].li = tr_wrap(sl[i] + s[k].si * (sl[i + 1] - sl[i]), sl[n]);
        p[m].lj = tr_wrap(sl[j] + s[k].sj * (sl[j + 1] - sl[j]), sl[n]);
        p[m].dist = s[k].dist;
        m++;
    }
    free(sl);
    *out = p;
    *nout = m;
    return TR_OK;
}

void tr_contact_fn_free(tr_contact_fn *f)
{
    if (!f)
        return;
    free(f->l), free(f->u);
    memset(f, 0, sizeof *f);
}

typedef struct lu {
    double l, u;
} lu;

static int by_l(const void *a, const void *b)
{
    double x = ((const lu *)a)->l, y = ((const lu *)b)->l;
    return (x > y) - (x < y);
}

int tr_contact_fn_from_samples(const double *l, const double *u, size_t n, double L,
                               tr_contact_fn *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (!(L > 0) || !isfinite(L))
        return tr_fail(err, TR_EINVAL, "a contact function needs a positive finite period, got %g", L);
    if (n < 2)
        return tr_fail(err, TR_EGEOMETRY, "a contact function needs at least 2 samples");
    if (n > ((size_t)-1) / sizeof(lu))
        return tr_fail(err, TR_ENOMEM, "too many samples (%zu) for a contact function", n);
    lu *s = malloc(n * sizeof *s);
    double *w = malloc(n * sizeof *w), *v = malloc(n * sizeof *v);
    size_t *len = malloc(n * sizeof *len);
    out->l = malloc(n * sizeof *out->l);
    out->u = malloc(n * sizeof *out->u);
    if (!s || !w || !v || !len || !out->l || !out->u) {
        free(s), free(w), free(v), free(len);
        tr_contact_fn_free(out);
        return tr_fail(err, TR_ENOMEM, "out of memory for a contact function");
    }
    for (size_t k = 0; k < n; k++) {
        double r = tr_wrap(l[k], L);
        s[k] = (lu){r, u[k] + (r - l[k])};
    }
    qsort(s, n, sizeof *s, by_l);
    /* Pool adjacent violators: blocks of equal value with weights. */
    size_t nb = 0;
    for (size_t k = 0; k < n; k++) {
        v[nb] = s[k].u;
        w[nb] = 1.0;
        len[nb] = 1;
        nb++;
        while (nb > 1 && v[nb - 2] > v[nb - 1]) {
            double ww = w[nb - 2] + w[nb - 1];
            v[nb - 2] = (w[nb - 2] * v[nb - 2] + w[nb - 1] * v[nb - 1]) / ww;
            w[nb - 2] = ww;
            len[nb - 2] += len[nb - 1];
            nb--;
        }
    }
    size_t k = 0;
    for (size_t b = 0; b < nb; b++)
        for (size_t j = 0; j < len[b]; j++, k++) {
            out->l[k] = s[k].l;
            out->u[k] = v[b];
        }
    /* Across the period: u(l_0) + L must not lie below u(l_{n-1}). */
    for (size_t j = n; j-- > 1 && out->u[j] > out->u[0] + L;)
        out->u[j] = out->u[0] + L;
    out->n = n;
    out->L = L;
    free(s), free(w), free(v), free(len);
    return TR_OK;
}

/* Segment holding r in [0, L): endpoints (la, ua), (lb, ub) with the
 * periodic continuation across the ends. */
static void segment(const tr_contact_fn *f, double r, double *la, double *ua, double *lb,
                    double *ub)
{
    size_t n = f->n;
    if (r < f->l[0]) {
        *la = f->l[n - 1] - f->L, *ua = f->u[n - 1] - f->L;
        *lb = f->l[0], *ub = f->u[0];
        return;
    }
    if (r >= f->l[n - 1]) {
        *la = f->l[n - 1], *ua = f->u[n - 1];
        *lb = f->l[0] + f->L, *ub = f->u[0] + f->L;
        return;
    }
    size_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (f->l[mid] <= r)
            lo = mid;
        else
            hi = mid;
    }
    *la = f->l[lo], *ua = f->u[lo], *lb = f->l[hi], *ub = f->u[hi];
}

double tr_contact_fn_lift(const tr_contact_fn *f, double l)
{
    double q = floor(l / f->L), r = l - q * f->L;
    if (r >= f->L)
        r -= f->L, q += 1.0;
    double la, ua, lb, ub;
    segment(f, r, &la, &ua, &lb, &ub);
    double t = lb > la ? (r - la) / (lb - la) : 0.0;
    return ua + t * (ub - ua) + q * f->L;
}

double tr_contact_fn_eval(const tr_contact_fn *f, double l)
{
    return tr_wrap(tr_contact_fn_lift(f, l), f->L);
}

double tr_contact_fn_slope(const tr_contact_fn *f, double l)
{
    double la, ua, lb, ub;
    segment(f, tr_wrap(l, f->L), &la, &ua, &lb, &ub);
    return lb > la ? (ub - ua) / (lb - la) : 0.0;
}

/* One occupied bin along t = l + partner. */
typedef struct bin_acc {
    size_t bin;         /* its index in [0, nb) */
    size_t count;
    int two;            /* split into two clusters */
    double lo_d, hi_d;  /* mean offsets (lo only when !two: the single cluster) */
    double lo_l, hi_l;  /* mean positions */
} bin_acc;

typedef struct pixel {
    size_t bin;
    double l, d;
} pixel;

static int by_bin_d(const void *a, const void *b)
{
    const pixel *x = a, *y = b;
    if (x->bin != y->bin)
        return (x->bin > y->bin) - (x->bin < y->bin);
    return (x->d > y->d) - (x->d < y->d);
}

/* Mean position and offset of pixels [i, j); positions unwrapped about the
 * first one (a cluster can straddle l = 0). */
static void cluster_mean(const pixel *px, size_t i, size_t j, double L, double *ml, double *md)
{
    double sl = 0.0, sd = 0.0;
    for (size_t k = i; k < j; k++) {
        sl += px[i].l + tr_wrap_signed(px[k].l - px[i].l, L);
        sd += px[k].d;
    }
    *ml = sl / (double)(j - i);
    *md = sd / (double)(j - i);
}

int tr_contact_functions_build(const tr_contact_pair *p, size_t np, double L, double bin,
                               tr_contact_fn *minus, tr_contact_fn *plus, tr_error *err)
{
    memset(minus, 0, sizeof *minus);
    memset(plus, 0, sizeof *plus);
    if (!(L > 0) || !isfinite(L))
        return tr_fail(err, TR_EINVAL, "contact functions need a positive finite length, got %g", L);
    if (np < 2)
        return tr_fail(err, TR_EGEOMETRY, "too few contacts (%zu) for contact functions", np);
    if (!(bin >= TR_CONTACT_BIN_MIN_REL * L) || !(bin <= TR_CONTACT_BIN_MAX_REL * L))
        return tr_fail(err, TR_EINVAL, "contact-function bin %g outside [%g, %g] (L x %g to L x %g)",
                       bin, TR_CONTACT_BIN_MIN_REL * L, TR_CONTACT_BIN_MAX_REL * L,
                       TR_CONTACT_BIN_MIN_REL, TR_CONTACT_BIN_MAX_REL);
    if (np > ((size_t)-1) / (2 * sizeof(pixel)))
        return tr_fail(err, TR_ENOMEM, "too many contacts (%zu)", np);
    /* Pixels are binned along t = l + partner = 2l + d (mod 2L), d the forward
     * offset, not along l: t grows along every monotone branch (dt/dl = 1 +
     * sigma' >= 1), so a bin of width `bin` holds a piece of each branch
     * whose offsets spread by at most `bin`, steep and flat parts alike, and
     * the two partners stay apart by the difference of their offsets.
     * nb <= 2 / TR_CONTACT_BIN_MIN_REL + 1; only occupied bins are stored. */
    size_t nb = (size_t)ceil(2.0 * L / bin), npx = 2 * np;
    pixel *px = malloc(npx * sizeof *px);
    bin_acc *b = malloc(npx * sizeof *b);
    size_t *fwd = malloc(npx * sizeof *fwd), *bwd = malloc(npx * sizeof *bwd);
    double *ml = malloc(npx * sizeof *ml), *mu = malloc(npx * sizeof *mu);
    double *pl = malloc(npx * sizeof *pl), *pu = malloc(npx * sizeof *pu);
    int rc = TR_OK;
    if (!px || !b || !fwd || !bwd || !ml || !mu || !pl || !pu) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory for contact functions");
        goto done;
    }
    for (size_t k = 0; k < np; k++) {
        double a = tr_wrap(p[k].li, L), c = tr_wrap(p[k].lj, L);
        double dac = tr_wrap(c - a, L), dca = tr_wrap(a - c, L);
        /* t / bin < 2L / bin <= nb; rounding can reach nb, which is bin 0 */
        px[2 * k] = (pixel){(size_t)(tr_wrap(2.0 * a + dac, 2.0 * L) / bin) % nb, a, dac};
        px[2 * k + 1] = (pixel){(size_t)(tr_wrap(2.0 * c + dca, 2.0 * L) / bin) % nb, c, dca};
    }
    qsort(px, npx, sizeof *px, by_bin_d);
    /* Two partners of one point are distinct strands: their offsets differ by
     * more than a small fraction of L. */
    double gap_min = 1e-3 * L;
    size_t ntwo = 0, ng = 0;
    for (size_t i = 0; i < npx;) {
        size_t j = i;
        while (j < npx && px[j].bin == px[i].bin)
            j++;
        bin_acc *B = &b[ng++];
        B->bin = px[i].bin;
        B->count = j - i;
        double gmax = 0.0, g2 = 0.0;
        size_t split = j;
        for (size_t k = i + 1; k < j; k++) {
            double g = px[k].d - px[k - 1].d;
            if (g > gmax)
                g2 = gmax, gmax = g, split = k;
            else if (g > g2)
                g2 = g;
        }
        /* two partners: one gap that dominates every gap inside the clusters */
        B->two = gmax > gap_min && gmax > 3.0 * g2 && gmax > 2.0 * bin;
        if (B->two) {
            cluster_mean(px, i, split, L, &B->lo_l, &B->lo_d);
            cluster_mean(px, split, j, L, &B->hi_l, &B->hi_d);
            ntwo++;
        } else {
            cluster_mean(px, i, j, L, &B->lo_l, &B->lo_d);
        }
        i = j;
    }
    if (ntwo == 0) {
        rc = tr_fail(err, TR_EGEOMETRY,
                     "contacts do not form two partner branches (no point has two partners)");
        goto done;
    }
    /* The nearest two-cluster bins after and before each occupied bin, around
     * the circle of bins (the bins are sorted). */
    size_t last = 0;
    for (size_t q = 2 * ng; q-- > 0;) {
        if (b[q % ng].two)
            last = q % ng;
        if (q < ng)
            fwd[q] = last;
    }
    for (size_t q = 0; q < 2 * ng; q++) {
        if (b[q % ng].two)
            last = q % ng;
        if (q >= ng)
            bwd[q - ng] = last;
    }
    size_t nm = 0, npl = 0;
    for (size_t k = 0; k < ng; k++) {
        const bin_acc *B = &b[k];
        if (B->two) {
            ml[nm] = B->lo_l, mu[nm++] = B->lo_l + B->lo_d;
            pl[npl] = B->hi_l, pu[npl++] = B->hi_l + B->hi_d;
            continue;
        }
        /* one cluster: the branch whose offset in the nearest two-cluster bin
         * is closer (offsets change by at most one bin width per bin); the
         * bin ahead wins a tie */
        const bin_acc *F = &b[fwd[k]], *R = &b[bwd[k]];
        size_t df = (F->bin + nb - B->bin) % nb, dr = (B->bin + nb - R->bin) % nb;
        const bin_acc *A = df <= dr ? F : R;
        if (fabs(B->lo_d - A->lo_d) <= fabs(B->lo_d - A->hi_d))
            ml[nm] = B->lo_l, mu[nm++] = B->lo_l + B->lo_d;
        else
            pl[npl] = B->lo_l, pu[npl++] = B->lo_l + B->lo_d;
    }
    if ((rc = tr_contact_fn_from_samples(ml, mu, nm, L, minus, err)) != TR_OK)
        goto done;
    if ((rc = tr_contact_fn_from_samples(pl, pu, npl, L, plus, err)) != TR_OK)
        tr_contact_fn_free(minus);
done:
    free(px), free(b), free(fwd), free(bwd), free(ml), free(mu), free(pl), free(pu);
    return rc;
}

static double lifted_power(const tr_contact_fn *f, int power, double l)
{
    for (int k = 0; k < power; k++)
        l = tr_contact_fn_lift(f, l);
    return l;
}

static double gfun(const tr_contact_fn *f, int power, double l)
{
    return tr_wrap_signed(lifted_power(f, power, l) - l, f->L);
}

int tr_power_fixed_points(const tr_contact_fn *f, int power, size_t grid, tr_fixed_point **fp,
                          size_t *nfp, tr_cycle **cyc, size_t *ncyc, tr_error *err)
{
    *fp = NULL, *cyc = NULL, *nfp = 0, *ncyc = 0;
    if (power < 1 || power > TR_CONTACT_POWER_MAX)
        return tr_fail(err, TR_EINVAL, "functional power %d outside [1, %d]", power, TR_CONTACT_POWER_MAX);
    if (grid < 8 || grid > ((size_t)1 << 40))
        return tr_fail(err, TR_EINVAL, "fixed points need a grid of 8 to 2^40 points, got %zu", grid);
    if (!f || f->n < 2 || !(f->L > 0) || !isfinite(f->L))
        return tr_fail(err, TR_EINVAL, "fixed points need a contact function of >= 2 knots and a positive period");
    double L = f->L;
    size_t cap = 64, n = 0;
    tr_fixed_point *pts = malloc(cap * sizeof *pts);
    if (!pts)
        return tr_fail(err, TR_ENOMEM, "out of memory for fixed points");
    double x0 = 0.0, g0 = gfun(f, power, 0.0);
    for (size_t j = 1; j <= grid; j++) {
        double x1 = (double)j * L / (double)grid, g1 = gfun(f, power, x1);
        /* A sign change with both values small is a crossing of the diagonal;
         * one where g wraps from +L/2 to -L/2 is not. */
        if (((g0 <= 0 && g1 > 0) || (g0 >= 0 && g1 < 0)) && fabs(g0) < L / 4 && fabs(g1) < L / 4) {
            double a = x0, b = x1, ga = g0;
            for (int it = 0; it < 100 && b - a > 1e-15 * L; it++) {
                double m = 0.5 * (a + b), gm = gfun(f, power, m);
                if ((ga <= 0) == (gm <= 0))
                    a = m, ga = gm;
                else
                    b = m;
            }
            if (n == cap) {
                cap *= 2;
                tr_fixed_point *t = realloc(pts, cap * sizeof *pts);
                if (!t) {
                    free(pts);
                    return tr_fail(err, TR_ENOMEM, "out of memory for fixed points");
                }
                pts = t;
            }
            double l = tr_wrap(0.5 * (a + b), L), slope = 1.0, y = l;
            for (int k = 0; k < power; k++) {
                slope *= tr_contact_fn_slope(f, y);
                y = tr_contact_fn_eval(f, y);
            }
            pts[n++] = (tr_fixed_point){l, slope, fabs(slope) < 1.0, -1, -1};
        }
        x0 = x1, g0 = g1;
    }
    /* Orbits under f: each fixed point of f^power maps to another one. */
    tr_cycle *cs = malloc((n ? n : 1) * sizeof *cs);
    if (!cs) {
        free(pts);
        return tr_fail(err, TR_ENOMEM, "out of memory for cycles");
    }
    size_t nc = 0;
    double tol = 1e-3 * L;
    for (size_t i = 0; i < n; i++) {
        if (pts[i].cycle >= 0)
            continue;
        int id = (int)nc;
        size_t cur = i;
        int order = 0, stable_all = 1, unstable_all = 1;
        size_t first = i;
        while (cur < n && pts[cur].cycle < 0) {
            pts[cur].cycle = id;
            pts[cur].order = order++;
            stable_all &= pts[cur].stable;
            unstable_all &= !pts[cur].stable;
            if (pts[cur].l < pts[first].l)
                first = cur;
            double y = tr_contact_fn_eval(f, pts[cur].l);
            size_t best = n;
            double bd = tol;
            for (size_t k = 0; k < n; k++) {
                double d = fabs(tr_wrap_signed(pts[k].l - y, L));
                if (d < bd)
                    bd = d, best = k;
            }
            cur = best;
        }
        /* renumber so the member with the smallest l is first */
        int shift = pts[first].order;
        for (size_t k = 0; k < n; k++)
            if (pts[k].cycle == id)
                pts[k].order = (pts[k].order - shift + order) % order;
        cs[nc++] = (tr_cycle){order, stable_all ? 1 : unstable_all ? 0 : -1, first};
    }
    *fp = pts, *nfp = n, *cyc = cs, *ncyc = nc;
    return TR_OK;
}
