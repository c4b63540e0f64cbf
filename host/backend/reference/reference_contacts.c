/* This file contains the serial reference's find_contacts (backend.h): the
 * candidate pairs from the tree over the edges (neighbour_search.h), in
 * both edges' partner lists. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/reference/reference_state.h"
#include "segment_distance.h"
#include "util/vec3.h"

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
int rb_find_contacts(void *sp, const tr_contact_params *prm, tr_contact_stats *out,
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
        rc = rb_ensure_rows(s, err);
    if (rc == TR_OK && out) {
        out->pairs = s->np;
        out->min_dist = w.mind;
    }
    if (rc != TR_OK)
        s->np = 0;
    return rc;
}

