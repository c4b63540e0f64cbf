/* This file contains the serial reference's correct (backend.h): the rows
 * (edges, curvature chords, struts), Gauss-Newton with CG on J M^-1 J^T and
 * its preconditioner. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/reference/reference_state.h"
#include "segment_distance.h"
#include "util/vec3.h"

static double edge_pair_distance(const ref_state *s, size_t a, size_t b)
{
    double ss, tt;
    return tr_segment_distance(s->x + 3 * a, s->x + 3 * (size_t)s->next[a], s->x + 3 * b,
                               s->x + 3 * (size_t)s->next[b], &ss, &tt);
}

/* A strut row is kept only where the pair is a local minimum of the
 * distance along both strands (d <= the pairs with a or b moved one edge):
 * neighbouring pairs of a contact carry nearly the same row, and solving
 * with all of them is singular in all but name. */
static int strut_local_min(const ref_state *s, size_t a, size_t b, double d)
{
    size_t e[2] = {a, b};
    for (int side = 0; side < 2; side++) {
        size_t me = e[side], other = e[1 - side];
        ptrdiff_t nb[2] = {s->prev[me], s->next[me]};
        for (int k = 0; k < 2; k++) {
            if (nb[k] < 0 || s->next[nb[k]] < 0 || (size_t)nb[k] == other)
                continue;
            size_t x = (size_t)nb[k];
            if ((size_t)s->next[x] == other || (size_t)s->next[other] == x)
                continue;
            double dn = side == 0 ? edge_pair_distance(s, x, other) : edge_pair_distance(s, other, x);
            if (dn < d)
                return 0;
        }
    }
    return 1;
}

/* Evaluates every row at the current x; returns the worst violation. */
double rb_eval_rows(ref_state *s, const tr_correct_params *prm)
{
    size_t nv = s->nv;
    double viol = 0.0;
    for (size_t a = 0; a < nv; a++) {
        s->ract[a] = 0;
        if (s->next[a] < 0)
            continue;
        double *u = s->rgrad + 3 * a;
        v3_sub(u, s->x + 3 * (size_t)s->next[a], s->x + 3 * a);
        double l = v3_norm(u);
        v3_scale(u, 1.0 / l, u);
        s->rC[a] = l - s->ebar[s->comp[a]];
        s->ract[a] = 1;
        if (fabs(s->rC[a]) > viol)
            viol = fabs(s->rC[a]);
    }
    for (size_t i = 0; i < nv; i++) {
        size_t r = nv + i;
        s->ract[r] = 0;
        if (s->prev[i] < 0 || s->next[i] < 0)
            continue;
        double pe[3], qe[3], cr[3];
        v3_sub(pe, s->x + 3 * i, s->x + 3 * (size_t)s->prev[i]);
        v3_sub(qe, s->x + 3 * (size_t)s->next[i], s->x + 3 * i);
        v3_cross(cr, pe, qe);
        double lp = v3_norm(pe), lq = v3_norm(qe), sn = v3_norm(cr), cs = v3_dot(pe, qe);
        double theta = atan2(sn, cs);
        double eb = s->ebar[s->comp[i]], rr = prm->minrad;
        double tmax = 2.0 * atan(eb / (2.0 * rr));
        double C = eb * (tmax - theta);
        double *ga = s->rgrad + 3 * r, *gb = s->cgq + 3 * i;
        s->rC[r] = C;
        s->cdeb[i] = (tmax - theta) + eb * (1.0 / rr) / (1.0 + eb * eb / (4.0 * rr * rr));
        if (sn < 1e-12 * lp * lq) {
            ga[0] = ga[1] = ga[2] = gb[0] = gb[1] = gb[2] = 0.0;
        } else {
            double c = cs / (lp * lq), sinv = lp * lq / sn;
            for (int k = 0; k < 3; k++) {
                double ph = pe[k] / lp, qh = qe[k] / lq;
                ga[k] = eb * (c * ph - qh) / lp * sinv;
                gb[k] = eb * (c * qh - ph) / lq * sinv;
            }
            s->ract[r] = C < prm->active_curv;
        }
        if (-C > viol)
            viol = -C;
    }
    for (size_t p = 0; p < s->np; p++) {
        size_t r = 2 * nv + p, a = s->pa[p], b = s->pb[p];
        const double *x = s->x;
        const double *p0 = x + 3 * a, *p1 = x + 3 * (size_t)s->next[a];
        const double *q0 = x + 3 * b, *q1 = x + 3 * (size_t)s->next[b];
        double ss, tt;
        double d = tr_segment_distance(p0, p1, q0, q1, &ss, &tt);
        double *n = s->rgrad + 3 * r;
        for (int k = 0; k < 3; k++)
            n[k] = ((p0[k] + ss * (p1[k] - p0[k])) - (q0[k] + tt * (q1[k] - q0[k]))) / d;
        s->rs[p] = ss;
        s->rt[p] = tt;
        double C = d - prm->strut_dist;
        s->rC[r] = C;
        s->ract[r] = C < prm->active_strut && strut_local_min(s, a, b, d);
        if (-C > viol)
            viol = -C;
    }
    return viol;
}

/* y (rows) -> dx (per vertex, projected), debar (per component). */
void rb_apply_JT(ref_state *s, const tr_correct_params *prm, const double *y)
{
    size_t nv = s->nv;
    for (size_t i = 0; i < nv; i++) {
        double g[3] = {0, 0, 0};
        ptrdiff_t pv = s->prev[i], nx = s->next[i];
        if (pv >= 0)
            v3_axpy(g, y[(size_t)pv], s->rgrad + 3 * (size_t)pv);
        if (nx >= 0)
            v3_axpy(g, -y[i], s->rgrad + 3 * i);
        if (pv >= 0 && s->ract[nv + (size_t)pv])
            v3_axpy(g, -y[nv + (size_t)pv], s->cgq + 3 * (size_t)pv);
        if (s->ract[nv + i]) {
            v3_axpy(g, y[nv + i], s->cgq + 3 * i);
            v3_axpy(g, -y[nv + i], s->rgrad + 3 * (nv + i));
        }
        if (nx >= 0 && s->ract[nv + (size_t)nx])
            v3_axpy(g, y[nv + (size_t)nx], s->rgrad + 3 * (nv + (size_t)nx));
        const size_t *adj = s->compact ? s->aadj : s->adj;
        const size_t *adj_start = s->compact ? s->aadj_start : s->adj_start;
        for (size_t m = adj_start[i]; m < adj_start[i + 1]; m++) {
            size_t p = adj[m] / 4, slot = adj[m] % 4, r = 2 * nv + p;
            if (!s->ract[r])
                continue;
            double c = slot == 0 ? 1.0 - s->rs[p] : slot == 1 ? s->rs[p] : slot == 2 ? -(1.0 - s->rt[p]) : -s->rt[p];
            v3_axpy(g, c * y[r], s->rgrad + 3 * r);
        }
        rb_project_motion(s, i, g);
        memcpy(s->dx + 3 * i, g, sizeof g);
    }
    for (int k = 0; k < s->ncomp; k++) {
        double sum = 0.0;
        for (size_t a = s->start[k]; a < s->start[k + 1]; a++)
            if (s->ract[a])
                sum += -y[a];
        for (size_t i = s->start[k]; i < s->start[k + 1]; i++)
            if (s->ract[nv + i])
                sum += s->cdeb[i] * y[nv + i];
        s->debar[k] = s->ne[k] ? sum / (prm->ebar_weight * (double)s->ne[k]) : 0.0;
    }
}

/* out_r = grad C_r . (dx, debar) + reg y_r on active rows, 0 elsewhere. */
void rb_apply_J(ref_state *s, const tr_correct_params *prm, const double *y, double *out)
{
    size_t nv = s->nv;
    const double *dx = s->dx;
    for (size_t a = 0; a < nv; a++) {
        if (!s->ract[a]) {
            out[a] = 0.0;
            continue;
        }
        double d[3];
        v3_sub(d, dx + 3 * (size_t)s->next[a], dx + 3 * a);
        out[a] = (v3_dot(s->rgrad + 3 * a, d) + prm->reg * y[a]) - s->debar[s->comp[a]];
    }
    for (size_t i = 0; i < nv; i++) {
        size_t r = nv + i;
        if (!s->ract[r]) {
            out[r] = 0.0;
            continue;
        }
        const double *ga = s->rgrad + 3 * r, *gb = s->cgq + 3 * i;
        const double *dp = dx + 3 * (size_t)s->prev[i], *di = dx + 3 * i, *dn = dx + 3 * (size_t)s->next[i];
        double v = 0.0;
        for (int k = 0; k < 3; k++)
            v += ga[k] * dp[k] + (gb[k] - ga[k]) * di[k] - gb[k] * dn[k];
        out[r] = (v + prm->reg * y[r]) + s->cdeb[i] * s->debar[s->comp[i]];
    }
    size_t nloop = s->compact ? s->nact : s->np;
    for (size_t l = 0; l < nloop; l++) {
        size_t p = s->compact ? s->act[l] : l;
        size_t r = 2 * nv + p;
        if (!s->ract[r]) {
            out[r] = 0.0;
            continue;
        }
        size_t a = s->pa[p], b = s->pb[p];
        double ss = s->rs[p], tt = s->rt[p], d[3];
        const double *da = dx + 3 * a, *dna = dx + 3 * (size_t)s->next[a];
        const double *db = dx + 3 * b, *dnb = dx + 3 * (size_t)s->next[b];
        for (int k = 0; k < 3; k++)
            d[k] = (1.0 - ss) * da[k] + ss * dna[k] - (1.0 - tt) * db[k] - tt * dnb[k];
        out[r] = v3_dot(s->rgrad + 3 * r, d) + prm->reg * y[r];
    }
}

static double dot_rows(const ref_state *st, const double *a, const double *b, size_t n)
{
    double s = 0.0;
    if (!st->compact) {
        for (size_t i = 0; i < n; i++)
            s += a[i] * b[i];
        return s;
    }
    for (size_t i = 0; i < 2 * st->nv; i++)
        s += a[i] * b[i];
    for (size_t l = 0; l < st->nact; l++) {
        size_t r = 2 * st->nv + st->act[l];
        s += a[r] * b[r];
    }
    return s;
}

/* The rows a compacted CG touches: every edge and curvature row, then the
 * active strut rows in list order. */
static size_t row_at(const ref_state *s, size_t l)
{
    return l < 2 * s->nv ? l : 2 * s->nv + s->act[l - 2 * s->nv];
}

/* Makes *v hold at least n entries. */
static int reserve_sizes(size_t **v, size_t *cap, size_t n)
{
    if (*v && n <= *cap)
        return 0;
    size_t *g = realloc(*v, (n ? n : 1) * sizeof *g);
    if (!g)
        return -1;
    *v = g;
    *cap = n;
    return 0;
}

/* Builds act / aadj from ract (see ref_state). */
static int compact_rows(ref_state *s)
{
    size_t nv = s->nv, na = 0, nadj = 0;
    for (size_t p = 0; p < s->np; p++)
        na += s->ract[2 * nv + p];
    if (reserve_sizes(&s->act, &s->act_cap, na) || reserve_sizes(&s->aadj, &s->aadj_cap, 4 * na))
        return -1;
    if (!s->aadj_start && !(s->aadj_start = malloc((nv + 1) * sizeof *s->aadj_start)))
        return -1;
    s->nact = 0;
    for (size_t p = 0; p < s->np; p++)
        if (s->ract[2 * nv + p])
            s->act[s->nact++] = p;
    for (size_t i = 0; i < nv; i++) {
        s->aadj_start[i] = nadj;
        for (size_t m = s->adj_start[i]; m < s->adj_start[i + 1]; m++)
            if (s->ract[2 * nv + s->adj[m] / 4])
                s->aadj[nadj++] = s->adj[m];
    }
    s->aadj_start[nv] = nadj;
    return 0;
}

static double proj_norm2(const ref_state *s, size_t v, const double *g, double c)
{
    double t[3] = {c * g[0], c * g[1], c * g[2]};
    rb_project_motion(s, v, t);
    return v3_dot(t, t);
}

/* The edge block of one component as Thomas factors: rows st .. st+n-1 with
 * diagonal b (b[0] is row st) and off-diagonals po[st .. st+n-2]. Stores
 * the multipliers w[j] = o_{j-1} / pivot_{j-1} and the reciprocal pivots ib,
 * so that every CG iteration's solve is two multiply-add sweeps with no
 * division. */
static void tridiag_factor(const double *po, const double *b, double b_first, double b_last,
                           size_t st, size_t n, double *w, double *ib)
{
    ib[0] = 1.0 / (n > 1 ? b_first : b_last);
    for (size_t j = 1; j < n; j++) {
        w[j] = po[st + j - 1] * ib[j - 1];
        ib[j] = 1.0 / ((j + 1 < n ? b[j] : b_last) - po[st + j - 1] * w[j]);
    }
}

/* x = T^-1 r from tridiag_factor's factors; x may alias r. */
static void tridiag_subst(const double *po, size_t st, size_t n, const double *w, const double *ib,
                          const double *r, double *x)
{
    x[0] = r[0] * ib[0];
    for (size_t j = 1; j < n; j++)
        x[j] = (r[j] - po[st + j - 1] * x[j - 1]) * ib[j];
    for (size_t j = n - 1; j-- > 0;)
        x[j] -= w[j + 1] * x[j + 1];
}

/* Sets up the preconditioner for the rows as evaluated: s->pd = diagonal of A
 * (every active row), s->po[a] = A entry between edge rows a and next(a). */
static void precond_setup(ref_state *s, const tr_correct_params *prm)
{
    size_t nv = s->nv, nr = 2 * nv + s->np;
    for (size_t r = 0; r < nr; r++)
        s->pd[r] = 1.0;
    for (size_t a = 0; a < nv; a++) {
        if (!s->ract[a])
            continue;
        int k = s->comp[a];
        const double *u = s->rgrad + 3 * a;
        size_t nx = (size_t)s->next[a];
        s->pd[a] = proj_norm2(s, a, u, 1.0) + proj_norm2(s, nx, u, 1.0) +
                   1.0 / (prm->ebar_weight * (double)s->ne[k]) + prm->reg;
        s->po[a] = 0.0;
        if (s->next[nx] >= 0 && s->ract[nx]) {
            double t[3] = {u[0], u[1], u[2]};
            rb_project_motion(s, nx, t);
            s->po[a] = -v3_dot(t, s->rgrad + 3 * nx);
        }
    }
    for (size_t i = 0; i < nv; i++) {
        size_t r = nv + i;
        if (!s->ract[r])
            continue;
        const double *ga = s->rgrad + 3 * r, *gb = s->cgq + 3 * i;
        double gm[3] = {gb[0] - ga[0], gb[1] - ga[1], gb[2] - ga[2]};
        int k = s->comp[i];
        s->pd[r] = proj_norm2(s, (size_t)s->prev[i], ga, 1.0) + proj_norm2(s, i, gm, 1.0) +
                   proj_norm2(s, (size_t)s->next[i], gb, 1.0) +
                   s->cdeb[i] * s->cdeb[i] / (prm->ebar_weight * (double)s->ne[k]) + prm->reg;
    }
    for (size_t p = 0; p < s->np; p++) {
        size_t r = 2 * nv + p;
        if (!s->ract[r])
            continue;
        size_t a = s->pa[p], b = s->pb[p];
        const double *n = s->rgrad + 3 * r;
        s->pd[r] = proj_norm2(s, a, n, 1.0 - s->rs[p]) + proj_norm2(s, (size_t)s->next[a], n, s->rs[p]) +
                   proj_norm2(s, b, n, 1.0 - s->rt[p]) + proj_norm2(s, (size_t)s->next[b], n, s->rt[p]) +
                   prm->reg;
    }
}

/* Factors every component's edge block (once per solve: the block is the
 * same in every CG iteration). Closed components: Sherman-Morrison on the
 * corner entries (Numerical Recipes 2.7, gamma = -D_first), so the factors
 * are of the block with a modified first and last diagonal entry, and the
 * correction vector uu is solved here too. */
static void precond_factor(ref_state *s)
{
    for (int k = 0; k < s->ncomp; k++) {
        size_t st = s->start[k], n = s->ne[k];
        const double *d = s->pd + st;
        double *w = s->tri_w + st, *ib = s->tri_ib + st, *uu = s->tri_uu + st;
        if (n == 0)
            continue;
        if (!s->closed[k] || n < 3) {
            tridiag_factor(s->po, d, d[0], d[n - 1], st, n, w, ib);
            continue;
        }
        double alpha = s->po[st + n - 1], beta = alpha, gamma = -d[0];
        tridiag_factor(s->po, d, d[0] - gamma, d[n - 1] - alpha * beta / gamma, st, n, w, ib);
        for (size_t j = 0; j < n; j++)
            uu[j] = 0.0;
        uu[0] = gamma;
        uu[n - 1] = alpha;
        tridiag_subst(s->po, st, n, w, ib, uu, uu);
    }
}

/* z = M^-1 r: per component the tridiagonal (cyclic for closed) block of
 * the edge rows, solved exactly; every other row divided by its diagonal. */
static void precond_apply(ref_state *s, const double *r, double *z)
{
    size_t nv = s->nv, nr = s->compact ? 2 * nv + s->nact : 2 * nv + s->np;
    for (size_t l = nv; l < nr; l++) {
        size_t q = s->compact ? row_at(s, l) : l;
        z[q] = s->ract[q] ? r[q] / s->pd[q] : 0.0;
    }
    /* the row of an open rope's last vertex has no edge and no block entry:
     * zero, or realloc'd garbage (possibly NaN) reaches p and the dot products */
    for (size_t q = 0; q < nv; q++)
        if (!s->ract[q])
            z[q] = 0.0;
    for (int k = 0; k < s->ncomp; k++) {
        size_t st = s->start[k], n = s->ne[k];
        const double *w = s->tri_w + st, *ib = s->tri_ib + st, *uu = s->tri_uu + st;
        double *x = z + st;
        if (n == 0)
            continue;
        tridiag_subst(s->po, st, n, w, ib, r + st, x);
        if (!s->closed[k] || n < 3)
            continue;
        double beta = s->po[st + n - 1], gamma = -s->pd[st];
        double fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + uu[0] + beta * uu[n - 1] / gamma);
        for (size_t j = 0; j < n; j++)
            x[j] -= fact * uu[j];
    }
}

/* Solves A y = b (rows, s->b) by preconditioned CG from y = 0 as backend.h
 * specifies; returns the iterations taken. */
int rb_cg_solve(ref_state *s, const tr_correct_params *prm)
{
    size_t nr = 2 * s->nv + s->np;
    precond_setup(s, prm);
    precond_factor(s);
    for (size_t r = 0; r < nr; r++) {
        s->y[r] = 0.0;
        s->r[r] = s->b[r];
    }
    precond_apply(s, s->r, s->z);
    memcpy(s->p, s->z, nr * sizeof *s->p);
    /* out of memory for the compaction only costs speed */
    s->compact = compact_rows(s) == 0;
    size_t nl = s->compact ? 2 * s->nv + s->nact : nr;
    double rr0 = dot_rows(s, s->r, s->r, nr), rr = rr0, rz = dot_rows(s, s->r, s->z, nr);
    int k;
    for (k = 0; k < prm->max_cg; k++) {
        if (rr <= prm->cg_rtol * prm->cg_rtol * rr0)
            break;
        rb_apply_JT(s, prm, s->p);
        rb_apply_J(s, prm, s->p, s->q);
        double pq = dot_rows(s, s->p, s->q, nr);
        double alpha = rz / pq;
        for (size_t l = 0; l < nl; l++) {
            size_t r = s->compact ? row_at(s, l) : l;
            s->y[r] += alpha * s->p[r];
            s->r[r] -= alpha * s->q[r];
        }
        rr = dot_rows(s, s->r, s->r, nr);
        precond_apply(s, s->r, s->z);
        double rz1 = dot_rows(s, s->r, s->z, nr);
        double beta = rz1 / rz;
        for (size_t l = 0; l < nl; l++) {
            size_t r = s->compact ? row_at(s, l) : l;
            s->p[r] = s->z[r] + beta * s->p[r];
        }
        rz = rz1;
    }
    s->compact = 0;
    return k;
}

int rb_correct(void *sp, const tr_correct_params *prm, tr_correct_stats *out, tr_error *err)
{
    ref_state *s = sp;
    int rc = rb_ensure_rows(s, err);
    if (rc)
        return rc;
    size_t nv = s->nv, nr = 2 * nv + s->np;
    tr_correct_stats st = {0};
    int it;
    for (it = 0; it < prm->max_newton; it++) {
        double viol = rb_eval_rows(s, prm);
        if (it == 0)
            st.viol_before = viol;
        if (viol <= prm->viol_tol)
            break;
        size_t nact = 0;
        for (size_t r = 0; r < nr; r++) {
            /* inequality rows inside the active band are held, not pulled */
            s->b[r] = !s->ract[r] ? 0.0 : (r < nv ? -s->rC[r] : -fmin(s->rC[r], 0.0));
            nact += s->ract[r];
        }
        st.active_rows = nact;
        st.cg_iters += rb_cg_solve(s, prm);
        rb_apply_JT(s, prm, s->y);
        double maxdx = 0.0;
        for (size_t i = 0; i < nv; i++) {
            double d = v3_norm(s->dx + 3 * i);
            if (d > maxdx)
                maxdx = d;
        }
        double scale = maxdx > prm->max_step ? prm->max_step / maxdx : 1.0;
        for (size_t i = 0; i < nv; i++) {
            if (scale != 1.0)
                v3_scale(s->dx + 3 * i, scale, s->dx + 3 * i);
            v3_add(s->x + 3 * i, s->x + 3 * i, s->dx + 3 * i);
            rb_snap(s, i);
        }
        for (int k = 0; k < s->ncomp; k++)
            s->ebar[k] += scale * s->debar[k];
    }
    st.newton_iters = it;
    st.viol_after = rb_eval_rows(s, prm);
    if (out)
        *out = st;
    return TR_OK;
}

