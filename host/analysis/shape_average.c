/* This file contains the m-averaged knot: block averages of m consecutive vertices at equal
 * arclength (shape_average.h). */
#include "analysis/shape_average.h"

#include <stdlib.h>
#include <string.h>

#include "curve/polyline.h"

void tr_averaged_knot_free(tr_averaged_knot *k)
{
    if (!k)
        return;
    free(k->w);
    free(k->pos);
    memset(k, 0, sizeof *k);
}

int tr_shape_average(const double *x, size_t n, size_t m, size_t first, tr_averaged_knot *out,
                     tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (m < 1)
        return tr_fail(err, TR_EINVAL, "averaging block size m must be at least 1");
    if (n < 4 * m)
        return tr_fail(err, TR_EINVAL, "averaging %zu vertices in blocks of %zu leaves fewer than 4",
                       n, m);
    size_t nb = n / m, np = nb * m;
    double *s = malloc((n + 1) * sizeof *s);
    double *p = malloc(3 * np * sizeof *p);      /* the points that are averaged */
    double *lp = malloc(np * sizeof *lp);         /* their arclengths, unwrapped from `first` */
    out->w = malloc(3 * nb * sizeof *out->w);
    out->pos = malloc(nb * sizeof *out->pos);
    if (!s || !p || !lp || !out->w || !out->pos) {
        free(s), free(p), free(lp);
        tr_averaged_knot_free(out);
        return tr_fail(err, TR_ENOMEM, "out of memory averaging %zu vertices", n);
    }
    tr_polyline_arclength(x, n, s);
    double L = s[n];
    first %= n;
    if (np == n) {
        for (size_t j = 0; j < n; j++) {
            size_t i = (first + j) % n;
            memcpy(p + 3 * j, x + 3 * i, 3 * sizeof *p);
            lp[j] = s[i] + (i < first ? L : 0.0);
        }
    } else {
        for (size_t j = 0; j < np; j++) {
            lp[j] = s[first] + (double)j * L / (double)np;
            tr_polyline_point_at(x, n, s, lp[j], p + 3 * j);
        }
    }
    for (size_t k = 0; k < nb; k++) {
        double acc[3] = {0, 0, 0}, lacc = 0.0;
        for (size_t j = 0; j < m; j++) {
            for (int d = 0; d < 3; d++)
                acc[d] += p[3 * (k * m + j) + d];
            lacc += lp[k * m + j];
        }
        for (int d = 0; d < 3; d++)
            out->w[3 * k + d] = acc[d] / (double)m;
        out->pos[k] = tr_wrap(lacc / (double)m, L);
    }
    out->n = nb;
    out->m = m;
    out->L = L;
    free(s), free(p), free(lp);
    return TR_OK;
}
