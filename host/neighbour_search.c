#include "neighbour_search.h"

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
    double lo[3], hi[3];
    size_t a, b;   /* edges [a, b) */
    int comp;      /* the component if all edges share one, else -1 */
    uint32_t left; /* child indices; left == 0 marks a leaf (the root is 0) */
    uint32_t right;
} node_t;

static void edge_box(const tr_nsearch *s, size_t e, double *lo, double *hi)
{
    const double *p = s->c->x + 3 * s->ea[e], *q = s->c->x + 3 * s->eb[e];
    for (int k = 0; k < 3; k++) {
        lo[k] = fmin(p[k], q[k]);
        hi[k] = fmax(p[k], q[k]);
    }
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
        if (n->left == 0) {
            edge_box(s, n->a, n->lo, n->hi);
            for (size_t e = n->a + 1; e < n->b; e++) {
                double lo[3], hi[3];
                edge_box(s, e, lo, hi);
                for (int k = 0; k < 3; k++) {
                    n->lo[k] = fmin(n->lo[k], lo[k]);
                    n->hi[k] = fmax(n->hi[k], hi[k]);
                }
            }
        } else {
            const node_t *l = &s->node[n->left], *r = &s->node[n->right];
            for (int k = 0; k < 3; k++) {
                n->lo[k] = fmin(l->lo[k], r->lo[k]);
                n->hi[k] = fmax(l->hi[k], r->hi[k]);
            }
        }
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

static double box_dist2(const double *alo, const double *ahi, const double *blo, const double *bhi)
{
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) {
        double g = fmax(blo[k] - ahi[k], alo[k] - bhi[k]);
        if (g > 0)
            d2 += g * g;
    }
    return d2;
}

/* What a query needs to know about edge i for the critical-point pruning. */
typedef struct query_edge {
    double lo[3], hi[3];
    const double *p;  /* start vertex */
    double t[3];      /* edge vector */
    double tprev[3];  /* v_i - v_{i-1} */
    double tt;        /* |t|^2 */
    int last;         /* last edge of an open component: no "front" */
} query_edge;

/* Interval of (y - p).u over a box, widened for rounding. */
static void box_project(const double *lo, const double *hi, const double *p, const double *u,
                        double *pmin, double *pmax)
{
    double c = 0.0, w = 0.0, scale = 0.0;
    for (int k = 0; k < 3; k++) {
        double m = 0.5 * (lo[k] + hi[k]), r = 0.5 * (hi[k] - lo[k]);
        c += (m - p[k]) * u[k];
        w += r * fabs(u[k]);
        scale += (fabs(m - p[k]) + r) * fabs(u[k]);
    }
    double slack = 1e-10 * scale;
    *pmin = c - w - slack;
    *pmax = c + w + slack;
}

/* Can a box hold a point y doubly critical for edge q? Such a y has
 * 0 < (y-p).t < |t|^2 (interior), or (y-p).t <= 0 and (y-p).tprev >= 0
 * (normal wedge at the start vertex); the end vertex belongs to the next
 * edge, except on the last edge of an open component. */
static int box_may_be_critical(const query_edge *q, const double *lo, const double *hi)
{
    double tmin, tmax;
    box_project(lo, hi, q->p, q->t, &tmin, &tmax);
    if (!q->last && tmin >= q->tt)
        return 0;
    if (tmax <= 0) {
        double pmin, pmax;
        box_project(lo, hi, q->p, q->tprev, &pmin, &pmax);
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
        edge_box(s, i, q.lo, q.hi);
        q.p = x + 3 * s->ea[i];
        v3_sub(q.t, x + 3 * s->eb[i], q.p);
        v3_sub(q.tprev, q.p, x + 3 * s->eprev[i]);
        q.tt = v3_dot(q.t, q.t);
        int k = s->ecomp[i];
        q.last = !s->c->closed[k] && i + 1 == s->estart[k + 1];
        int sp = 0;
        stack[sp].id = 0;
        stack[sp++].d2 = box_dist2(q.lo, q.hi, s->node[0].lo, s->node[0].hi);
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
            if ((flags & TR_NSEARCH_CRITICAL) && !box_may_be_critical(&q, n->lo, n->hi))
                continue;
            if (n->left == 0) {
                for (size_t j = n->a; j < b; j++) {
                    if (tr_nsearch_excluded(s, i, j, min_gap))
                        continue;
                    double lo[3], hi[3];
                    edge_box(s, j, lo, hi);
                    cut = *cutoff * (1.0 + PRUNE_SLACK);
                    if (box_dist2(q.lo, q.hi, lo, hi) > cut * cut)
                        continue;
                    if ((flags & TR_NSEARCH_CRITICAL) && !box_may_be_critical(&q, lo, hi))
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
                    d2[c] = box_dist2(q.lo, q.hi, s->node[ch[c]].lo, s->node[ch[c]].hi);
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
