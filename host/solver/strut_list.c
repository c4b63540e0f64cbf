/* This file contains the strut list: the edge pairs near a local minimum of their distance, rebuilt as the rope moves. */
#include "solver/newton_internal.h"

#include <stdlib.h>
#include <string.h>

#include "segment_distance.h"

/* the distance between edges a and b at the positions the list was built at */
static double pair_dist(const solver *s, size_t a, size_t b)
{
    double sp, tp;
    const double *x = s->w.x;
    return tr_segment_distance(x + 3 * a, x + 3 * s->next[a], x + 3 * b, x + 3 * s->next[b], &sp, &tp);
}

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

/* Of the pairs within the cutoff (sorted), keeps those within NEAR_MIN
 * places along either strand of a local minimum of the distance: a strand
 * pair in contact has ~1/edge pairs within any fixed cutoff, but the
 * constraint is the distance between the strands, which the local minima
 * carry; their neighbours keep the contact from slipping between list
 * rebuilds, which follow the motion (minimise). */
#define NEAR_MIN 2
static size_t keep_near_minima(solver *s, strut_row *r, size_t n)
{
    unsigned char *keep = calloc(n ? n : 1, 1);
    if (!keep)
        return n; /* keep them all: slower, as correct */
    for (size_t i = 0; i < n; i++) {
        if (!is_local_min(s, r[i].a, r[i].b, pair_dist(s, r[i].a, r[i].b)))
            continue;
        /* mark (a', b') with a' within NEAR_MIN of a and b' within NEAR_MIN of b */
        size_t av[2 * NEAR_MIN + 1], bv[2 * NEAR_MIN + 1];
        int na = 0, nb = 0;
        av[na++] = r[i].a;
        bv[nb++] = r[i].b;
        for (int side = 0; side < 2; side++) {
            size_t u = r[i].a, v = r[i].b;
            for (int g = 0; g < NEAR_MIN; g++) {
                u = u == NONE ? NONE : (side ? s->next[u] : s->prev[u]);
                v = v == NONE ? NONE : (side ? s->next[v] : s->prev[v]);
                if (u != NONE && s->next[u] != NONE)
                    av[na++] = u;
                if (v != NONE && s->next[v] != NONE)
                    bv[nb++] = v;
            }
        }
        for (int ia = 0; ia < na; ia++)
            for (int ib = 0; ib < nb; ib++) {
                strut_row q = {.a = av[ia] < bv[ib] ? av[ia] : bv[ib], .b = av[ia] < bv[ib] ? bv[ib] : av[ia]};
                strut_row *hit = bsearch(&q, r, n, sizeof *r, tr_strut_pair_cmp);
                if (hit)
                    keep[hit - r] = 1;
            }
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (keep[i])
            r[m++] = r[i];
    free(keep);
    return m;
}

/* Rebuilds the strut list at y, carrying the multipliers of kept pairs. */
int tr_newton_i_rebuild(solver *s, const double *y, tr_error *err)
{
    memcpy(s->w.x, y, 3 * s->nv * sizeof *y);
    tr_nsearch_refit(&s->ns);
    int rc = tr_strut_candidates(&s->ns, s->w.x, s->next, s->gap, s->nc, 2.0 + s->p->skin, &s->sp, &s->nsp, err);
    if (rc)
        return rc;
    s->nsp = keep_near_minima(s, s->sp, s->nsp);
    free(s->pi_s);
    s->pi_s = calloc(s->nsp ? s->nsp : 1, sizeof *s->pi_s);
    if (!s->pi_s)
        return tr_fail(err, TR_ENOMEM, "out of memory (strut list)");
    return TR_OK;
}
