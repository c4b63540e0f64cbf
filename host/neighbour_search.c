#include "neighbour_search.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vec3.h"

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

int tr_nsearch_build(tr_nsearch *s, const tr_curve *c, tr_error *err)
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
    s->node = malloc(maxnodes * sizeof *s->node);
    if (!s->ea || !s->eb || !s->eprev || !s->ecomp || !s->estart || !s->node) {
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
    if (ne > 0) {
        build_node(s, 0, ne);
        tr_nsearch_refit(s);
    }
    return TR_OK;
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

/* Are all edges j in [a, b) (all j < i, all in i's component) excluded? */
static int range_excluded(const tr_nsearch *s, size_t i, size_t a, size_t b, size_t min_gap)
{
    int k = s->ecomp[i];
    size_t dmax = i - a, dmin = i - (b - 1);
    if (dmax < min_gap)
        return 1;
    if (!s->c->closed[k])
        return 0;
    size_t m = s->estart[k + 1] - s->estart[k];
    return dmin + min_gap > m;
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

int tr_nsearch_pairs(const tr_nsearch *s, double *cutoff, size_t min_gap, unsigned flags,
                     tr_pair_fn fn, void *ctx)
{
    if (s->ne < 2)
        return 0;
    const double *x = s->c->x;
    struct {
        uint32_t id;
        double d2;
    } stack[STACK_DEPTH];
    for (size_t i = 1; i < s->ne; i++) {
        query_edge q;
        edge_centre_half(s, i, q.m, q.r);
        q.p = x + 3 * s->ea[i];
        v3_sub(q.t, x + 3 * s->eb[i], q.p);
        v3_sub(q.tprev, q.p, x + 3 * s->eprev[i]);
        for (int a = 0; a < 3; a++) {
            q.at[a] = fabs(q.t[a]);
            q.atprev[a] = fabs(q.tprev[a]);
        }
        q.tt = v3_dot(q.t, q.t);
        int k = s->ecomp[i];
        q.last = !s->c->closed[k] && i + 1 == s->estart[k + 1];
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
            size_t b = n->b < i ? n->b : i;
            if (n->comp == k && range_excluded(s, i, n->a, b, min_gap))
                continue;
            if ((flags & TR_NSEARCH_CRITICAL) && !box_may_be_critical(&q, n->m, n->r))
                continue;
            if (n->left == 0) {
                for (size_t j = n->a; j < b; j++) {
                    if (tr_nsearch_excluded(s, i, j, min_gap))
                        continue;
                    double em[3], er[3];
                    edge_centre_half(s, j, em, er);
                    cut = *cutoff * (1.0 + PRUNE_SLACK);
                    if (box_dist2(q.m, q.r, em, er) > cut * cut)
                        continue;
                    if ((flags & TR_NSEARCH_CRITICAL) && !box_may_be_critical(&q, em, er))
                        continue;
                    int rc = fn(ctx, i, j, cutoff);
                    if (rc)
                        return rc;
                }
                continue;
            }
            /* Children that start at or after i hold no j < i. The nearer
             * child goes on top, so it is looked at first and tightens the
             * cutoff before the farther one. */
            uint32_t ch[2] = {n->left, n->right};
            double d2[2] = {INFINITY, INFINITY};
            for (int c = 0; c < 2; c++)
                if (s->node[ch[c]].a < i)
                    d2[c] = box_dist2(q.m, q.r, s->node[ch[c]].m, s->node[ch[c]].r);
            if (sp + 2 > STACK_DEPTH)
                return -1; /* cannot happen: the depth is log2(N) */
            int near = d2[1] < d2[0];
            for (int c = 0; c < 2; c++) {
                int w = c == 0 ? 1 - near : near; /* farther first, nearer on top */
                if (d2[w] <= cut2) {
                    stack[sp].id = ch[w];
                    stack[sp++].d2 = d2[w];
                }
            }
        }
    }
    return 0;
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
