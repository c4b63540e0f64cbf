/* This file contains the pieces of a tight clasp's rope found on its curvature profile
 * (clasp_anatomy.h). */
#include "analysis/clasp_anatomy.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/profile_features.h"

const char *const tr_clasp_piece_names[TR_CLASP_NPIECES] = {"E", "S", "D1", "G", "D2", "K"};

/* The kink is a plateau as analyze reads them on closed knots (its defaults,
 * docs/physics.md 3.4): arcs at kappa >= 1 - 0.02 holding one at 1 - 1e-4
 * (a clasp of 100 vertices per rope has two kink arcs). */
#define KINK_CORE (1.0 - 1e-4)
#define KINK_EDGE (1.0 - 0.02)
/* The shoulder: arcs within 0.1 of 1/2 whose neighbours average to 1/2
 * within 0.01, at least 4 of them. A tight polygon alternates by up to
 * +-0.02 there (100 vertices per rope: 0.482, 0.518), the pair averages stay
 * at 1/2 to 1e-4; the Gehring piece next to it averages 0.45-0.48. */
#define SHOULDER_ARC_TOL 0.1
#define SHOULDER_PAIR_TOL 0.01
#define SHOULDER_MIN_ARCS 4
/* A deep shows as a dip: arcs below 3/4 of the curvature around them. A
 * straight piece of width d inside one cell of length e lowers that arc's
 * curvature by the fraction d/e, so a quarter edge shows (half an edge split
 * over two cells); the engine's 2 x 1000 clasp has its D1 as two arcs at
 * 0.36 and 0.33 on one rope, one at 0.24 on the other; the Gehring piece's
 * own period-2 wave reaches 0.40 beside 0.47. An arc below a tenth of the
 * level is straight (REFERENCE.md 6.3: kappa < 0.05 beside the shoulder's
 * 1/2). A deep is resolved when at least two edges wide with a straight arc
 * on it: then its width is measured to +-35 %. */
#define DIP_FRACTION 0.75
#define STRAIGHT_FRACTION 0.1
#define RESOLVED_EDGES 2.0
/* The Gehring piece's curvature at either end: a line through the pair
 * averages of its four arcs nearest the boundary (the one-sided fits of the
 * jump measurements, profile_features.h), extrapolated to it. Not their
 * quadratic: G rises into K, and over eight arcs of a coarse rope (100 per
 * rope: 0.43 .. 0.57 in 0.56 of length) a quadratic overshoots by 0.2. The
 * fit starts at the boundary's cell edge (0.4 e: the next arc's centre is
 * e/2 away), or one arc later beside a dip, whose straight piece reaches
 * into the next cell unless it ends on a cell's edge. */
#define SIDE_AT_EDGE 0.4
#define SIDE_PAST_ARC 1.4
#define SIDE_SPAN_EDGES 4.0
/* Each boundary is estimated over windows of 1, 2 and 3 arcs beyond the
 * transition's, at each level and at each level moved by its standard error. */
#define WINDOW_MAX 3

/* One half of the rope seen from its free end: view arc i is profile arc i
 * (half 0) or n - 1 - i (half 1); positions s run from that end. */
typedef struct half_view {
    const tr_arc_profile *p;
    const double *cl, *cr; /* cells in rope coordinates: between the midpoints of an arc's edges */
    int rev;
    size_t m;              /* arcs on this side of the tip, the tip's own included */
} half_view;

typedef struct level {
    double v, se;
} level;

static size_t vk(const half_view *v, size_t i) { return v->rev ? v->p->n - 1 - i : i; }
static double vkap(const half_view *v, size_t i) { return v->p->kappa[vk(v, i)]; }
/* the turning angle of arc i: curvature times the inscribed arc's length */
static double vth(const half_view *v, size_t i) { return v->p->kappa[vk(v, i)] * v->p->dl[vk(v, i)]; }
static double vs(const half_view *v, size_t i)
{
    return v->rev ? v->p->L - v->p->pos[vk(v, i)] : v->p->pos[vk(v, i)];
}
static double va(const half_view *v, size_t i) { return v->rev ? v->p->L - v->cr[vk(v, i)] : v->cl[vk(v, i)]; }
static double vb(const half_view *v, size_t i) { return v->rev ? v->p->L - v->cl[vk(v, i)] : v->cr[vk(v, i)]; }
static double to_rope(const half_view *v, double s) { return v->rev ? v->p->L - s : s; }

/* The curvature next to view position s, on the side toward the tip (1) or
 * toward the free end (0), from skip edges on: a line through the pair
 * averages over four edges, extrapolated to s; where that has too few
 * points, the mean of the next four arcs on that side. */
static level side_level(const half_view *v, double s, int toward_tip, double skip, double e)
{
    level l;
    int side = toward_tip ? !v->rev : v->rev; /* rope coordinates run the other way on half 1 */
    double w = skip * e;
    if (tr_profile_kappa_side(v->p, to_rope(v, s), side, w, w + SIDE_SPAN_EDGES * e, 0, &l.v, &l.se, NULL) == TR_OK &&
        isfinite(l.v))
        return l;
    double sum = 0.0, sum2 = 0.0;
    size_t c = 0;
    for (size_t i = 0; i < v->m && c < 4; i++) {
        size_t j = toward_tip ? i : v->m - 1 - i;
        double d = toward_tip ? vs(v, j) - s : s - vs(v, j);
        if (d >= w) {
            double k = vkap(v, j);
            sum += k, sum2 += k * k, c++;
        }
    }
    l.v = c ? sum / (double)c : NAN;
    l.se = c > 1 ? sqrt(fmax(0.0, sum2 / (double)c - l.v * l.v) / (double)(c - 1)) : 0.0;
    return l;
}

/* The sharp step from level a to level b that turns the rope over the cells
 * of arcs lo..hi, [A, B], as much as those arcs do:
 * a (x - A) + b (B - x) = sum of their turning angles. */
static double sharp_step(const half_view *v, size_t lo, size_t hi, double a, double b)
{
    double A = va(v, lo), B = vb(v, hi), th = 0.0;
    for (size_t i = lo; i <= hi; i++)
        th += vth(v, i);
    double x = (b * B - a * A - th) / (b - a);
    return fmin(fmax(x, A), B);
}

typedef struct estimate {
    double x, spread; /* the windows' mean at the measured levels; half the range over every variant */
} estimate;

static void widen(double *lo, double *hi, double x)
{
    *lo = fmin(*lo, x);
    *hi = fmax(*hi, x);
}

/* A step from level a to level b at view arc first_b (the first arc at b),
 * its windows kept within arcs lo_min..hi_max (the neighbouring transitions). */
static estimate step_between(const half_view *v, size_t first_b, level a, level b, size_t lo_min, size_t hi_max)
{
    double sum = 0.0, mn = INFINITY, mx = -INFINITY;
    const double da[5] = {0, -a.se, a.se, 0, 0}, db[5] = {0, 0, 0, -b.se, b.se};
    for (size_t j = 1; j <= WINDOW_MAX; j++) {
        size_t lo = first_b >= lo_min + 1 + j ? first_b - 1 - j : lo_min;
        size_t hi = first_b + j <= hi_max ? first_b + j : hi_max;
        for (int q = 0; q < 5; q++) {
            double x = sharp_step(v, lo, hi, a.v + da[q], b.v + db[q]);
            widen(&mn, &mx, x);
            if (q == 0)
                sum += x;
        }
    }
    return (estimate){sum / WINDOW_MAX, 0.5 * (mx - mn)};
}

/* A straight piece seen as the dip c0..c1 between level a (toward the end)
 * and level b (toward the tip): its width is the turning the arcs around it
 * lack, sum (cell - theta / ref) with ref the level on each arc's side, and
 * its centre the first moment of that lack over the dip and one arc either
 * side. Windows and levels varied as in step_between. */
static void dip_between(const half_view *v, size_t c0, size_t c1, level a, level b, size_t lo_min, size_t hi_max,
                        estimate *width, estimate *centre)
{
    double mid = 0.5 * (va(v, c0) + vb(v, c1));
    double wsum = 0.0, wmn = INFINITY, wmx = -INFINITY, csum = 0.0, cmn = INFINITY, cmx = -INFINITY;
    const double da[5] = {0, -a.se, a.se, 0, 0}, db[5] = {0, 0, 0, -b.se, b.se};
    for (size_t j = 1; j <= WINDOW_MAX; j++) {
        size_t lo = c0 >= lo_min + j ? c0 - j : lo_min;
        size_t hi = c1 + j <= hi_max ? c1 + j : hi_max;
        for (int q = 0; q < 5; q++) {
            double la = a.v + da[q], lb = b.v + db[q], d = 0.0, m0 = 0.0, m1 = 0.0;
            for (size_t i = lo; i <= hi; i++) {
                double s = vs(v, i);
                double ref = i < c0 || (i <= c1 && s < mid) ? la : i > c1 || s > mid ? lb : 0.5 * (la + lb);
                double lack = (vb(v, i) - va(v, i)) - vth(v, i) / ref;
                d += lack;
                if (i + 1 >= c0 && i <= c1 + 1 && lack > 0)
                    m0 += lack, m1 += lack * s;
            }
            double c = m0 > 0 ? m1 / m0 : mid;
            widen(&wmn, &wmx, d);
            widen(&cmn, &cmx, c);
            if (q == 0)
                wsum += d, csum += c;
        }
    }
    *width = (estimate){wsum / WINDOW_MAX, 0.5 * (wmx - wmn)};
    *centre = (estimate){csum / WINDOW_MAX, 0.5 * (cmx - cmn)};
}

/* Curvature over the arcs whose cells lie wholly on the piece (a
 * straddling arc is half one piece, half the next); over the arcs centred on
 * it when none does (a dip narrower than an edge). */
static void piece_stats(const half_view *v, tr_clasp_piece *pc)
{
    for (int whole = 1; whole >= 0; whole--) {
        double mn = INFINITY, mx = -INFINITY, sum = 0.0;
        size_t c = 0;
        for (size_t i = 0; i < v->m; i++) {
            int in = whole ? va(v, i) >= pc->from && vb(v, i) <= pc->to : vs(v, i) >= pc->from && vs(v, i) <= pc->to;
            if (in) {
                double k = vkap(v, i);
                mn = fmin(mn, k), mx = fmax(mx, k), sum += k, c++;
            }
        }
        pc->arcs = c;
        pc->kappa_min = c ? mn : NAN;
        pc->kappa_max = c ? mx : NAN;
        pc->kappa_mean = c ? sum / (double)c : NAN;
        if (c)
            return;
    }
}

static void set_piece(tr_clasp_piece *pc, double from, double from_err, double to, double to_err)
{
    pc->status = TR_PIECE_RESOLVED;
    pc->from = from, pc->from_err = from_err;
    pc->to = to, pc->to_err = to_err;
    pc->width = to - from;
    pc->err = hypot(from_err, to_err);
    pc->why[0] = '\0';
}

static void unseen(tr_clasp_piece *pc, const char *between, const char *level, double e, double published)
{
    memset(pc, 0, sizeof *pc);
    pc->status = TR_PIECE_UNSEEN;
    pc->from = pc->to = pc->width = pc->err = pc->from_err = pc->to_err = NAN;
    pc->kappa_min = pc->kappa_mean = pc->kappa_max = NAN;
    snprintf(pc->why, sizeof pc->why,
             "no dip between %s (no arc below 3/4 of %s): a straight piece there, if any, is narrower than about "
             "half an edge (e = %.3g; two edges across %.2g need e <= %.2g)",
             between, level, e, published, published / RESOLVED_EDGES);
}

/* The deep c0..c1 measured as a dip: sets pc and returns its extent. */
static void deep_piece(const half_view *v, size_t c0, size_t c1, level a, level b, size_t lo_min, size_t hi_max,
                       double e, tr_clasp_piece *pc)
{
    estimate w, c;
    dip_between(v, c0, c1, a, b, lo_min, hi_max, &w, &c);
    double berr = hypot(hypot(0.5 * e, c.spread), 0.5 * w.spread);
    set_piece(pc, c.x - 0.5 * w.x, berr, c.x + 0.5 * w.x, berr);
    pc->width = w.x;
    pc->err = hypot(e / sqrt(2.0), w.spread); /* two boundaries, each +- e/2 */
    size_t straight = 0;
    double kmin = INFINITY, kmax = -INFINITY, ksum = 0.0;
    for (size_t i = c0; i <= c1; i++) {
        kmin = fmin(kmin, vkap(v, i)), kmax = fmax(kmax, vkap(v, i)), ksum += vkap(v, i);
        straight += vkap(v, i) < STRAIGHT_FRACTION * fmin(a.v, b.v);
    }
    pc->arcs = c1 - c0 + 1;
    pc->kappa_min = kmin, pc->kappa_max = kmax, pc->kappa_mean = ksum / (double)pc->arcs;
    if (!(w.x >= RESOLVED_EDGES * e && straight >= 1)) {
        pc->status = TR_PIECE_DIP;
        snprintf(pc->why, sizeof pc->why,
                 "a dip of %zu arc%s (min kappa %.3g), narrower than %g edges (e = %.3g): the width is the turning "
                 "the dip lacks",
                 c1 - c0 + 1, c1 > c0 ? "s" : "", kmin, RESOLVED_EDGES, e);
    }
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median curvature of view arcs [lo, hi); NAN when empty or out of memory
 * (then no dip is looked for). */
static double median_kappa(const half_view *v, size_t lo, size_t hi)
{
    if (hi <= lo)
        return NAN;
    double *k = malloc((hi - lo) * sizeof *k);
    if (!k)
        return NAN;
    for (size_t i = lo; i < hi; i++)
        k[i - lo] = vkap(v, i);
    qsort(k, hi - lo, sizeof *k, by_value);
    double m = k[(hi - lo) / 2];
    free(k);
    return m;
}

/* The first run of shoulder arcs in view arcs [0, end): *i0..*i1. */
static int find_shoulder(const half_view *v, size_t end, size_t *i0, size_t *i1)
{
    for (size_t i = 0; i + 1 < end; i++) {
        size_t j = i;
        while (j + 1 < end && fabs(vkap(v, j) - 0.5) <= SHOULDER_ARC_TOL &&
               fabs(vkap(v, j + 1) - 0.5) <= SHOULDER_ARC_TOL &&
               fabs(0.5 * (vkap(v, j) + vkap(v, j + 1)) - 0.5) <= SHOULDER_PAIR_TOL)
            j++;
        if (j + 1 - i >= SHOULDER_MIN_ARCS) {
            *i0 = i, *i1 = j;
            return 1;
        }
        if (j > i)
            i = j;
    }
    return 0;
}

/* One half: the pieces from the free end up to K's first boundary (K's far
 * end, the tip, is set once both halves are known). iK: the first kink arc. */
static int read_half(const half_view *v, size_t iK, level kink, double e, tr_clasp_half *h, double *shoulder_sum,
                     double *pair_dev, double *alt, size_t *npairs, char *why, size_t whylen)
{
    size_t i0, i1;
    if (!find_shoulder(v, iK, &i0, &i1)) {
        snprintf(why, whylen, "no shoulder on the half from vertex %zu: no run of %d arcs at curvature 1/2 "
                              "(pair averages within %g) before the kink", h->end_vertex, SHOULDER_MIN_ARCS,
                 SHOULDER_PAIR_TOL);
        return 0;
    }
    /* the shoulder's level: the mean of its pair averages, which the
     * period-2 alternation leaves alone */
    double sum = 0.0, sum2 = 0.0;
    size_t np = i1 - i0;
    for (size_t i = i0; i < i1; i++) {
        double pa = 0.5 * (vkap(v, i) + vkap(v, i + 1));
        sum += pa, sum2 += pa * pa;
        *pair_dev = fmax(*pair_dev, fabs(pa - 0.5));
    }
    for (size_t i = i0; i <= i1; i++)
        *alt = fmax(*alt, fabs(vkap(v, i) - 0.5));
    double mean = sum / (double)np;
    level S = {mean, np > 1 ? sqrt(fmax(0.0, sum2 / (double)np - mean * mean) / (double)(np - 1)) : 0.0};
    *shoulder_sum += sum;
    *npairs += np;

    tr_clasp_piece *pc = h->piece;
    double half_e = 0.5 * e;
    /* E | S: a step from straight (a free rope is straight) to 1/2 */
    estimate es = step_between(v, i0, (level){0.0, 0.0}, S, 0, i1);
    set_piece(&pc[TR_CLASP_E], 0.0, 0.0, es.x, hypot(half_e, es.spread));

    /* S | D1 | G: a dip within three arcs of the shoulder's end */
    size_t c0 = iK, g0;
    for (size_t i = i1 + 1; i < iK && i <= i1 + 3; i++)
        if (vkap(v, i) < DIP_FRACTION * S.v) {
            c0 = i;
            break;
        }
    if (c0 < iK) {
        size_t c1 = c0;
        while (c1 + 1 < iK && vkap(v, c1 + 1) < DIP_FRACTION * S.v)
            c1++;
        level G = side_level(v, vb(v, c1), 1, SIDE_PAST_ARC, e);
        deep_piece(v, c0, c1, S, G, i0, iK - 1, e, &pc[TR_CLASP_D1]);
        g0 = c1 + 1;
    } else {
        unseen(&pc[TR_CLASP_D1], "S and G", "the shoulder's curvature", e, TR_CLASP_D1_STAROSTIN);
        g0 = i1 + 1;
    }
    /* G | D2 | K: a dip ending within three arcs of the kink, below 3/4 of
     * the median curvature of G (G's own level near K is what the dip would
     * hide) */
    double gmed = median_kappa(v, g0, iK);
    size_t d1 = iK, d0 = iK;
    for (size_t i = iK, skipped = 0; i > g0 && skipped < 3; skipped++)
        if (vkap(v, --i) < DIP_FRACTION * gmed) {
            d1 = d0 = i;
            break;
        }
    while (d1 < iK && d0 > g0 && vkap(v, d0 - 1) < DIP_FRACTION * gmed)
        d0--;
    double kfrom, kfrom_err;
    if (d1 < iK) {
        level G = side_level(v, va(v, d0), 0, SIDE_PAST_ARC, e);
        deep_piece(v, d0, d1, G, kink, g0, v->m - 1, e, &pc[TR_CLASP_D2]);
        kfrom = pc[TR_CLASP_D2].to, kfrom_err = pc[TR_CLASP_D2].to_err;
    } else {
        unseen(&pc[TR_CLASP_D2], "G and K", "G's median curvature", e, TR_CLASP_D2_STAROSTIN);
        /* the arc before K belongs to the step when it is more than halfway
         * from its predecessor's curvature to K's (2 x 2000: 0.62, 0.90, 1) */
        size_t t = iK;
        if (iK >= g0 + 2 && vkap(v, iK - 1) - vkap(v, iK - 2) > 0.5 * (kink.v - vkap(v, iK - 2)))
            t = iK - 1;
        level G = side_level(v, va(v, t), 0, SIDE_AT_EDGE, e);
        estimate gk = step_between(v, iK, G, kink, g0, v->m - 1);
        kfrom = gk.x, kfrom_err = hypot(half_e, gk.spread);
    }
    /* S and G between their neighbours; without a dip the shoulder's last
     * arc at 1/2 ends it, to an edge */
    const tr_clasp_piece *D1 = &pc[TR_CLASP_D1], *D2 = &pc[TR_CLASP_D2];
    double s_to = D1->status != TR_PIECE_UNSEEN ? D1->from : vb(v, i1);
    double s_to_err = D1->status != TR_PIECE_UNSEEN ? D1->from_err : e;
    double g_from = D1->status != TR_PIECE_UNSEEN ? D1->to : s_to;
    double g_from_err = D1->status != TR_PIECE_UNSEEN ? D1->to_err : s_to_err;
    set_piece(&pc[TR_CLASP_S], pc[TR_CLASP_E].to, pc[TR_CLASP_E].to_err, s_to, s_to_err);
    double g_to = D2->status != TR_PIECE_UNSEEN ? D2->from : kfrom;
    double g_to_err = D2->status != TR_PIECE_UNSEEN ? D2->from_err : kfrom_err;
    set_piece(&pc[TR_CLASP_G], g_from, g_from_err, g_to, g_to_err);
    set_piece(&pc[TR_CLASP_K], kfrom, kfrom_err, NAN, NAN);
    double order[6] = {pc[TR_CLASP_E].to, s_to, g_from, g_to, kfrom, vb(v, v->m - 1)};
    for (int q = 0; q < 5; q++)
        if (!(order[q] <= order[q + 1]) || (q != 1 && q != 3 && !(order[q] < order[q + 1]))) {
            snprintf(why, whylen, "pieces out of order on the half from vertex %zu: E|S %.6g, S end %.6g, G %.6g to "
                                  "%.6g, K from %.6g", h->end_vertex, order[0], order[1], order[2], order[3],
                     order[4]);
            return 0;
        }
    return 1;
}

int tr_clasp_rope_anatomy(const tr_arc_profile *p, tr_clasp_rope *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (p->closed)
        return tr_fail(err, TR_EINVAL, "the clasp's anatomy is read on an open rope");
    size_t n = p->n;
    out->n = n + 2;
    out->L = p->L;
    out->e = p->L / (double)(n + 1);
    out->tip = out->tip_err = out->kink_width = out->kink_width_err = NAN;
    if (n < 8) {
        snprintf(out->why, sizeof out->why, "too few vertices (%zu) for a clasp's pieces", n + 2);
        return TR_OK;
    }
    tr_plateau *pl;
    size_t npl;
    int rc = tr_profile_find_plateaus_margin(p, KINK_CORE, KINK_EDGE, 1, &pl, &npl, err);
    if (rc != TR_OK)
        return rc;
    /* the kink: the run nearest the middle (the profile is open: a run
     * through index 0 would need both ends bent, and is not one) */
    size_t best = npl;
    double bd = INFINITY;
    for (size_t i = 0; i < npl; i++) {
        double d = fabs(0.5 * (p->pos[pl[i].first] + p->pos[pl[i].last]) - 0.5 * p->L);
        if (pl[i].first <= pl[i].last && d < bd)
            bd = d, best = i;
    }
    if (best == npl) {
        double kmax = 0.0;
        for (size_t k = 0; k < n; k++)
            kmax = fmax(kmax, p->kappa[k]);
        snprintf(out->why, sizeof out->why, "no kink: the curvature reaches %.6g, not %g (not a tight clasp)", kmax,
                 KINK_CORE);
        free(pl);
        return TR_OK;
    }
    size_t kf = pl[best].first, kl = pl[best].last;
    free(pl);
    double sum = 0.0, sum2 = 0.0;
    out->kink_min = INFINITY, out->kink_max = -INFINITY;
    for (size_t k = kf; k <= kl; k++) {
        sum += p->kappa[k], sum2 += p->kappa[k] * p->kappa[k];
        out->kink_min = fmin(out->kink_min, p->kappa[k]);
        out->kink_max = fmax(out->kink_max, p->kappa[k]);
    }
    size_t nk = kl - kf + 1;
    out->kink_kappa = sum / (double)nk;
    level kink = {out->kink_kappa,
                  nk > 1 ? sqrt(fmax(0.0, sum2 / (double)nk - out->kink_kappa * out->kink_kappa) / (double)(nk - 1))
                         : 0.0};
    double tip0 = 0.5 * (p->pos[kf] + p->pos[kl]);

    double *cl = malloc(n * sizeof *cl), *cr = malloc(n * sizeof *cr);
    if (!cl || !cr) {
        free(cl), free(cr);
        return tr_fail(err, TR_ENOMEM, "out of memory for the clasp's anatomy");
    }
    for (size_t k = 0; k < n; k++) {
        cl[k] = k ? 0.5 * (p->pos[k - 1] + p->pos[k]) : 0.5 * p->pos[0];
        cr[k] = k + 1 < n ? 0.5 * (p->pos[k] + p->pos[k + 1]) : 0.5 * (p->pos[k] + p->L);
    }
    double shoulder = 0.0;
    size_t npairs = 0;
    int ok = 1;
    for (int h = 0; h < 2 && ok; h++) {
        half_view v = {p, cl, cr, h, 0};
        while (v.m < n && (h ? p->pos[n - 1 - v.m] >= tip0 : p->pos[v.m] <= tip0))
            v.m++;
        size_t iK = h ? n - 1 - kl : kf;
        out->half[h].end_vertex = h ? n + 1 : 0;
        ok = read_half(&v, iK, kink, out->e, &out->half[h], &shoulder, &out->shoulder_pair_dev,
                       &out->shoulder_alt, &npairs, out->why, sizeof out->why);
    }
    if (ok) {
        /* the tip: halfway between the kink's two boundaries */
        double k0 = out->half[0].piece[TR_CLASP_K].from, k1 = p->L - out->half[1].piece[TR_CLASP_K].from;
        double e0 = out->half[0].piece[TR_CLASP_K].from_err, e1 = out->half[1].piece[TR_CLASP_K].from_err;
        out->tip = 0.5 * (k0 + k1);
        out->kink_width = k1 - k0;
        out->kink_width_err = hypot(e0, e1);
        out->tip_err = 0.5 * out->kink_width_err;
        out->shoulder_kappa = shoulder / (double)npairs;
        for (int h = 0; h < 2; h++) {
            tr_clasp_half *hf = &out->half[h];
            hf->length = h ? p->L - out->tip : out->tip;
            tr_clasp_piece *K = &hf->piece[TR_CLASP_K];
            K->to = hf->length, K->to_err = out->tip_err;
            K->width = 0.5 * out->kink_width, K->err = 0.5 * out->kink_width_err;
            half_view v = {p, cl, cr, h, n};
            for (int q = 0; q < TR_CLASP_NPIECES; q++)
                if (hf->piece[q].status == TR_PIECE_RESOLVED)
                    piece_stats(&v, &hf->piece[q]);
        }
        if (!(out->kink_width > 0)) {
            snprintf(out->why, sizeof out->why, "the kink's boundaries cross (%.6g, %.6g)", k0, k1);
            ok = 0;
        }
    }
    free(cl), free(cr);
    out->found = ok;
    return TR_OK;
}
