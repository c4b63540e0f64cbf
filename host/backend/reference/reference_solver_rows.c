/* This file contains the serial reference backend's strut_rows (backend.h):
 * the second-order solver's strut rows, pair by pair in list order with the
 * body the solver's own serial path runs (kernels/segment_distance.h), so
 * that a solver driving this backend takes the same steps to the bit. */
#include <math.h>
#include <stdlib.h>

#include "backend/reference/reference_state.h"
#include "segment_distance.h"

/* The pair's four vertices' coordinates, p0 p1 q0 q1. */
static void gather(const tr_strut_rows *r, size_t p, double *x12)
{
    for (int j = 0; j < 4; j++)
        for (int c = 0; c < 3; c++)
            x12[3 * j + c] = r->x[3 * r->quad[4 * p + (size_t)j] + (size_t)c];
}

/* Room for n pairs' distances and block numbers. */
static int reserve_pairs(ref_state *s, size_t n, tr_error *err)
{
    if (n <= s->sr_np && s->sr_d)
        return TR_OK;
    size_t cap = n + n / 2 + 16;
    double *d = realloc(s->sr_d, cap * sizeof *d);
    if (d)
        s->sr_d = d;
    int *sel = d ? realloc(s->sr_sel, cap * sizeof *sel) : NULL;
    if (!sel)
        return tr_fail(err, TR_ENOMEM, "out of memory (strut rows, %zu pairs)", n);
    s->sr_sel = sel;
    s->sr_np = cap;
    return TR_OK;
}

/* Room for block k (gradient and, with hess, Hessian), grown by half as
 * the selection walks the list, so that a list with few selected rows (a
 * tenth on a tight knot) holds few blocks. */
static int grow_blocks(double **buf, size_t *cap, size_t k, size_t per, tr_error *err)
{
    if (k < *cap)
        return TR_OK;
    size_t c = k + k / 2 + 64;
    double *b = realloc(*buf, per * c * sizeof *b);
    if (!b)
        return tr_fail(err, TR_ENOMEM, "out of memory (strut rows, %zu blocks)", c);
    *buf = b;
    *cap = c;
    return TR_OK;
}

static int reserve_block(ref_state *s, size_t k, int hess, tr_error *err)
{
    int rc = grow_blocks(&s->sr_g, &s->sr_gcap, k, 12, err);
    if (rc == TR_OK && hess)
        rc = grow_blocks(&s->sr_h, &s->sr_hcap, k, 144, err);
    return rc;
}

int rb_strut_rows(void *sp, tr_strut_rows *r, tr_error *err)
{
    ref_state *s = sp;
    double x12[12];
    if (r->mode == TR_ROWS_VALUE) {
        double f = r->sum0, dmin = INFINITY;
        for (size_t p = 0; p < r->np; p++) {
            gather(r, p, x12);
            double d = tr_strut_row_derivs(x12, NULL, NULL, 0, 0), pi;
            dmin = fmin(dmin, d);
            f += tr_phr_ineq_term(d - r->dist, r->lam[p], r->mu, &pi);
        }
        r->sum = f;
        r->dmin = dmin;
        return TR_OK;
    }
    if (r->mode != TR_ROWS_GRAD && r->mode != TR_ROWS_HESS)
        return tr_fail(err, TR_EINVAL, "strut_rows: unknown mode %d", r->mode);
    int hess = r->mode == TR_ROWS_HESS;
    int rc = reserve_pairs(s, r->np, err);
    if (rc)
        return rc;
    size_t k = 0;
    double f = r->sum0, dmin = INFINITY;
    for (size_t p = 0; p < r->np; p++) {
        gather(r, p, x12);
        double d = tr_strut_row_derivs(x12, NULL, NULL, 0, 0), pi;
        s->sr_d[p] = d;
        dmin = fmin(dmin, d);
        f += tr_phr_ineq_term(d - r->dist, r->lam[p], r->mu, &pi);
        if (!(pi > 0.0 || d - r->dist < r->band)) {
            s->sr_sel[p] = -1;
            continue;
        }
        if ((rc = reserve_block(s, k, hess, err)))
            return rc;
        tr_strut_row_derivs(x12, s->sr_g + 12 * k, hess ? s->sr_h + 144 * k : NULL, 1, hess);
        s->sr_sel[p] = (int)k++;
    }
    r->nsel = k;
    r->sum = f;
    r->dmin = dmin;
    r->d = s->sr_d;
    r->sel = s->sr_sel;
    r->g = s->sr_g;
    r->h = hess ? s->sr_h : NULL;
    return TR_OK;
}
