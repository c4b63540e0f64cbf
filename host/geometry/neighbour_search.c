/* This file contains the neighbour search over a curve's edges: a tree along the curve, pair
 * walks and exclusions (neighbour_search.h). */
#include "geometry/neighbour_search.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "util/vec3.h"

/* Edges per leaf: small enough that a leaf box stays close to its edges,
 * large enough that the tree is shallow. */
#define LEAF_EDGES 8
#define STACK_DEPTH 256

/* Relative widening of every pruning test against rounding in the box
 * arithmetic (the exact distances come from the callback). */
#define PRUNE_SLACK 1e-12

typedef struct tr_nsearch_node {
    double m[3], r[3]; /* box centre and half-widths (widened a few ulps) */
    size_t a, b;       /* edges [a, b) */
    int comp;      /* the component if all edges share one, else -1 */
    uint32_t left; /* child indices; left == 0 marks a leaf (the root is 0) */
    uint32_t right;
} node_t;

static void edge_box(const tr_nsearch *s, size_t e, double *lo, double *hi)
{
    const double *p = s->c->x + 3 * s->ea[e], *q = s->c->x + 3 * s->eb[e];
    for (int k = 0; k < 3; k++) {
        lo[k] = p[k] < q[k] ? p[k] : q[k];
        hi[k] = p[k] < q[k] ? q[k] : p[k];
    }
}

/* Centre and half-widths of [lo, hi], widened so that the rounding of the
 * centre never shrinks the box. */
static void centre_half(const double *lo, const double *hi, double *m, double *r)
{
    for (int k = 0; k < 3; k++) {
        m[k] = 0.5 * (lo[k] + hi[k]);
        r[k] = 0.5 * (hi[k] - lo[k]);
        r[k] += 4 * DBL_EPSILON * (fabs(m[k]) + r[k]);
    }
}

static void edge_centre_half(const tr_nsearch *s, size_t e, double *m, double *r)
{
    double lo[3], hi[3];
    edge_box(s, e, lo, hi);
    centre_half(lo, hi, m, r);
}

static size_t build_node(tr_nsearch *s, size_t a, size_t b)
{
    size_t id = s->nnodes++;
    node_t *n = &s->node[id];
    n->a = a;
    n->b = b;
    n->comp = s->ecomp[a] == s->ecomp[b - 1] ? s->ecomp[a] : -1;
    n->left = n->right = 0;
    if (b - a > LEAF_EDGES) {
        size_t m = a + (b - a) / 2;
        size_t l = build_node(s, a, m);
        size_t r = build_node(s, m, b);
        s->node[id].left = (uint32_t)l;
        s->node[id].right = (uint32_t)r;
    }
    return id;
}

void tr_nsearch_refit(tr_nsearch *s)
{
    /* Nodes are stored in preorder, so children come after their parent. */
    for (size_t id = s->nnodes; id-- > 0;) {
        node_t *n = &s->node[id];
        double lo[3], hi[3];
        if (n->left == 0) {
            edge_box(s, n->a, lo, hi);
            for (size_t e = n->a + 1; e < n->b; e++) {
                double elo[3], ehi[3];
                edge_box(s, e, elo, ehi);
                for (int k = 0; k < 3; k++) {
                    lo[k] = elo[k] < lo[k] ? elo[k] : lo[k];
                    hi[k] = ehi[k] > hi[k] ? ehi[k] : hi[k];
                }
            }
        } else {
            const node_t *l = &s->node[n->left], *r = &s->node[n->right];
            for (int k = 0; k < 3; k++) {
                double a0 = l->m[k] - l->r[k], a1 = r->m[k] - r->r[k];
                double b0 = l->m[k] + l->r[k], b1 = r->m[k] + r->r[k];
                lo[k] = a0 < a1 ? a0 : a1;
                hi[k] = b0 > b1 ? b0 : b1;
            }
        }
        centre_half(lo, hi, n->m, n->r);
    }
}

void tr_nsearch_free(tr_nsearch *s)
{
    if (!s)
        return;
    free(s->ea);
    free(s->eb);
    free(s->eprev);
    free(s->ecomp);
    free(s->estart);
    free(s->node);
    memset(s, 0, sizeof *s);
}

static int build(tr_nsearch *s, const tr_curve *c, int tree, tr_error *err)
{
    memset(s, 0, sizeof *s);
    s->c = c;
    size_t ne = 0;
    for (int k = 0; k < c->ncomp; k++)
        ne += tr_comp_ne(c, k);
    s->ne = ne;
    size_t nalloc = ne ? ne : 1;
    size_t maxnodes = 4 * (nalloc / LEAF_EDGES) + 4;
    if (maxnodes > UINT32_MAX)
        return tr_fail(err, TR_EINVAL, "too many edges for the neighbour search (%zu)", ne);
    s->ea = malloc(nalloc * sizeof *s->ea);
    s->eb = malloc(nalloc * sizeof *s->eb);
    s->eprev = malloc(nalloc * sizeof *s->eprev);
    s->ecomp = malloc(nalloc * sizeof *s->ecomp);
    s->estart = malloc((size_t)(c->ncomp + 1) * sizeof *s->estart);
    s->node = tree ? malloc(maxnodes * sizeof *s->node) : NULL;
    if (!s->ea || !s->eb || !s->eprev || !s->ecomp || !s->estart || (tree && !s->node)) {
        tr_nsearch_free(s);
        return tr_fail(err, TR_ENOMEM, "out of memory building the neighbour search for %zu edges", ne);
    }
    size_t e = 0;
    for (int k = 0; k < c->ncomp; k++) {
        s->estart[k] = e;
        size_t v0 = c->start[k], n = tr_comp_nv(c, k), m = tr_comp_ne(c, k);
        for (size_t l = 0; l < m; l++, e++) {
            s->ea[e] = v0 + l;
            s->eb[e] = v0 + (l + 1) % n;
            if (l > 0)
                s->eprev[e] = v0 + l - 1;
            else
                s->eprev[e] = c->closed[k] ? v0 + n - 1 : v0 + (n > 1 ? 1 : 0);
            s->ecomp[e] = k;
        }
    }
    s->estart[c->ncomp] = e;
    if (tree && ne > 0) {
        build_node(s, 0, ne);
        tr_nsearch_refit(s);
    }
    return TR_OK;
}

int tr_nsearch_build(tr_nsearch *s, const tr_curve *c, tr_error *err) { return build(s, c, 1, err); }

int tr_nsearch_build_flat(tr_nsearch *s, const tr_curve *c, tr_error *err) { return build(s, c, 0, err); }

void tr_nsearch_node(const tr_nsearch *s, size_t id, size_t *a, size_t *b, int *comp, size_t *left,
                     size_t *right)
{
    const node_t *n = &s->node[id];
    *a = n->a;
    *b = n->b;
    *comp = n->comp;
    *left = n->left;
    *right = n->right;
}

int tr_nsearch_excluded(const tr_nsearch *s, size_t ei, size_t ej, size_t min_gap)
{
    if (ei == ej)
        return 1;
    int k = s->ecomp[ei];
    if (k != s->ecomp[ej])
        return 0;
    size_t d = ei > ej ? ei - ej : ej - ei;
    size_t m = s->estart[k + 1] - s->estart[k];
    if (d < min_gap)
        return 1;
    return s->c->closed[k] && d + min_gap > m;
}

/* Are all pairs (i, j), i in [i0, i1] and j in [a, b), excluded? Both runs
 * lie in component k. In terms of the index difference d = i - j, which runs
 * over [i0 - (b-1), i1 - a], a pair is excluded when |d| < g, or on a closed
 * component when |d| > m - g (m edges): the excluded d form intervals, and
 * the whole range must fall in one of them. */
static int range_excluded(const tr_nsearch *s, int k, size_t i0, size_t i1, size_t a, size_t b,
                          size_t min_gap)
{
    long long dlo = (long long)i0 - (long long)(b - 1), dhi = (long long)i1 - (long long)a;
    long long g = (long long)min_gap;
    if (dlo > -g && dhi < g)
        return 1;
    if (!s->c->closed[k])
        return 0;
    long long m = (long long)(s->estart[k + 1] - s->estart[k]);
    if (2 * g > m)
        return 1;
    return dlo > m - g || dhi < -(m - g);
}

static inline double box_dist2(const double *am, const double *ar, const double *bm, const double *br)
{
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) {
        double g = fabs(am[k] - bm[k]) - ar[k] - br[k];
        if (g > 0)
            d2 += g * g;
    }
    return d2;
}

/* What a query needs to know about edge i. */
typedef struct query_edge {
    double m[3], r[3]; /* its box */
    const double *p;   /* start vertex */
    double t[3];       /* edge vector */
    double at[3];      /* |t| componentwise */
    double tprev[3];   /* v_i - v_{i-1} */
    double atprev[3];
    double tt;         /* |t|^2 */
    double tl;         /* |t| */
    double pad;        /* TR_NSEARCH_SLAB: how far the slab reaches past each end */
    int last;          /* last edge of an open component: no "front" */
} query_edge;

/* Interval of (y - p).u over a box, widened for rounding. */
static inline void box_project(const double *m, const double *r, const double *p, const double *u,
                               const double *au, double *pmin, double *pmax)
{
    double c = 0.0, w = 0.0, scale = 0.0;
    for (int k = 0; k < 3; k++) {
        double d = m[k] - p[k];
        c += d * u[k];
        w += r[k] * au[k];
        scale += fabs(d) * au[k];
    }
    double slack = 1e-10 * (scale + w);
    *pmin = c - w - slack;
    *pmax = c + w + slack;
}

/* Can a box hold a point y doubly critical for edge q? Such a y has
 * 0 < (y-p).t < |t|^2 (interior), or (y-p).t <= 0 and (y-p).tprev >= 0
 * (normal wedge at the start vertex); the end vertex belongs to the next
 * edge, except on the last edge of an open component. */
static inline int box_may_be_critical(const query_edge *q, const double *m, const double *r)
{
    double tmin, tmax;
    box_project(m, r, q->p, q->t, q->at, &tmin, &tmax);
    if (!q->last && tmin >= q->tt)
        return 0;
    if (tmax <= 0) {
        double pmin, pmax;
        box_project(m, r, q->p, q->tprev, q->atprev, &pmin, &pmax);
        if (pmax < 0)
            return 0;
    }
    return 1;
}

/* Can a box hold a point y with (y - p).t/|t| in [-pad, |t| + pad]? */
static inline int box_may_be_in_slab(const query_edge *q, const double *m, const double *r)
{
    double tmin, tmax;
    box_project(m, r, q->p, q->t, q->at, &tmin, &tmax);
    double reach = q->pad * q->tl;
    return tmax >= -reach && tmin <= q->tt + reach;
}

static inline int box_may_match(const query_edge *q, unsigned flags, const double *m, const double *r)
{
    if (flags & TR_NSEARCH_SLAB)
        return box_may_be_in_slab(q, m, r);
    if (flags & TR_NSEARCH_CRITICAL)
        return box_may_be_critical(q, m, r);
    return 1;
}

typedef struct stack_entry {
    uint32_t id;
    double d2;
} stack_entry;

static void query_setup(const tr_nsearch *s, size_t i, double pad, query_edge *q)
{
    const double *x = s->c->x;
    edge_centre_half(s, i, q->m, q->r);
    q->p = x + 3 * s->ea[i];
    v3_sub(q->t, x + 3 * s->eb[i], q->p);
    v3_sub(q->tprev, q->p, x + 3 * s->eprev[i]);
    for (int a = 0; a < 3; a++) {
        q->at[a] = fabs(q->t[a]);
        q->atprev[a] = fabs(q->tprev[a]);
    }
    q->tt = v3_dot(q->t, q->t);
    q->tl = sqrt(q->tt);
    q->pad = pad;
    int k = s->ecomp[i];
    q->last = !s->c->closed[k] && i + 1 == s->estart[k + 1];
}

/* TR_NSEARCH_SLAB prunes from both sides: besides edge j's box meeting
 * edge i's slab, edge i's box must meet edge j's (a strand crossing edge i's
 * normal plane at a steep angle lies in that plane's slab for a long way,
 * but only near its closest point is the strut normal to it as well). The
 * run slabs of all leaves are set up once per search for that. */
typedef struct slab_index {
    struct block_query *leaf; /* per node id; used for leaves */
    unsigned char *ok;        /* the leaf's run slab could be formed */
    double pad;
} slab_index;

static int edge_meets_slab_of(const tr_nsearch *s, const slab_index *si, size_t j, const double *m,
                              const double *r);
static int box_meets_leaf_slab(const slab_index *si, uint32_t id, const double *m, const double *r);

/* The edges j < jend of one leaf against query edge i. */
static int query_leaf(const tr_nsearch *s, const query_edge *q, size_t i, size_t jend, const node_t *n,
                      size_t min_gap, unsigned flags, const slab_index *si, double *cutoff, tr_pair_fn fn,
                      void *ctx)
{
    size_t b = n->b < jend ? n->b : jend;
    for (size_t j = n->a; j < b; j++) {
        if (tr_nsearch_excluded(s, i, j, min_gap))
            continue;
        double em[3], er[3];
        edge_centre_half(s, j, em, er);
        double cut = *cutoff * (1.0 + PRUNE_SLACK);
        if (box_dist2(q->m, q->r, em, er) > cut * cut)
            continue;
        if (!box_may_match(q, flags, em, er))
            continue;
        if (si && !edge_meets_slab_of(s, si, j, q->m, q->r))
            continue;
        int rc = fn(ctx, i, j, cutoff);
        if (rc)
            return rc;
    }
    return 0;
}

/* Pushes the children of n that may hold some j < jend and lie within the
 * cutoff of the box (m, r), the nearer one on top. */
static int push_children(const tr_nsearch *s, const node_t *n, const double *m, const double *r,
                         size_t jend, double cut2, stack_entry *stack, int *sp)
{
    uint32_t ch[2] = {n->left, n->right};
    double d2[2] = {INFINITY, INFINITY};
    for (int c = 0; c < 2; c++)
        if (s->node[ch[c]].a < jend)
            d2[c] = box_dist2(m, r, s->node[ch[c]].m, s->node[ch[c]].r);
    if (*sp + 2 > STACK_DEPTH)
        return -1; /* cannot happen: the depth is log2(N) */
    int near = d2[1] < d2[0];
    for (int c = 0; c < 2; c++) {
        int w = c == 0 ? 1 - near : near; /* farther first, nearer on top */
        if (d2[w] <= cut2) {
            stack[*sp].id = ch[w];
            stack[(*sp)++].d2 = d2[w];
        }
    }
    return 0;
}

/* One query edge walks the tree from the root, partners j < jend. */
static int query_edge_walk(const tr_nsearch *s, size_t i, size_t jend, size_t min_gap, unsigned flags,
                           double pad, const slab_index *si, double *cutoff, tr_pair_fn fn, void *ctx)
{
    stack_entry stack[STACK_DEPTH];
    query_edge q;
    query_setup(s, i, pad, &q);
    int k = s->ecomp[i];
    int sp = 0;
    stack[sp].id = 0;
    stack[sp++].d2 = box_dist2(q.m, q.r, s->node[0].m, s->node[0].r);
    while (sp > 0) {
        --sp;
        const node_t *n = &s->node[stack[sp].id];
        double cut = *cutoff * (1.0 + PRUNE_SLACK);
        double cut2 = cut * cut;
        /* The cutoff may have dropped since this node was pushed. */
        if (stack[sp].d2 > cut2)
            continue;
        if (n->a >= jend)
            continue;
        size_t b = n->b < jend ? n->b : jend;
        if (n->comp == k && range_excluded(s, k, i, i, n->a, b, min_gap))
            continue;
        if (!box_may_match(&q, flags, n->m, n->r))
            continue;
        if (n->left == 0) {
            if (si && !box_meets_leaf_slab(si, stack[sp].id, q.m, q.r))
                continue;
            int rc = query_leaf(s, &q, i, jend, n, min_gap, flags, si, cutoff, fn, ctx);
            if (rc)
                return rc;
            continue;
        }
        if (push_children(s, n, q.m, q.r, jend, cut2, stack, &sp))
            return -1;
    }
    return 0;
}

/* A run of consecutive edges of one component (a leaf) as one query: the
 * union of their normal slabs and wedges, for partners within distance D,
 * lies in a slab along the chord u of the run,
 *   (y - p0).u in [min_k (p_k - p0).u - w, max_k ((p_k - p0).u + l_k) + w],
 *   w = (D + l_max) max_k |u - tau_k|,
 * because (y - p_k).tau_k is in [0, l_k] on edge k's slab (and <= 0 <= the
 * previous edge's along its wedge) and |y - p_k| <= D + l_k. With
 * TR_NSEARCH_SLAB each edge's slab reaches pad further at both ends, and so
 * does the run's. Returns 0 if the run cannot be treated so (a fold-back),
 * else fills lo, hi. */
typedef struct block_query {
    double m[3], r[3]; /* box of the run */
    const double *p0;
    double u[3], au[3];
    double lo, hi;
} block_query;

static int block_setup(const tr_nsearch *s, const node_t *leaf, double D, double pad, block_query *bq)
{
    const double *x = s->c->x;
    bq->m[0] = leaf->m[0], bq->m[1] = leaf->m[1], bq->m[2] = leaf->m[2];
    bq->r[0] = leaf->r[0], bq->r[1] = leaf->r[1], bq->r[2] = leaf->r[2];
    bq->p0 = x + 3 * s->ea[leaf->a];
    double ch[3];
    v3_sub(ch, x + 3 * s->eb[leaf->b - 1], bq->p0);
    double L = v3_norm(ch);
    if (!(L > 0))
        return 0;
    v3_scale(bq->u, 1.0 / L, ch);
    for (int a = 0; a < 3; a++)
        bq->au[a] = fabs(bq->u[a]);
    double lo = 0.0, hi = -INFINITY, lmax = 0.0, dmax = 0.0;
    int open_end = 0;
    for (size_t e = leaf->a; e <= leaf->b; e++) {
        /* e == leaf->b stands for the edge before the run (its wedge). */
        const double *pa = x + 3 * (e < leaf->b ? s->ea[e] : s->eprev[leaf->a]);
        const double *pb = x + 3 * (e < leaf->b ? s->eb[e] : s->ea[leaf->a]);
        double t[3];
        v3_sub(t, pb, pa);
        double l = v3_norm(t);
        if (!(l > 0))
            return 0;
        double du[3] = {t[0] / l - bq->u[0], t[1] / l - bq->u[1], t[2] / l - bq->u[2]};
        double dn = v3_norm(du);
        if (dn > 0.5)
            return 0; /* the run turns too much for one chord */
        dmax = dn > dmax ? dn : dmax;
        if (e == leaf->b)
            continue;
        lmax = l > lmax ? l : lmax;
        double w[3];
        v3_sub(w, pa, bq->p0);
        double pr = v3_dot(w, bq->u);
        lo = pr < lo ? pr : lo;
        hi = pr + l > hi ? pr + l : hi;
        int k = s->ecomp[e];
        if (!s->c->closed[k] && e + 1 == s->estart[k + 1])
            open_end = 1;
    }
    double wdt = (D + lmax) * dmax;
    double slack = 1e-10 * (L + lmax + D);
    bq->lo = lo - wdt - pad - slack;
    bq->hi = open_end ? INFINITY : hi + wdt + pad + slack;
    return 1;
}

static int block_may_be_critical(const block_query *bq, const double *m, const double *r)
{
    double pmin, pmax;
    box_project(m, r, bq->p0, bq->u, bq->au, &pmin, &pmax);
    return pmax >= bq->lo && pmin <= bq->hi;
}

static int box_meets_leaf_slab(const slab_index *si, uint32_t id, const double *m, const double *r)
{
    return !si->ok[id] || block_may_be_critical(&si->leaf[id], m, r);
}

static int edge_meets_slab_of(const tr_nsearch *s, const slab_index *si, size_t j, const double *m,
                              const double *r)
{
    query_edge qj;
    query_setup(s, j, si->pad, &qj);
    return box_may_be_in_slab(&qj, m, r);
}

static void slab_index_free(slab_index *si)
{
    free(si->leaf);
    free(si->ok);
}

static int slab_index_build(const tr_nsearch *s, double D, double pad, slab_index *si)
{
    si->pad = pad;
    si->leaf = malloc(s->nnodes * sizeof *si->leaf);
    si->ok = calloc(s->nnodes, 1);
    if (!si->leaf || !si->ok) {
        slab_index_free(si);
        return -1;
    }
    for (size_t id = 0; id < s->nnodes; id++)
        if (s->node[id].left == 0 && s->node[id].comp >= 0)
            si->ok[id] = (unsigned char)block_setup(s, &s->node[id], D, pad, &si->leaf[id]);
    return 0;
}

typedef struct leaf_list {
    uint32_t *id;
    size_t n, cap;
} leaf_list;

/* Walks the tree once for the run of edges in `leaf`, collecting the leaves
 * that may hold a partner of any of its edges, then tests each edge of the
 * run against those leaves only. */
static int query_block(const tr_nsearch *s, const node_t *leaf, size_t min_gap, unsigned flags,
                       double pad, const slab_index *si, double *cutoff, tr_pair_fn fn, void *ctx,
                       leaf_list *cand)
{
    block_query bq;
    if (!block_setup(s, leaf, *cutoff, pad, &bq)) {
        for (size_t i = leaf->a; i < leaf->b; i++) {
            int rc = query_edge_walk(s, i, i, min_gap, flags, pad, si, cutoff, fn, ctx);
            if (rc)
                return rc;
        }
        return 0;
    }
    stack_entry stack[STACK_DEPTH];
    size_t iend = leaf->b; /* partners j < iend - 1 at most */
    size_t i0 = leaf->a, i1 = leaf->b - 1;
    cand->n = 0;
    int sp = 0;
    stack[sp].id = 0;
    stack[sp++].d2 = box_dist2(bq.m, bq.r, s->node[0].m, s->node[0].r);
    while (sp > 0) {
        --sp;
        const node_t *n = &s->node[stack[sp].id];
        double cut = *cutoff * (1.0 + PRUNE_SLACK);
        double cut2 = cut * cut;
        if (stack[sp].d2 > cut2)
            continue;
        if (n->comp == leaf->comp && range_excluded(s, n->comp, i0, i1, n->a, n->b, min_gap))
            continue;
        if (!block_may_be_critical(&bq, n->m, n->r))
            continue;
        if (n->left == 0) {
            if (si && !box_meets_leaf_slab(si, stack[sp].id, bq.m, bq.r))
                continue;
            if (cand->n == cand->cap) {
                size_t cap = cand->cap ? 2 * cand->cap : 256;
                uint32_t *g = realloc(cand->id, cap * sizeof *g);
                if (!g)
                    return -1;
                cand->id = g;
                cand->cap = cap;
            }
            cand->id[cand->n++] = (uint32_t)(n - s->node);
            continue;
        }
        if (push_children(s, n, bq.m, bq.r, iend - 1, cut2, stack, &sp))
            return -1;
    }
    for (size_t i = leaf->a; i < leaf->b; i++) {
        if (i == 0)
            continue;
        query_edge q;
        query_setup(s, i, pad, &q);
        int k = s->ecomp[i];
        for (size_t c = 0; c < cand->n; c++) {
            const node_t *n = &s->node[cand->id[c]];
            if (n->a >= i)
                continue;
            double cut = *cutoff * (1.0 + PRUNE_SLACK);
            if (box_dist2(q.m, q.r, n->m, n->r) > cut * cut)
                continue;
            size_t b = n->b < i ? n->b : i;
            if (n->comp == k && range_excluded(s, k, i, i, n->a, b, min_gap))
                continue;
            if (!box_may_match(&q, flags, n->m, n->r))
                continue;
            if (si && !box_meets_leaf_slab(si, cand->id[c], q.m, q.r))
                continue;
            int rc = query_leaf(s, &q, i, i, n, min_gap, flags, si, cutoff, fn, ctx);
            if (rc)
                return rc;
        }
    }
    return 0;
}

static int pairs_walk(const tr_nsearch *s, double *cutoff, size_t min_gap, unsigned flags, double pad,
                      tr_pair_fn fn, void *ctx)
{
    if (s->ne < 2)
        return 0;
    /* Runs of edges (the leaves, in order) are queried together once the
     * cutoff is finite and the run lies on one component; before that, and
     * without the critical-point pruning, each edge walks the tree itself. */
    leaf_list cand = {0};
    slab_index si_store = {0}, *si = NULL;
    if ((flags & TR_NSEARCH_SLAB) && isfinite(*cutoff)) {
        if (slab_index_build(s, *cutoff, pad, &si_store))
            return -1;
        si = &si_store;
    }
    int rc = 0;
    size_t leaves = 0;
    for (size_t id = 0; id < s->nnodes && rc == 0; id++) {
        const node_t *leaf = &s->node[id];
        if (leaf->left != 0)
            continue;
        if (s->bound && ++leaves % 64 == 0 && tr_deadline_passed(s->bound)) {
            rc = TR_NSEARCH_STOPPED;
            break;
        }
        if ((flags & (TR_NSEARCH_CRITICAL | TR_NSEARCH_SLAB)) && isfinite(*cutoff) && leaf->comp >= 0 &&
            leaf->b - leaf->a > 1) {
            rc = query_block(s, leaf, min_gap, flags, pad, si, cutoff, fn, ctx, &cand);
        } else {
            for (size_t i = leaf->a; i < leaf->b && rc == 0; i++)
                if (i > 0)
                    rc = query_edge_walk(s, i, i, min_gap, flags, pad, si, cutoff, fn, ctx);
        }
    }
    free(cand.id);
    if (si)
        slab_index_free(si);
    return rc;
}

int tr_nsearch_pairs(const tr_nsearch *s, double *cutoff, size_t min_gap, unsigned flags,
                     tr_pair_fn fn, void *ctx)
{
    return pairs_walk(s, cutoff, min_gap, flags & ~(unsigned)TR_NSEARCH_SLAB, 0.0, fn, ctx);
}

int tr_nsearch_pairs_slab(const tr_nsearch *s, double cutoff, size_t min_gap, double pad, tr_pair_fn fn,
                          void *ctx)
{
    if (!(pad >= 0.0) || !isfinite(cutoff))
        return pairs_walk(s, &cutoff, min_gap, 0, 0.0, fn, ctx);
    return pairs_walk(s, &cutoff, min_gap, TR_NSEARCH_SLAB, pad, fn, ctx);
}

int tr_nsearch_edge(const tr_nsearch *s, size_t i, double *cutoff, size_t min_gap, unsigned flags,
                    tr_pair_fn fn, void *ctx)
{
    if (i >= s->ne)
        return 0;
    return query_edge_walk(s, i, s->ne, min_gap, flags & ~(unsigned)TR_NSEARCH_SLAB, 0.0, NULL, cutoff, fn,
                           ctx);
}

int tr_nsearch_pairs_brute(const tr_nsearch *s, double *cutoff, size_t min_gap, unsigned flags,
                           tr_pair_fn fn, void *ctx)
{
    (void)flags; /* every non-excluded pair is offered; the callback decides */
    for (size_t i = 1; i < s->ne; i++)
        for (size_t j = 0; j < i; j++) {
            if (tr_nsearch_excluded(s, i, j, min_gap))
                continue;
            int rc = fn(ctx, i, j, cutoff);
            if (rc)
                return rc;
        }
    return 0;
}
