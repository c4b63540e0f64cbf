/* This file contains the strut list: the edge pairs near a local minimum of their distance, rebuilt as the rope moves. */
#include "solver/newton_internal.h"

#include <stdlib.h>
#include <string.h>

#include "geometry/neighbour_search.h"
#include "geometry/struts.h"

/* the distance of row (a, b) (edges, or their first vertices: contact_model.c)
 * at the positions the list was built at */
static double pair_dist(const solver *s, size_t a, size_t b) { return tr_newton_i_pair_distance(s, s->w.x, a, b); }

/* Is b a local minimum of d(a, .) along its strand, or a one of d(., b)? */
static int is_local_min(const solver *s, size_t a, size_t b, double d)
{
    size_t bn = s->next[b], bp = s->prev[b], an = s->next[a], ap = s->prev[a];
    int over_b = (bn == NONE || s->next[bn] == NONE || pair_dist(s, a, bn) >= d) &&
                 (bp == NONE || pair_dist(s, a, bp) >= d);
    int over_a = (an == NONE || s->next[an] == NONE || pair_dist(s, an, b) >= d) &&
                 (ap == NONE || pair_dist(s, ap, b) >= d);
    return over_b || over_a;
}

/* The list keeps the pairs within NEAR_MIN places along either strand of
 * a local minimum of the distance (within the cutoff): a strand pair in
 * contact has ~1/edge pairs within any fixed cutoff, but the constraint is
 * the distance between the strands, which the local minima carry; their
 * neighbours keep the contact from slipping between list rebuilds, which
 * follow the motion (minimise). The pairs within the cutoff are not stored
 * on the way: they are ~1/edge per edge in contact, so their number grows
 * like N^2 (some 1e8 pairs, 2.5 GB, at N = 38 400; at 102 400 a rebuild
 * took the solve from 15 to 23.5 GB), where the minima are a few per edge.
 * The search reports each pair once; only the local minima are kept, and
 * their neighbourhoods are added after. */
#define NEAR_MIN 2

typedef struct list_build {
    const solver *s;
    double cutoff;
    tr_strut_pair *out;
    size_t n, cap;
    int oom;
    const tr_deadline *bound; /* NULL: none */
    size_t calls;
    int stopped; /* the bound passed: 1 the clock, 2 a signal */
} list_build;

/* pairs the search reports between two looks at the clock */
#define LIST_CLOCK_EVERY (1u << 16)

/* edge v's index in the search's numbering (neighbour_search.h) */
static size_t edge_index(const solver *s, size_t v)
{
    int k = s->comp[v];
    return s->ns.estart[k] + (v - s->w.start[k]);
}

/* the search's callback: a pair within the cutoff that is a local minimum */
static int take_minimum(void *v, size_t ei, size_t ej, double *cutoff)
{
    (void)cutoff;
    list_build *lb = v;
    if (lb->bound && ++lb->calls % LIST_CLOCK_EVERY == 0 && (lb->stopped = tr_deadline_passed(lb->bound)))
        return 1;
    const solver *s = lb->s;
    const tr_nsearch *ns = &s->ns;
    if (tr_nsearch_excluded(ns, ei, ej, (size_t)s->gap[ns->ecomp[ei]]))
        return 0;
    size_t a = ns->ea[ei], b = ns->ea[ej];
    if (a > b) {
        size_t t = a;
        a = b;
        b = t;
    }
    double d = pair_dist(s, a, b);
    if (d < lb->cutoff && is_local_min(s, a, b, d) && tr_strut_pair_append(&lb->out, &lb->n, &lb->cap, a, b))
        lb->oom = 1;
    return lb->oom;
}

/* sorts the pairs and drops repeats */
static size_t sort_unique(tr_strut_pair *r, size_t n)
{
    if (n == 0)
        return 0;
    qsort(r, n, sizeof *r, tr_strut_pair_cmp);
    size_t m = 1;
    for (size_t i = 1; i < n; i++)
        if (tr_strut_pair_cmp(&r[i], &r[m - 1]) != 0)
            r[m++] = r[i];
    return m;
}

/* The list at s->w.x: the local minima, then every pair (a', b') within
 * NEAR_MIN of a minimum (a, b) along both strands that the search would
 * have reported (an edge each, not excluded, within the cutoff). */
static int build_list(solver *s, double cutoff, tr_strut_pair **list, size_t *n_list, const tr_deadline *bound,
                      tr_error *err)
{
    const tr_nsearch *ns = &s->ns;
    list_build lb = {.s = s, .cutoff = cutoff, .bound = bound};
    double cut = cutoff;
    int gmin = s->gap[0];
    for (int k = 1; k < s->nc; k++)
        gmin = s->gap[k] < gmin ? s->gap[k] : gmin;
    tr_nsearch_pairs(ns, &cut, (size_t)gmin, 0, take_minimum, &lb);
    if (lb.stopped) {
        free(lb.out);
        return tr_fail(err, TR_EINTERRUPTED, "the strut list of %zu vertices: %s before it was built", s->nv,
                       lb.stopped == 2 ? "stopped by a signal" : "the time limit came");
    }
    size_t nmin = sort_unique(lb.out, lb.n);
    lb.n = nmin;
    for (size_t i = 0; i < nmin && !lb.oom; i++) {
        size_t av[2 * NEAR_MIN + 1], bv[2 * NEAR_MIN + 1];
        int na = 0, nb = 0;
        size_t a0 = lb.out[i].a, b0 = lb.out[i].b;
        for (int side = 0; side < 2; side++) {
            size_t u = a0, v = b0;
            for (int g = 0; g < NEAR_MIN; g++) {
                u = u == NONE ? NONE : (side ? s->next[u] : s->prev[u]);
                v = v == NONE ? NONE : (side ? s->next[v] : s->prev[v]);
                if (u != NONE && s->next[u] != NONE)
                    av[na++] = u;
                if (v != NONE && s->next[v] != NONE)
                    bv[nb++] = v;
            }
        }
        av[na++] = a0;
        bv[nb++] = b0;
        for (int ia = 0; ia < na; ia++)
            for (int ib = 0; ib < nb; ib++) {
                size_t a = av[ia], b = bv[ib];
                if ((ia == na - 1 && ib == nb - 1) || a == b)
                    continue;
                size_t ea = edge_index(s, a);
                if (tr_nsearch_excluded(ns, ea, edge_index(s, b), (size_t)s->gap[ns->ecomp[ea]]))
                    continue;
                if (pair_dist(s, a < b ? a : b, a < b ? b : a) < cutoff &&
                    tr_strut_pair_append(&lb.out, &lb.n, &lb.cap, a, b))
                    lb.oom = 1;
            }
    }
    if (lb.oom) {
        free(lb.out);
        return tr_fail(err, TR_ENOMEM, "out of memory (strut list)");
    }
    lb.n = sort_unique(lb.out, lb.n);
    /* a pair already listed keeps its multiplier */
    tr_strut_pairs_carry(*list, *n_list, lb.out, lb.n);
    free(*list);
    *list = lb.out;
    *n_list = lb.n;
    return TR_OK;
}

/* Rebuilds the strut list at y, carrying the multipliers of kept pairs. */
int tr_newton_i_rebuild(solver *s, const double *y, const tr_deadline *bound, tr_error *err)
{
    memcpy(s->w.x, y, 3 * s->nv * sizeof *y);
    tr_nsearch_refit(&s->ns);
    int rc = build_list(s, 2.0 + s->p->skin, &s->sp, &s->nsp, bound, err);
    if (rc)
        return rc;
    free(s->pi_s);
    s->pi_s = calloc(s->nsp ? s->nsp : 1, sizeof *s->pi_s);
    if (!s->pi_s)
        return tr_fail(err, TR_ENOMEM, "out of memory (strut list)");
    return TR_OK;
}
