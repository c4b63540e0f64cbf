/* The vertex model of thickness (vertex_thickness.h). */
#include "oracle/vertex_thickness.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "geometry/neighbour_search.h"
#include "util/vec3.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The least distance between vertices that count, for one K, as a squared
 * distance and the pair realising it. */
typedef struct vertex_search {
    const tr_curve *c;
    const tr_nsearch *ns;
    size_t K;
    double best2;
    size_t vi, vj;
} vertex_search;

/* Whether vertices i and j (global indices) count as a pair for K. */
static int pair_counts(const tr_curve *c, size_t K, size_t i, size_t j)
{
    if (i == j)
        return 0;
    int ki = tr_curve_comp_of(c, i), kj = tr_curve_comp_of(c, j);
    if (ki != kj)
        return 1;
    size_t g = i > j ? i - j : j - i, n = tr_comp_nv(c, ki);
    if (c->closed[ki] && n - g < g)
        g = n - g; /* the shorter way round */
    return g >= K;
}

static void offer(vertex_search *S, size_t i, size_t j)
{
    double d2 = v3_dist2(S->c->x + 3 * i, S->c->x + 3 * j);
    if (d2 < S->best2) {
        S->best2 = d2;
        S->vi = i > j ? i : j;
        S->vj = i > j ? j : i;
    }
}

static int is_open_end(const tr_curve *c, size_t v)
{
    int k = tr_curve_comp_of(c, v);
    return !c->closed[k] && (v == c->start[k] || v + 1 == c->start[k + 1]);
}

/* Edge pairs from the tree stand for the pairs of their first vertices; the
 * open ends (which are no edge's first vertex, or whose bisector region is a
 * half space the slab does not hold) are looked at on their own. Vertex and
 * edge index gaps agree for first vertices, so the tree's exclusion by
 * min_gap = K is the vertex model's. */
static int slab_candidate(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    vertex_search *S = ctx;
    (void)cutoff;
    size_t i = S->ns->ea[ei], j = S->ns->ea[ej];
    if (!is_open_end(S->c, i) && !is_open_end(S->c, j))
        offer(S, i, j);
    return 0;
}

/* The same for the seed queries, which may lower the cutoff as they go: any
 * pair that counts bounds the least distance from above. */
static int seed_candidate(void *ctx, size_t ei, size_t ej, double *cutoff)
{
    vertex_search *S = ctx;
    offer(S, S->ns->ea[ei], S->ns->ea[ej]);
    double d = sqrt(S->best2);
    if (d < *cutoff)
        *cutoff = d;
    return 0;
}

static void search_brute(vertex_search *S)
{
    for (size_t i = 1; i < S->c->nv; i++)
        for (size_t j = 0; j < i; j++)
            if (pair_counts(S->c, S->K, i, j))
                offer(S, i, j);
}

/* |u_i - u_{i-1}| at the vertices with two edges (twice the sine of half the
 * turning angle), the largest, and the longest edge: they bound how far a
 * vertex's bisector slab leans from the slab of its outgoing edge. */
static void slab_lean(const tr_curve *c, double *du_max, double *e_max)
{
    *du_max = 0.0;
    *e_max = 0.0;
    for (int k = 0; k < c->ncomp; k++) {
        size_t v0 = c->start[k], n = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
        for (size_t l = 0; l < ne; l++)
        {
            double e[3];
            tr_curve_edge(c, v0 + l, v0 + (l + 1) % n, e);
            *e_max = fmax(*e_max, v3_norm(e));
        }
        size_t first = c->closed[k] ? 0 : 1, end = c->closed[k] ? n : n - 1;
        for (size_t l = first; l < end; l++) {
            double a[3], b[3], du[3];
            tr_curve_edge(c, v0 + (l + n - 1) % n, v0 + l, a);
            tr_curve_edge(c, v0 + l, v0 + (l + 1) % n, b);
            double la = v3_norm(a), lb = v3_norm(b);
            for (int q = 0; q < 3; q++)
                du[q] = b[q] / lb - a[q] / la;
            *du_max = fmax(*du_max, v3_norm(du));
        }
    }
}

/* The least distance for one K, without looking at all pairs:
 *  (a) pairs exactly K apart along a component, where the exclusion cuts a
 *      pair off from a neighbour that would be closer;
 *  (b) pairs with an end vertex of an open component, against every vertex;
 *  (c) the rest: if (i, j) is least and all of (i +- 1, j), (i, j +- 1)
 *      count, then |v_j - v_i| <= |v_j - v_{i+-1}|, so v_j lies in i's
 *      bisector slab, (y - v_i).u_{i-1} >= -|e_{i-1}|/2 and (y - v_i).u_i <=
 *      |e_i|/2, and within D (a bound on the least distance from (a), (b)
 *      and a few seed queries) of v_i. Then (y - v_i).u_i >= -|e_{i-1}|/2 -
 *      D |u_i - u_{i-1}|: y lies in edge i's slab stretched by pad =
 *      e_max/2 + D du_max, and likewise v_i in j's, which is what
 *      tr_nsearch_pairs_slab offers (a superset) in time linear in N. */
static int search_fast(vertex_search *S, double du_max, double e_max)
{
    const tr_curve *c = S->c;
    const tr_nsearch *ns = S->ns;
    size_t K = S->K;
    for (int k = 0; k < c->ncomp; k++) {
        size_t v0 = c->start[k], n = tr_comp_nv(c, k);
        /* (a): the shorter way round is K; K comes from the whole curve's
         * mean edge, so on a small component of a link it can exceed n,
         * where n - K would wrap (a vertex paired with itself) */
        if (c->closed[k] && K <= n / 2)
            for (size_t l = 0; l < n; l++)
                offer(S, v0 + (l + K) % n, v0 + l);
        else if (!c->closed[k] && K <= n - 1)
            for (size_t l = 0; l + K < n; l++)
                offer(S, v0 + l + K, v0 + l);
        if (!c->closed[k]) /* (b) */
            for (size_t e = 0; e < 2; e++) {
                size_t v = e ? c->start[k + 1] - 1 : v0;
                for (size_t j = 0; j < c->nv; j++)
                    if (pair_counts(c, K, v, j))
                        offer(S, v, j);
            }
    }
    /* The tree's min_gap: beyond the longest component every pair on one
     * component is excluded, and the tree's index arithmetic wants no more. */
    size_t nmax = 0;
    for (int k = 0; k < c->ncomp; k++)
        nmax = tr_comp_nv(c, k) > nmax ? tr_comp_nv(c, k) : nmax;
    size_t gap = K < nmax + 1 ? K : nmax + 1;
    /* Seeds, so that D is finite when pairs between components are all there
     * is: the partners of a few edges, nearest first. */
    double D = sqrt(S->best2);
    size_t step = ns->ne / 64 + 1;
    for (size_t i = 0; i < ns->ne; i += step)
        if (tr_nsearch_edge(ns, i, &D, gap, 0, seed_candidate, S))
            return TR_ENOMEM;
    D = sqrt(S->best2);
    if (!isfinite(D))
        return TR_OK; /* no pair counts */
    /* Rounding in the slab's directions is far below this margin. */
    double pad = (0.5 * e_max + D * du_max) * (1.0 + 1e-6) + 1e-12 * D;
    if (tr_nsearch_pairs_slab(ns, D, gap, pad, slab_candidate, S))
        return TR_ENOMEM;
    return TR_OK;
}

static size_t exclusion_of(double R, double e)
{
    if (!(R < INFINITY))
        return SIZE_MAX;
    double K = ceil(M_PI * R / e);
    if (!(K < (double)(SIZE_MAX / 2)))
        return SIZE_MAX;
    return K < 1.0 ? 1 : (size_t)K; /* a vertex never pairs with itself */
}

/* The vertex model in the curve's own frame (lengths in its units). */
static int measure_frame(const tr_curve *c, const tr_vertex_opts *opts, double length, double minrad,
                         tr_vertex_thickness *out)
{
    size_t ne = 0;
    for (int k = 0; k < c->ncomp; k++)
        ne += tr_comp_ne(c, k);
    double e = length / (double)ne;
    int brute = opts && opts->brute_force;
    tr_nsearch ns;
    double du_max = 0.0, e_max = 0.0;
    if (!brute) {
        tr_error err;
        if (tr_nsearch_build(&ns, c, &err))
            return TR_ENOMEM;
        slab_lean(c, &du_max, &e_max);
    }
    vertex_search S = {.c = c, .ns = brute ? NULL : &ns};
    /* Scale free: the largest R with MinRad >= R and d(K(R)) >= 2R. The least
     * distance d(K) does not fall as K grows, so from R = MinRad each
     * infeasible R gives way to R' = d(K(R)) / 2 < R, and every radius in
     * between is infeasible too (its K is at most K(R), its d at most 2R');
     * K falls at each such step, so this ends, in one or two steps on a
     * tight knot. A fixed radius is one pass. */
    int fixed = opts && opts->radius > 0;
    double R = fixed ? opts->radius : minrad;
    int rc = TR_OK;
    for (;;) {
        S.K = exclusion_of(R, e);
        S.best2 = INFINITY;
        S.vi = S.vj = 0;
        rc = brute ? (search_brute(&S), TR_OK) : search_fast(&S, du_max, e_max);
        if (rc || fixed)
            break;
        double half = 0.5 * sqrt(S.best2);
        if (half >= R)
            break;
        if (exclusion_of(half, e) == S.K) {
            R = half; /* feasible: d(K(R')) = 2R' */
            break;
        }
        R = half;
    }
    if (!brute)
        tr_nsearch_free(&ns);
    if (rc)
        return rc;
    out->edge = e;
    out->radius = R;
    out->exclusion = S.K;
    out->vertex_dmin = sqrt(S.best2);
    out->vi = S.vi;
    out->vj = S.vj;
    out->thickness = fmin(minrad, 0.5 * out->vertex_dmin);
    return TR_OK;
}

int tr_vertex_thickness_measure(const tr_curve *c, const tr_vertex_opts *opts, const tr_thickness *rawdon,
                                tr_vertex_thickness *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (opts && !(opts->radius >= 0 && opts->radius < INFINITY))
        return tr_fail(err, TR_EINVAL, "the rope radius must be finite and >= 0 (0: the thickness), got %g",
                       opts->radius);
    tr_thickness own;
    if (!rawdon) {
        int rc = tr_thickness_measure(c, NULL, &own, NULL, err);
        if (rc)
            return rc;
        rawdon = &own;
    }
    out->vertices = c->nv;
    out->length = rawdon->length;
    out->minrad = rawdon->minrad;
    out->minrad_vertex = rawdon->minrad_vertex;
    /* Measured where the thickness oracle measures (thickness.c): centred
     * and scaled by a power of two when the coordinates ask for it. */
    tr_curve_frame f;
    tr_curve_frame_of(c, &f);
    int rc;
    if (tr_curve_frame_is_identity(&f)) {
        rc = measure_frame(c, opts, out->length, out->minrad, out);
    } else {
        tr_curve s;
        if ((rc = tr_curve_to_frame(&s, c, &f, err)))
            return rc;
        tr_vertex_opts o = opts ? *opts : (tr_vertex_opts){0};
        o.radius = ldexp(o.radius, -f.e);
        rc = measure_frame(&s, &o, ldexp(out->length, -f.e), ldexp(out->minrad, -f.e), out);
        tr_curve_free(&s);
        double *len[] = {&out->edge, &out->radius, &out->vertex_dmin, &out->thickness};
        for (size_t i = 0; rc == TR_OK && i < sizeof len / sizeof *len; i++)
            *len[i] = ldexp(*len[i], f.e);
    }
    if (rc)
        return tr_fail(err, rc, "out of memory in the vertex-contact search");
    out->ropelength = out->length / out->thickness;
    return TR_OK;
}
