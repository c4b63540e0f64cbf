/* This file contains the exclusion gap, the strut gradient and the strut
 * candidate list (struts.h). */
#include "geometry/struts.h"

#include <math.h>
#include <stdlib.h>

#include "segment_distance.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int tr_exclusion_gap(double radius, double ebar)
{
    if (!(ebar > 0))
        return 2;
    double g = ceil(M_PI * radius / ebar);
    return g < 2.0 ? 2 : (g > 1e9 ? 1000000000 : (int)g);
}

void tr_strut_gradient(const double c[3], double s, double t, double d, double scale,
                       double g[4][3])
{
    for (int k = 0; k < 3; k++) {
        double n = scale * c[k] / d;
        g[0][k] = (1.0 - s) * n;
        g[1][k] = s * n;
        g[2][k] = -(1.0 - t) * n;
        g[3][k] = -t * n;
    }
}

int tr_strut_pair_cmp(const void *x, const void *y)
{
    const tr_strut_pair *a = x, *b = y;
    if (a->a != b->a)
        return a->a < b->a ? -1 : 1;
    return a->b < b->b ? -1 : (a->b > b->b);
}

int tr_strut_pair_append(tr_strut_pair **p, size_t *n, size_t *cap, size_t a, size_t b)
{
    if (*n == *cap) {
        size_t nc = *cap ? 2 * *cap : 1024;
        tr_strut_pair *g = realloc(*p, nc * sizeof *g);
        if (!g)
            return -1;
        *p = g;
        *cap = nc;
    }
    (*p)[(*n)++] = (tr_strut_pair){.a = a < b ? a : b, .b = a < b ? b : a, .lam = 0.0};
    return 0;
}

void tr_strut_pairs_carry(const tr_strut_pair *from, size_t nfrom, tr_strut_pair *to, size_t nto)
{
    size_t j = 0;
    for (size_t i = 0; i < nto; i++) {
        while (j < nfrom && tr_strut_pair_cmp(&from[j], &to[i]) < 0)
            j++;
        if (j < nfrom && tr_strut_pair_cmp(&from[j], &to[i]) == 0)
            to[i].lam = from[j].lam;
    }
}

typedef struct collect {
    const tr_nsearch *ns;
    const double *x;
    const size_t *next;
    const int *gap;
    tr_strut_pair *out;
    size_t n, cap;
    double cutoff;
    int oom;
} collect;

static int collect_pair(void *vc, size_t ei, size_t ej, double *cutoff)
{
    (void)cutoff;
    collect *cl = vc;
    const tr_nsearch *ns = cl->ns;
    if (tr_nsearch_excluded(ns, ei, ej, (size_t)cl->gap[ns->ecomp[ei]]))
        return 0;
    size_t a = ns->ea[ei], b = ns->ea[ej];
    double sp, tp;
    const double *x = cl->x;
    double d = tr_segment_distance(x + 3 * a, x + 3 * cl->next[a], x + 3 * b, x + 3 * cl->next[b], &sp, &tp);
    if (!(d < cl->cutoff))
        return 0;
    if (tr_strut_pair_append(&cl->out, &cl->n, &cl->cap, a, b)) {
        cl->oom = 1;
        return 1;
    }
    return 0;
}

int tr_strut_candidates(const tr_nsearch *ns, const double *x, const size_t *next, const int *gap, int ncomp,
                        double cutoff, tr_strut_pair **list, size_t *n_list, tr_error *err)
{
    collect cl = {.ns = ns, .x = x, .next = next, .gap = gap, .cutoff = cutoff};
    double cut = cutoff;
    int gmin = gap[0];
    for (int k = 1; k < ncomp; k++)
        gmin = gap[k] < gmin ? gap[k] : gmin;
    tr_nsearch_pairs(ns, &cut, (size_t)gmin, 0, collect_pair, &cl);
    if (cl.oom) {
        free(cl.out);
        return tr_fail(err, TR_ENOMEM, "out of memory (strut candidates)");
    }
    if (cl.n)
        qsort(cl.out, cl.n, sizeof *cl.out, tr_strut_pair_cmp);
    tr_strut_pairs_carry(*list, *n_list, cl.out, cl.n);
    free(*list);
    *list = cl.out;
    *n_list = cl.n;
    return TR_OK;
}
