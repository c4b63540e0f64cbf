/* This file contains the coarse level's multipliers carried to the curve refined from it (newton.h coarse). */
#include "solver/newton_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "segment_distance.h"
#include "util/vec3.h"

/* Why: a refined level that starts from the warm start's least-squares
 * multipliers has to find again the loads the coarse solve ended with; on
 * a long stretch held by MinRad alone (the clasp's tip K, about 115
 * vertices a rope at 2 x 3200) those grow like the square of its length in
 * edges, the least squares' damping takes them away, and the first steps
 * bend K past MinRad (bench/notes/2026-11-29-clasp-6400-cold-start.md).
 * The coarse solve's own multipliers are the continuum's loads sampled at
 * the coarse edges; carried along arclength and rescaled to the finer
 * edges they are the same loads:
 *  - an edge row's multiplier is the tension, a force: the same;
 *  - a MinRad row g = (c(l) - |w|^2) / S (newton_rows.c) with
 *    w ~ l^2 kappa n pushes vertex j by (2 / S) Delta^2(lambda w)_j, which
 *    must be l times a force density: lambda / S scales as l^-3;
 *  - a strut's multiplier is its force: it goes to the finer pair whose
 *    pieces hold the coarse pair's closest points, so it acts where it did.
 * What does not carry over is the coarse polygon's own shape: with the
 * linear refinement the finer vertices' curvature alternates on K (3.7 %
 * over MinRad), which times K's large multipliers is an unbalanced force
 * of 150 tensions a vertex; on arcs (refine_arcs.h) it is uniform, and the
 * unbalance is left at the tip's point contact, a kink of the MinRad
 * multipliers that the coarse chain can only place at a vertex (59
 * tensions a vertex at 2 x 6400), which the first full steps take away
 * (bench/notes/2026-11-29-clasp-prolongation.md). */

/* cumulative arclength of component k at positions x (3 per vertex), as a
 * fraction of the whole; t has tr_comp_nv + 1 entries (the last 1: the
 * wrap edge's end on a closed component, the last vertex on an open one) */
static void arclength(const tr_curve *shape, const size_t *start, int k, const double *x, double *t)
{
    size_t st = start[k], n = start[k + 1] - start[k];
    t[0] = 0.0;
    for (size_t j = 1; j < n; j++)
        t[j] = t[j - 1] + sqrt(v3_dist2(x + 3 * (st + j - 1), x + 3 * (st + j)));
    double total = t[n - 1];
    if (shape->closed[k]) {
        total += sqrt(v3_dist2(x + 3 * (st + n - 1), x + 3 * st));
        t[n] = total;
    } else
        t[n] = total;
    for (size_t j = 0; j <= n; j++)
        t[j] /= total;
}

/* the coarse edge (by its place in its component) holding fraction u, and
 * where along it (0..1) */
static size_t locate(const double *tc, size_t ne, double u, double *frac)
{
    size_t lo = 0, hi = ne; /* tc[lo] <= u < tc[hi] */
    if (u <= 0.0) {
        *frac = 0.0;
        return 0;
    }
    if (u >= tc[ne]) {
        *frac = 1.0;
        return ne - 1;
    }
    while (hi - lo > 1) {
        size_t m = (lo + hi) / 2;
        if (tc[m] <= u)
            lo = m;
        else
            hi = m;
    }
    double w = tc[lo + 1] - tc[lo];
    *frac = w > 0.0 ? (u - tc[lo]) / w : 0.0;
    return lo;
}

int tr_newton_i_prolong(solver *s, const tr_newton_state *r, const double *y, tr_error *err)
{
    int nc = s->nc;
    if (r->ncomp != nc)
        return tr_fail(err, TR_EINVAL, "newton: the coarse state has %d components, the curve %d", r->ncomp, nc);
    size_t *cstart = malloc(((size_t)nc + 1) * sizeof *cstart);
    if (!cstart)
        return tr_fail(err, TR_ENOMEM, "out of memory (coarse multipliers)");
    cstart[0] = 0;
    for (int k = 0; k < nc; k++)
        cstart[k + 1] = cstart[k] + r->comp_nv[k];
    if (cstart[nc] != r->nv) {
        free(cstart);
        return tr_fail(err, TR_EINVAL, "newton: the coarse state's components do not add up to its vertices");
    }
    size_t nv = s->nv;
    double *tc = malloc((r->nv + (size_t)nc) * sizeof *tc), *tf = malloc((nv + (size_t)nc) * sizeof *tf);
    double *lam_m = malloc(nv * sizeof *lam_m), *lam_e = malloc(nv * sizeof *lam_e);
    int rc = TR_OK;
    if (!tc || !tf || !lam_m || !lam_e) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory (coarse multipliers)");
        goto done;
    }
    double worst_gap = 0.0;
    for (int k = 0; k < nc; k++) {
        size_t ncv = r->comp_nv[k], nfv = tr_comp_nv(&s->w, k), sc = cstart[k], sf = s->w.start[k];
        int closed = s->w.closed[k];
        size_t nce = closed ? ncv : ncv - 1, nfe = closed ? nfv : nfv - 1;
        if (ncv < 3 || nfv < ncv) {
            rc = tr_fail(err, TR_EINVAL, "newton: component %d has %zu vertices, its coarse state %zu: not a refinement",
                         k + 1, nfv, ncv);
            goto done;
        }
        double *tck = tc + sc + (size_t)k, *tfk = tf + sf + (size_t)k;
        arclength(&s->w, cstart, k, r->y, tck);
        arclength(&s->w, s->w.start, k, y, tfk);
        double lc = r->y[3 * r->nv + (size_t)k], lf = y[3 * nv + (size_t)k];
        /* the MinRad rows' lambda / S scales as l^-3 (above) */
        double fm = (s->scale_m[k] / r->scale_m[k]) * pow(lc / lf, 3.0);
        for (size_t j = 0; j < nfv; j++) {
            double frac;
            size_t e = locate(tck, nce, tfk[j], &frac);
            size_t a = sc + e, b = sc + (e + 1 < ncv ? e + 1 : 0);
            /* the fine vertex on the coarse polygon: the two must be the
             * same curve (the refinement keeps the start vertex in place) */
            double p[3];
            for (int d = 0; d < 3; d++)
                p[d] = (1.0 - frac) * r->y[3 * a + d] + frac * r->y[3 * b + d];
            double gap = sqrt(v3_dist2(p, y + 3 * (sf + j))) / lc;
            worst_gap = isnan(gap) ? INFINITY : fmax(worst_gap, gap);
            lam_m[sf + j] = fm * ((1.0 - frac) * r->lam_m[a] + frac * r->lam_m[b]);
            if (j < nfe) {
                double mid = 0.5 * (tfk[j] + tfk[j + 1]);
                size_t em = locate(tck, nce, mid, &frac);
                lam_e[sf + j] = r->lam_e[sc + em];
            } else {
                lam_e[sf + j] = s->lam_e[sf + j];
            }
        }
    }
    /* a coarse polygon a few of its edges away from the curve: not the
     * curve this one was refined from */
    if (!(worst_gap < 2.0)) {
        rc = tr_fail(err, TR_EINVAL,
                     "newton: the curve is %.3g coarse edges away from the coarse state's: not its refinement", worst_gap);
        goto done;
    }
    memcpy(s->lam_m, lam_m, nv * sizeof *lam_m);
    memcpy(s->lam_e, lam_e, nv * sizeof *lam_e);
    /* the struts: each coarse pair's force where it acts, on the finer
     * pair of the pieces that hold its closest points (sharing it among
     * all the pieces of its two edges moved forces of 25 times a vertex's
     * tension by half an edge: an unbalanced force of 28 at 2 x 3300) */
    for (size_t q = 0; q < s->nsp; q++)
        s->sp[q].lam = 0.0;
    for (size_t q = 0; q < r->nstrut; q++) {
        size_t A = r->strut_a[q], B = r->strut_b[q], fe[2];
        size_t ends[2] = {A, B};
        double st[2];
        int ok = 1;
        /* the coarse edges' next vertices and their components */
        size_t nxt[2];
        int kk[2];
        for (int h = 0; h < 2; h++) {
            int k = 0;
            while (k + 1 < nc && ends[h] >= cstart[k + 1])
                k++;
            kk[h] = k;
            size_t j = ends[h] - cstart[k], n = r->comp_nv[k];
            if (j + 1 >= n && !s->w.closed[k])
                ok = 0;
            nxt[h] = cstart[k] + (j + 1 < n ? j + 1 : 0);
        }
        if (!ok)
            continue;
        tr_segment_distance(r->y + 3 * A, r->y + 3 * nxt[0], r->y + 3 * B, r->y + 3 * nxt[1], &st[0], &st[1]);
        for (int h = 0; h < 2; h++) {
            int k = kk[h];
            size_t j = ends[h] - cstart[k], nfv = tr_comp_nv(&s->w, k);
            const double *tck = tc + cstart[k] + (size_t)k, *tfk = tf + s->w.start[k] + (size_t)k;
            double u = tck[j] + st[h] * (tck[j + 1] - tck[j]), frac;
            size_t nfe = s->w.closed[k] ? nfv : nfv - 1;
            fe[h] = s->w.start[k] + locate(tfk, nfe, u, &frac);
        }
        tr_strut_pair key = {.a = fe[0] < fe[1] ? fe[0] : fe[1], .b = fe[0] < fe[1] ? fe[1] : fe[0]};
        tr_strut_pair *hit = s->nsp ? bsearch(&key, s->sp, s->nsp, sizeof *s->sp, tr_strut_pair_cmp) : NULL;
        if (hit)
            hit->lam += r->strut_lam[q];
    }
    /* The first penalty (newton.h mu0, or coarse_mu), not the coarse
     * solve's last: at its cap (1e5 / l0) the first steps stood still (an
     * unbalanced force of 3e6 at step 0 with the linear refinement). And
     * each carried row holds its force at the start: the finer curve's
     * contacts are open by a little (the arcs of refine_arcs.h bulge out
     * by 2.4e-7 at 2 x 6400), which at mu g above the row's multiplier
     * (4e-3 against 1e-4) would leave it inactive, as it left every strut at
     * step 0; so lambda + mu g for each carried row that is not at its
     * bound. */
    s->mu = (s->p->coarse_mu > 0.0 ? s->p->coarse_mu : s->p->mu0) / s->l0min;
    for (size_t q = 0; q < s->nsp; q++)
        if (s->sp[q].lam > 0.0) {
            double d = tr_newton_i_pair_distance(s, y, s->sp[q].a, s->sp[q].b);
            if (d > 2.0)
                s->sp[q].lam += s->mu * (d - 2.0);
        }
    for (size_t i = 0; i < nv; i++) {
        double c, dc, d2c, w[3];
        if (s->lam_m[i] > 0.0 && tr_newton_i_minrad_row(s, y, y + 3 * nv, i, w, &c, &dc, &d2c)) {
            double g = (c - v3_dot(w, w)) / s->scale_m[s->comp[i]];
            if (g > 0.0)
                s->lam_m[i] += s->mu * g;
        }
    }
done:
    free(cstart);
    free(tc);
    free(tf);
    free(lam_m);
    free(lam_e);
    return rc;
}
