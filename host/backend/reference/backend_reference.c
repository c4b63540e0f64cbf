/* The serial reference backend: plain C, written to follow the specification
 * in backend.h line by line (same sums in the same order), so the OpenCL
 * backend can be held against it. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/backend.h"
#include "geometry/neighbour_search.h"
#include "segment_distance.h"
#include "util/vec3.h"

enum { PJ_NONE = 0, PJ_PLANE, PJ_LINE, PJ_FIXED };

typedef struct ref_state {
    size_t nv;
    int ncomp;
    size_t *start;
    unsigned char *closed;
    int *comp;
    ptrdiff_t *next, *prev; /* -1: none */
    size_t *ne;             /* edges per component */
    double *x, *xs;
    double *ebar, *ebar_s;
    int saved;
    /* per-vertex constraints */
    unsigned char *pj;
    double *pu; /* 3 per vertex: plane normal or line direction */
    int *vcst;
    tr_constraint *cst;
    /* candidate contacts, sorted (a, b) */
    size_t np, pcap;
    size_t *pa, *pb;
    size_t *adj_start, *adj; /* CSR: adj holds 4*pair + slot */
    size_t adj_cap;
    /* work */
    double *F, *G, *H;  /* 3 nv each */
    double *dx;         /* 3 nv */
    double *debar;      /* ncomp */
    /* rows: [0,nv) edges, [nv,2nv) curvature, [2nv, 2nv+np) struts */
    size_t rcap;
    double *rC, *rgrad; /* value; 3-vector (u, w^, n) */
    double *rs, *rt;    /* strut closest-point parameters (np) */
    unsigned char *ract;
    double *y, *r, *p, *q, *b;
    double *cgq, *cdeb; /* curvature rows: second gradient vector, dC/debar */
    double *pd, *z;     /* preconditioner diagonal, preconditioned residual (rows) */
    double *po;         /* edge-row off-diagonal (nv) */
    /* the edge block factored once per solve (precond_factor): Thomas
     * multipliers, reciprocal pivots, Sherman-Morrison vector (nv each) */
    double *tri_w, *tri_ib, *tri_uu;
    /* inside cg_solve: the active strut rows (ascending) and the per-vertex
     * strut adjacency restricted to them, so that CG iterations skip the
     * many inactive rows of a long list (they hold exact zeros: skipping
     * them changes no sum) */
    int compact;
    size_t nact, *act, *aadj_start, *aadj, act_cap, aadj_cap;
    /* neighbour search: a tree over the edges of a curve that views x */
    tr_curve view;
    tr_nsearch ns;
    int ns_built;
} ref_state;

static void ref_destroy(void *sp)
{
    ref_state *s = sp;
    if (!s)
        return;
    void *ptrs[] = {s->start, s->closed, s->comp, s->next, s->prev, s->ne, s->x, s->xs, s->ebar,
                    s->ebar_s, s->pj, s->pu, s->vcst, s->cst, s->pa, s->pb, s->adj_start, s->adj,
                    s->F, s->G, s->H, s->dx, s->debar, s->rC, s->rgrad, s->rs, s->rt, s->ract,
                    s->y, s->r, s->p, s->q, s->b, s->cgq, s->cdeb, s->pd, s->z, s->po,
                    s->tri_w, s->tri_ib, s->tri_uu, s->act, s->aadj_start, s->aadj};
    for (size_t i = 0; i < sizeof ptrs / sizeof ptrs[0]; i++)
        free(ptrs[i]);
    if (s->ns_built)
        tr_nsearch_free(&s->ns);
    free(s);
}

static void snap(const ref_state *s, size_t i)
{
    if (s->pj[i] != PJ_NONE)
        tr_constraint_project(&s->cst[s->vcst[i]], s->x + 3 * i);
}

static void project_motion(const ref_state *s, size_t i, double *v)
{
    const double *u = s->pu + 3 * i;
    switch (s->pj[i]) {
    case PJ_PLANE: {
        double d = v3_dot(v, u);
        v3_axpy(v, -d, u);
        break;
    }
    case PJ_LINE: {
        double d = v3_dot(v, u);
        v3_scale(v, d, u);
        break;
    }
    case PJ_FIXED:
        v[0] = v[1] = v[2] = 0.0;
        break;
    default:
        break;
    }
}

static void reset_ebar(ref_state *s)
{
    for (int k = 0; k < s->ncomp; k++) {
        double sum = 0.0;
        size_t ne = 0;
        for (size_t a = s->start[k]; a < s->start[k + 1]; a++) {
            if (s->next[a] < 0)
                continue;
            sum += sqrt(v3_dist2(s->x + 3 * a, s->x + 3 * (size_t)s->next[a]));
            ne++;
        }
        s->ebar[k] = ne ? sum / (double)ne : 0.0;
    }
}

static int ref_upload(void *sp, const double *x, const double *ebar, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    memcpy(s->x, x, 3 * s->nv * sizeof *x);
    if (ebar)
        memcpy(s->ebar, ebar, (size_t)s->ncomp * sizeof *ebar);
    else
        reset_ebar(s);
    s->np = 0;
    s->saved = 0;
    return TR_OK;
}

static int ref_download(void *sp, double *x, double *ebar, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    memcpy(x, s->x, 3 * s->nv * sizeof *x);
    if (ebar)
        memcpy(ebar, s->ebar, (size_t)s->ncomp * sizeof *ebar);
    return TR_OK;
}

static int ref_save(void *sp, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    memcpy(s->xs, s->x, 3 * s->nv * sizeof *s->x);
    memcpy(s->ebar_s, s->ebar, (size_t)s->ncomp * sizeof *s->ebar);
    s->saved = 1;
    return TR_OK;
}

static int ref_restore(void *sp, tr_error *err)
{
    ref_state *s = sp;
    if (!s->saved)
        return tr_fail(err, TR_EINVAL, "restore without a saved state");
    memcpy(s->x, s->xs, 3 * s->nv * sizeof *s->x);
    memcpy(s->ebar, s->ebar_s, (size_t)s->ncomp * sizeof *s->ebar);
    return TR_OK;
}

/* ---- neighbour search: the tree over the edges (neighbour_search.h) ---- */

static int excluded(const ref_state *s, size_t a, size_t b, const int *gap)
{
    int k = s->comp[a];
    if (s->comp[b] != k)
        return 0;
    size_t d = a > b ? a - b : b - a;
    if (s->closed[k]) {
        size_t n = s->start[k + 1] - s->start[k];
        if (n - d < d)
            d = n - d;
    }
    int g = gap[k] < 2 ? 2 : gap[k];
    return d < (size_t)g;
}

static int push_pair(ref_state *s, size_t a, size_t b)
{
    if (s->np == s->pcap) {
        size_t nc = s->pcap ? 2 * s->pcap : 1024;
        size_t *na = realloc(s->pa, nc * sizeof *na);
        if (!na)
            return TR_ENOMEM;
        s->pa = na;
        size_t *nb = realloc(s->pb, nc * sizeof *nb);
        if (!nb)
            return TR_ENOMEM;
        s->pb = nb;
        s->pcap = nc;
    }
    s->pa[s->np] = a;
    s->pb[s->np] = b;
    s->np++;
    return TR_OK;
}

typedef struct pair_key {
    size_t a, b;
} pair_key;

static int cmp_pair(const void *x, const void *y)
{
    const pair_key *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

static int build_csr(ref_state *s, tr_error *err)
{
    memset(s->adj_start, 0, (s->nv + 1) * sizeof *s->adj_start);
    for (size_t p = 0; p < s->np; p++) {
        size_t v[4] = {s->pa[p], (size_t)s->next[s->pa[p]], s->pb[p], (size_t)s->next[s->pb[p]]};
        for (int k = 0; k < 4; k++)
            s->adj_start[v[k] + 1]++;
    }
    for (size_t i = 0; i < s->nv; i++)
        s->adj_start[i + 1] += s->adj_start[i];
    if (4 * s->np > s->adj_cap) {
        size_t nc = 4 * s->np + 1024;
        size_t *na = realloc(s->adj, nc * sizeof *na);
        if (!na)
            return tr_fail(err, TR_ENOMEM, "out of memory for the contact adjacency");
        s->adj = na;
        s->adj_cap = nc;
    }
    /* fill in pair order, so each vertex lists its pairs ascending */
    size_t *cur = malloc((s->nv + 1) * sizeof *cur);
    if (!cur)
        return tr_fail(err, TR_ENOMEM, "out of memory for the contact adjacency");
    memcpy(cur, s->adj_start, (s->nv + 1) * sizeof *cur);
    for (size_t p = 0; p < s->np; p++) {
        size_t v[4] = {s->pa[p], (size_t)s->next[s->pa[p]], s->pb[p], (size_t)s->next[s->pb[p]]};
        for (size_t k = 0; k < 4; k++)
            s->adj[cur[v[k]]++] = 4 * p + k;
    }
    free(cur);
    return TR_OK;
}

static int ensure_rows(ref_state *s, tr_error *err)
{
    size_t need = 2 * s->nv + s->np;
    if (need <= s->rcap)
        return TR_OK;
    size_t nc = need + need / 2 + 64;
    double **arrs[] = {&s->rC, &s->y, &s->r, &s->p, &s->q, &s->b, &s->pd, &s->z};
    for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++) {
        double *n = realloc(*arrs[i], nc * sizeof *n);
        if (!n)
            return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
        *arrs[i] = n;
    }
    double *g = realloc(s->rgrad, 3 * nc * sizeof *g);
    if (!g)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->rgrad = g;
    unsigned char *act = realloc(s->ract, nc);
    if (!act)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->ract = act;
    size_t npc = nc - 2 * s->nv;
    double *rs = realloc(s->rs, npc * sizeof *rs), *rt;
    if (!rs)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->rs = rs;
    rt = realloc(s->rt, npc * sizeof *rt);
    if (!rt)
        return tr_fail(err, TR_ENOMEM, "out of memory for %zu constraint rows", nc);
    s->rt = rt;
    s->rcap = nc;
    return TR_OK;
}

/* One candidate from the tree: the exact tests of backend.h. */
typedef struct contact_walk {
    ref_state *s;
    const tr_contact_params *prm;
    double mind;
} contact_walk;

static int contact_pair(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    (void)cutoff;
    contact_walk *w = ctx;
    ref_state *s = w->s;
    size_t a = s->ns.ea[ej], b = s->ns.ea[ei]; /* ej < ei, so a < b */
    if (excluded(s, a, b, w->prm->exclude_gap))
        return 0;
    const double *a0 = s->x + 3 * a, *a1 = s->x + 3 * (size_t)s->next[a];
    const double *b0 = s->x + 3 * b, *b1 = s->x + 3 * (size_t)s->next[b];
    double ss, tt;
    double d = tr_segment_distance(a0, a1, b0, b1, &ss, &tt);
    double tilt = w->prm->tilt;
    if (!(d < w->prm->cutoff) ||
        (tilt > 0.0 && tilt < 1.0 && !tr_segment_nearly_normal(a0, a1, b0, b1, ss, tt, d, tilt)))
        return 0;
    if (push_pair(s, a, b) != TR_OK)
        return 1;
    if (d < w->mind)
        w->mind = d;
    return 0;
}

/* The tree over the edges (host/geometry/neighbour_search.h) is built once, refitted
 * per search; with a tilt its slab test keeps the walk linear in N. */
static int ref_find_contacts(void *sp, const tr_contact_params *prm, tr_contact_stats *out,
                             tr_error *err)
{
    ref_state *s = sp;
    s->np = 0;
    int rc;
    if (!s->ns_built) {
        s->view = (tr_curve){.nv = s->nv, .x = s->x, .ncomp = s->ncomp, .start = s->start, .closed = s->closed};
        if ((rc = tr_nsearch_build(&s->ns, &s->view, err)))
            return rc;
        s->ns_built = 1;
    } else {
        tr_nsearch_refit(&s->ns);
    }
    int gmin = 0;
    for (int k = 0; k < s->ncomp; k++) {
        int g = prm->exclude_gap[k] < 2 ? 2 : prm->exclude_gap[k];
        gmin = k == 0 || g < gmin ? g : gmin;
    }
    contact_walk w = {.s = s, .prm = prm, .mind = INFINITY};
    double pad = prm->tilt > 0.0 && prm->tilt < 1.0 ? prm->tilt * prm->cutoff : -1.0;
    if (tr_nsearch_pairs_slab(&s->ns, prm->cutoff, (size_t)gmin, pad, contact_pair, &w)) {
        s->np = 0;
        return tr_fail(err, TR_ENOMEM, "out of memory for contact pairs");
    }
    pair_key *keys = malloc((s->np ? s->np : 1) * sizeof *keys);
    if (!keys) {
        s->np = 0;
        return tr_fail(err, TR_ENOMEM, "out of memory for contact pairs");
    }
    for (size_t p = 0; p < s->np; p++) {
        keys[p].a = s->pa[p];
        keys[p].b = s->pb[p];
    }
    qsort(keys, s->np, sizeof *keys, cmp_pair);
    for (size_t p = 0; p < s->np; p++) {
        s->pa[p] = keys[p].a;
        s->pb[p] = keys[p].b;
    }
    free(keys);
    rc = build_csr(s, err);
    if (rc == TR_OK)
        rc = ensure_rows(s, err);
    if (rc == TR_OK && out) {
        out->pairs = s->np;
        out->min_dist = w.mind;
    }
    if (rc != TR_OK)
        s->np = 0;
    return rc;
}

/* ---- force evaluation ---- */

static void edge_unit(const ref_state *s, size_t a, double *u)
{
    v3_sub(u, s->x + 3 * (size_t)s->next[a], s->x + 3 * a);
    double l = v3_norm(u);
    v3_scale(u, 1.0 / l, u);
}

/* ---- coupled constraint correction ---- */

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
static double eval_rows(ref_state *s, const tr_correct_params *prm)
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
static void apply_JT(ref_state *s, const tr_correct_params *prm, const double *y)
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
        project_motion(s, i, g);
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
static void apply_J(ref_state *s, const tr_correct_params *prm, const double *y, double *out)
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
    project_motion(s, v, t);
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
            project_motion(s, nx, t);
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
static int cg_solve(ref_state *s, const tr_correct_params *prm)
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
        apply_JT(s, prm, s->p);
        apply_J(s, prm, s->p, s->q);
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

static int ref_correct(void *sp, const tr_correct_params *prm, tr_correct_stats *out, tr_error *err)
{
    ref_state *s = sp;
    int rc = ensure_rows(s, err);
    if (rc)
        return rc;
    size_t nv = s->nv, nr = 2 * nv + s->np;
    tr_correct_stats st = {0};
    int it;
    for (it = 0; it < prm->max_newton; it++) {
        double viol = eval_rows(s, prm);
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
        st.cg_iters += cg_solve(s, prm);
        apply_JT(s, prm, s->y);
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
            snap(s, i);
        }
        for (int k = 0; k < s->ncomp; k++)
            s->ebar[k] += scale * s->debar[k];
    }
    st.newton_iters = it;
    st.viol_after = eval_rows(s, prm);
    if (out)
        *out = st;
    return TR_OK;
}

/* Tangent projection of the (smoothed) force G: rows in the active band
 * (edges always) evaluated at x; solve A y = J (P G); v = P G - M^-1 J^T y;
 * inequality rows whose multiplier pulls (y_r > 0: the force would separate
 * them) are released and the solve repeated, passes times in all. G <- v,
 * s->debar <- the ebar velocity. */
static void project_tangent(ref_state *s, const tr_correct_params *prm, double *G)
{
    size_t nv = s->nv, nr = 2 * nv + s->np;
    eval_rows(s, prm);
    for (size_t i = 0; i < nv; i++) {
        project_motion(s, i, G + 3 * i);
    }
    for (int pass = 0; pass < prm->max_newton; pass++) {
        memcpy(s->dx, G, 3 * nv * sizeof *G);
        for (int k = 0; k < s->ncomp; k++)
            s->debar[k] = 0.0;
        for (size_t r = 0; r < nr; r++)
            s->y[r] = 0.0;
        apply_J(s, prm, s->y, s->b);
        cg_solve(s, prm);
        if (pass + 1 < prm->max_newton) {
            int changed = 0;
            for (size_t r = nv; r < nr; r++)
                if (s->ract[r] && s->y[r] > 0.0) {
                    s->ract[r] = 0;
                    changed = 1;
                }
            if (changed)
                continue;
        }
        break;
    }
    apply_JT(s, prm, s->y);
    for (size_t i = 0; i < 3 * nv; i++)
        G[i] -= s->dx[i];
    for (int k = 0; k < s->ncomp; k++)
        s->debar[k] = -s->debar[k];
}

static int ref_tension_step(void *sp, const tr_tension_params *prm, tr_tension_stats *out,
                            tr_error *err)
{
    ref_state *s = sp;
    size_t nv = s->nv;
    double *F = s->F, *G = s->G, *H = s->H;
    for (size_t i = 0; i < nv; i++) {
        double f[3] = {0, 0, 0}, u[3];
        if (s->next[i] >= 0) {
            edge_unit(s, i, u);
            v3_add(f, f, u);
        }
        if (s->prev[i] >= 0) {
            edge_unit(s, (size_t)s->prev[i], u);
            v3_sub(f, f, u);
        }
        memcpy(F + 3 * i, f, sizeof f);
    }
    memcpy(G, F, 3 * nv * sizeof *F);
    for (int pass = 0; pass < prm->smooth_passes; pass++) {
        for (size_t i = 0; i < nv; i++) {
            const double *g = G + 3 * i;
            double *h = H + 3 * i;
            ptrdiff_t pv = s->prev[i], nx = s->next[i];
            if (pv >= 0 && nx >= 0) {
                const double *gp = G + 3 * (size_t)pv, *gn = G + 3 * (size_t)nx;
                for (int k = 0; k < 3; k++)
                    h[k] = (gp[k] + 2.0 * g[k] + gn[k]) / 4.0;
            } else if (pv >= 0 || nx >= 0) {
                const double *gb = G + 3 * (size_t)(pv >= 0 ? pv : nx);
                for (int k = 0; k < 3; k++)
                    h[k] = (3.0 * g[k] + gb[k]) / 4.0;
            } else {
                memcpy(h, g, 3 * sizeof *h);
            }
        }
        double *t = G;
        G = H;
        H = t;
    }
    double smooth2 = 0.0, free2 = 0.0;
    for (size_t i = 0; i < nv; i++) {
        double g[3] = {G[3 * i], G[3 * i + 1], G[3 * i + 2]};
        project_motion(s, i, g);
        smooth2 += v3_dot(g, g);
    }
    if (prm->project) {
        int rc = ensure_rows(s, err);
        if (rc)
            return rc;
        project_tangent(s, prm->project, G);
        for (size_t i = 0; i < 3 * nv; i++)
            free2 += G[i] * G[i];
    } else {
        free2 = smooth2;
    }
    double force2 = 0.0, pred = 0.0, maxm = 0.0;
    for (size_t i = 0; i < nv; i++) {
        double f[3], d[3];
        memcpy(f, F + 3 * i, sizeof f);
        project_motion(s, i, f);
        force2 += v3_dot(f, f);
        v3_scale(d, prm->h, G + 3 * i);
        project_motion(s, i, d);
        double m = v3_norm(d);
        if (m > prm->max_move) {
            v3_scale(d, prm->max_move / m, d);
            m = prm->max_move;
        }
        if (m > maxm)
            maxm = m;
        pred += v3_dot(F + 3 * i, d);
        v3_add(s->x + 3 * i, s->x + 3 * i, d);
        snap(s, i);
    }
    if (prm->project)
        for (int k = 0; k < s->ncomp; k++)
            s->ebar[k] += prm->h * s->debar[k];
    if (out) {
        out->force2 = force2;
        out->predicted = pred;
        out->max_move = maxm;
        out->smooth2 = smooth2;
        out->free2 = free2;
    }
    return TR_OK;
}

/* ---- reductions ---- */

static int ref_measure(void *sp, tr_measure *out, double *comp_length, double *comp_ebar, tr_error *err)
{
    (void)err;
    ref_state *s = sp;
    tr_measure m = {0};
    m.min_strut = INFINITY;
    m.min_minrad = INFINITY;
    for (int k = 0; k < s->ncomp; k++) {
        double len = 0.0;
        for (size_t a = s->start[k]; a < s->start[k + 1]; a++) {
            if (s->next[a] < 0)
                continue;
            double l = sqrt(v3_dist2(s->x + 3 * a, s->x + 3 * (size_t)s->next[a]));
            len += l;
            double dev = fabs(l - s->ebar[k]) / s->ebar[k];
            if (dev > m.edge_dev)
                m.edge_dev = dev;
        }
        m.length += len;
        if (comp_length)
            comp_length[k] = len;
        if (comp_ebar)
            comp_ebar[k] = s->ebar[k];
    }
    for (size_t p = 0; p < s->np; p++) {
        size_t a = s->pa[p], b = s->pb[p];
        double ss, tt;
        double d = tr_segment_distance(s->x + 3 * a, s->x + 3 * (size_t)s->next[a], s->x + 3 * b,
                                       s->x + 3 * (size_t)s->next[b], &ss, &tt);
        if (d < m.min_strut)
            m.min_strut = d;
    }
    for (size_t i = 0; i < s->nv; i++) {
        if (s->prev[i] < 0 || s->next[i] < 0)
            continue;
        double a[3], b[3], c[3];
        v3_sub(a, s->x + 3 * i, s->x + 3 * (size_t)s->prev[i]);
        v3_sub(b, s->x + 3 * (size_t)s->next[i], s->x + 3 * i);
        v3_cross(c, a, b);
        double cn = v3_norm(c);
        if (cn == 0.0)
            continue;
        double la = v3_norm(a), lb = v3_norm(b);
        double mr = fmin(la, lb) * (la * lb + v3_dot(a, b)) / (2.0 * cn);
        if (mr < m.min_minrad)
            m.min_minrad = mr;
    }
    if (s->saved)
        for (size_t i = 0; i < s->nv; i++) {
            double d = sqrt(v3_dist2(s->x + 3 * i, s->xs + 3 * i));
            if (d > m.max_disp)
                m.max_disp = d;
        }
    *out = m;
    return TR_OK;
}

static const tr_backend_ops reference_ops = {
    .name = "reference",
    .serial = 1,
    .destroy = ref_destroy,
    .upload = ref_upload,
    .download = ref_download,
    .save = ref_save,
    .restore = ref_restore,
    .find_contacts = ref_find_contacts,
    .tension_step = ref_tension_step,
    .correct = ref_correct,
    .measure = ref_measure,
};

int tr_backend_reference_open(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err)
{
    if (spec && *spec && strcmp(spec, "reference") != 0)
        return tr_fail(err, TR_EUNSUPPORTED, "the serial reference is selected by 'reference'");
    memset(out, 0, sizeof *out);
    if (c->nv == 0 || c->ncomp <= 0)
        return tr_fail(err, TR_EINVAL, "empty curve");
    ref_state *s = calloc(1, sizeof *s);
    if (!s)
        return tr_fail(err, TR_ENOMEM, "out of memory opening the reference backend");
    size_t nv = c->nv;
    s->nv = nv;
    s->ncomp = c->ncomp;
    s->start = malloc((size_t)(c->ncomp + 1) * sizeof *s->start);
    s->closed = malloc((size_t)c->ncomp);
    s->ne = malloc((size_t)c->ncomp * sizeof *s->ne);
    s->comp = malloc(nv * sizeof *s->comp);
    s->next = malloc(nv * sizeof *s->next);
    s->prev = malloc(nv * sizeof *s->prev);
    s->x = malloc(3 * nv * sizeof *s->x);
    s->xs = malloc(3 * nv * sizeof *s->xs);
    s->ebar = malloc((size_t)c->ncomp * sizeof *s->ebar);
    s->ebar_s = malloc((size_t)c->ncomp * sizeof *s->ebar_s);
    s->debar = malloc((size_t)c->ncomp * sizeof *s->debar);
    s->pj = calloc(nv, 1);
    s->pu = calloc(3 * nv, sizeof *s->pu);
    s->vcst = malloc(nv * sizeof *s->vcst);
    s->cst = malloc((size_t)(c->ncst > 0 ? c->ncst : 1) * sizeof *s->cst);
    s->adj_start = calloc(nv + 1, sizeof *s->adj_start);
    s->F = malloc(3 * nv * sizeof *s->F);
    s->G = malloc(3 * nv * sizeof *s->G);
    s->H = malloc(3 * nv * sizeof *s->H);
    s->dx = malloc(3 * nv * sizeof *s->dx);
    s->cgq = malloc(3 * nv * sizeof *s->cgq);
    s->cdeb = malloc(nv * sizeof *s->cdeb);
    s->po = calloc(nv, sizeof *s->po);
    s->tri_w = calloc(nv, sizeof *s->tri_w);
    s->tri_ib = calloc(nv, sizeof *s->tri_ib);
    s->tri_uu = calloc(nv, sizeof *s->tri_uu);
    if (!s->start || !s->closed || !s->ne || !s->comp || !s->next || !s->prev || !s->x || !s->xs ||
        !s->ebar || !s->ebar_s || !s->debar || !s->pj || !s->pu || !s->vcst || !s->cst ||
        !s->adj_start || !s->F || !s->G || !s->H || !s->dx || !s->cgq || !s->cdeb || !s->po || !s->tri_w ||
        !s->tri_ib || !s->tri_uu) {
        ref_destroy(s);
        return tr_fail(err, TR_ENOMEM, "out of memory opening the reference backend (%zu vertices)", nv);
    }
    memcpy(s->start, c->start, (size_t)(c->ncomp + 1) * sizeof *s->start);
    memcpy(s->closed, c->closed, (size_t)c->ncomp);
    for (int k = 0; k < c->ncomp; k++) {
        size_t a = c->start[k], e = c->start[k + 1], n = e - a;
        if (n < (c->closed[k] ? 3u : 2u)) {
            ref_destroy(s);
            return tr_fail(err, TR_EGEOMETRY, "component %d has only %zu vertices", k, n);
        }
        s->ne[k] = tr_comp_ne(c, k);
        for (size_t i = a; i < e; i++) {
            s->comp[i] = k;
            s->next[i] = i + 1 < e ? (ptrdiff_t)(i + 1) : (c->closed[k] ? (ptrdiff_t)a : -1);
            s->prev[i] = i > a ? (ptrdiff_t)(i - 1) : (c->closed[k] ? (ptrdiff_t)(e - 1) : -1);
        }
    }
    if (c->ncst > 0)
        memcpy(s->cst, c->cst, (size_t)c->ncst * sizeof *s->cst);
    for (size_t i = 0; i < nv; i++) {
        s->vcst[i] = c->vcst && c->ncst > 0 ? c->vcst[i] : -1;
        if (s->vcst[i] < 0 || s->vcst[i] >= c->ncst) {
            s->vcst[i] = -1;
            continue;
        }
        const tr_constraint *k = &c->cst[s->vcst[i]];
        s->pj[i] = k->kind == TR_CST_PLANE ? PJ_PLANE : k->kind == TR_CST_LINE ? PJ_LINE : PJ_FIXED;
        memcpy(s->pu + 3 * i, k->u, 3 * sizeof(double));
    }
    memcpy(s->x, c->x, 3 * nv * sizeof *s->x);
    for (size_t i = 0; i < nv; i++)
        snap(s, i);
    reset_ebar(s);
    tr_error e2;
    if (ensure_rows(s, &e2) != TR_OK) {
        ref_destroy(s);
        return tr_fail(err, TR_ENOMEM, "%s", e2.msg);
    }
    out->ops = &reference_ops;
    out->state = s;
    snprintf(out->description, sizeof out->description, "serial reference (CPU, double precision)");
    return TR_OK;
}
