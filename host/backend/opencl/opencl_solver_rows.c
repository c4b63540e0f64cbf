/* This file contains the OpenCL backend's strut_rows (backend.h): the
 * second-order solver's strut rows by the kernels of kernels/solver_rows.cl.
 * The solver's positions, pair list and multipliers come with every call
 * (they are the solver's, not the backend's uploaded curve), go to the
 * device, and what the Newton matrix needs comes back: every pair's
 * distance, and the gradient and Hessian blocks of the selected pairs only,
 * packed in list order (a tenth of the list on a tight knot: reading back
 * 144 reals per listed pair would cost more than computing them). */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/opencl_state.h"

void clb_rows_free(clb_rows *r)
{
    cl_mem *m[] = {&r->x, &r->quad, &r->lam, &r->d, &r->flag, &r->off, &r->g, &r->h, &r->psum, &r->pmin, &r->sc};
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        clb_release(m[i]);
    free(r->hquad);
    free(r->hoff);
    free(r->hsel);
    free(r->hd);
    free(r->hg);
    free(r->hh);
    memset(r, 0, sizeof *r);
}

/* Grows a host array to hold n elements of size sz (by half again). */
static int host_room(void **a, size_t *cap, size_t n, size_t sz, tr_error *err)
{
    if (n <= *cap && *a)
        return TR_OK;
    size_t c = n + n / 2 + 64;
    void *p = realloc(*a, c * sz);
    if (!p)
        return tr_fail(err, TR_ENOMEM, "out of memory (strut rows, %zu entries)", c);
    *a = p;
    *cap = c;
    return TR_OK;
}

/* Grows a device buffer to hold n elements of size sz (by half again;
 * its contents are not kept). */
static int dev_room(cl_state *s, cl_mem *m, size_t *cap, size_t n, size_t sz, tr_error *err)
{
    if (n <= *cap && *m)
        return TR_OK;
    size_t c = n + n / 2 + 64;
    *cap = 0;
    int rc = clb_buffer(s, m, c * sz, err);
    if (rc == TR_OK)
        *cap = c;
    return rc;
}

/* Positions, the pair list (as ints) and the multipliers to the device. */
static int upload(cl_state *s, const tr_strut_rows *q, tr_error *err)
{
    clb_rows *r = &s->rows;
    int rc = TR_OK;
    size_t np = q->np;
    if (q->nv > (size_t)INT_MAX / 3 || np > (size_t)INT_MAX / 144)
        return tr_fail(err, TR_EINVAL, "strut_rows: %zu vertices, %zu pairs: too many for int indices", q->nv, np);
    TR_TRY(dev_room(s, &r->x, &r->xcap, 3 * q->nv, sizeof(double), err));
    TR_TRY(dev_room(s, &r->quad, &r->qcap, 4 * np, sizeof(int), err));
    TR_TRY(dev_room(s, &r->lam, &r->lcap, np, sizeof(double), err));
    TR_TRY(host_room((void **)&r->hquad, &r->hqcap, 4 * np, sizeof(int), err));
    for (size_t k = 0; k < 4 * np; k++) {
        if (q->quad[k] >= q->nv)
            return tr_fail(err, TR_EINVAL, "strut_rows: vertex %zu of pair %zu is not one of the %zu", q->quad[k],
                           k / 4, q->nv);
        r->hquad[k] = (int)q->quad[k];
    }
    /* the writes need not block: the call ends in a blocking read on the
     * same in-order queue, before which neither array is touched again */
    TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, r->x, CL_FALSE, 0, 3 * q->nv * sizeof(double), q->x, 0, NULL,
                                     NULL));
    if (np > 0) {
        TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, r->quad, CL_FALSE, 0, 4 * np * sizeof(int), r->hquad, 0,
                                         NULL, NULL));
        TR_CL_CHECK(clEnqueueWriteBuffer(s->ctx.queue, r->lam, CL_FALSE, 0, np * sizeof(double), q->lam, 0, NULL,
                                         NULL));
    }
cleanup:
    return rc;
}

/* Room for the per-item partials of np pairs; their number. */
static int partials(cl_state *s, int np, size_t *g, tr_error *err)
{
    clb_rows *r = &s->rows;
    int rc = TR_OK;
    *g = tr_cl_items_global(&s->ctx, (size_t)np);
    TR_TRY(dev_room(s, &r->psum, &r->partcap, *g, sizeof(double), err));
    TR_TRY(dev_room(s, &r->pmin, &r->pmcap, *g, sizeof(double), err));
    TR_TRY(dev_room(s, &r->sc, &r->sccap, 3, sizeof(double), err));
    TR_TRY(tr_cl_reduce_reserve(&s->red, &s->ctx, *g, err));
cleanup:
    return rc;
}

/* Queues the folds of g per-item partials: sc = (sum, min, max). */
static int fold(cl_state *s, size_t g, tr_error *err)
{
    clb_rows *r = &s->rows;
    int rc = TR_OK;
    TR_TRY(tr_cl_reduce_sum(&s->red, &s->ctx, r->psum, (int)g, r->sc, 0, err));
    TR_TRY(tr_cl_reduce_minmax(&s->red, &s->ctx, r->pmin, (int)g, r->sc, 1, err));
cleanup:
    return rc;
}

/* TR_ROWS_VALUE: per-item partial sums and minima, folded by the reductions. */
static int rows_value(cl_state *s, tr_strut_rows *q, tr_error *err)
{
    clb_rows *r = &s->rows;
    int rc = TR_OK;
    int np = (int)q->np;
    double sc[3] = {0.0, INFINITY, INFINITY};
    if (np > 0) {
        size_t g;
        TR_TRY(partials(s, np, &g, err));
        double mu = q->mu, dist = q->dist;
        TR_TRY(clb_run(s, K_strut_rows_value, (size_t)np, err, A(r->x), A(r->quad), A(r->lam), A(np), A(mu),
                       A(dist), A(r->psum), A(r->pmin), END));
        TR_TRY(fold(s, g, err));
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, r->sc, CL_TRUE, 0, sizeof sc, sc, 0, NULL, NULL));
    } else
        TR_CL_CHECK(clFinish(s->ctx.queue)); /* the position write done before the caller moves on */
    q->sum = q->sum0 + sc[0];
    q->dmin = sc[1];
cleanup:
    return rc;
}

/* TR_ROWS_GRAD / _HESS: distances and flags, the flags' scan, the selected blocks. */
static int rows_blocks(cl_state *s, tr_strut_rows *q, tr_error *err)
{
    clb_rows *r = &s->rows;
    int rc = TR_OK;
    int np = (int)q->np, hess = q->mode == TR_ROWS_HESS, nsel = 0;
    size_t n = (size_t)np;
    double sc[3] = {0.0, INFINITY, INFINITY};
    TR_TRY(host_room((void **)&r->hd, &r->hdcap, n, sizeof(double), err));
    TR_TRY(host_room((void **)&r->hoff, &r->hocap, n + 1, sizeof(int), err));
    TR_TRY(host_room((void **)&r->hsel, &r->hscap, n, sizeof(int), err));
    if (np > 0) {
        TR_TRY(dev_room(s, &r->d, &r->dcap, n, sizeof(double), err));
        TR_TRY(dev_room(s, &r->flag, &r->fcap, n, sizeof(int), err));
        TR_TRY(dev_room(s, &r->off, &r->ocap, n + 1, sizeof(int), err));
        TR_TRY(tr_cl_reduce_reserve(&s->red, &s->ctx, n, err));
        size_t g;
        TR_TRY(partials(s, np, &g, err));
        double mu = q->mu, dist = q->dist, band = q->band;
        TR_TRY(clb_run(s, K_strut_rows_select, n, err, A(r->x), A(r->quad), A(r->lam), A(np), A(mu), A(dist),
                       A(band), A(r->d), A(r->flag), A(r->psum), A(r->pmin), END));
        TR_TRY(fold(s, g, err));
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, r->sc, CL_FALSE, 0, sizeof sc, sc, 0, NULL, NULL));
        TR_TRY(tr_cl_reduce_scan(&s->red, &s->ctx, r->flag, np, r->off, err));
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, r->off, CL_TRUE, n * sizeof(int), sizeof nsel, &nsel, 0, NULL,
                                        NULL));
        if (nsel < 0 || nsel > np) {
            rc = tr_fail(err, TR_EGEOMETRY, "strut_rows: %d rows selected of %d", nsel, np);
            goto cleanup;
        }
        size_t ns = (size_t)nsel;
        TR_TRY(host_room((void **)&r->hg, &r->hgcap, 12 * ns, sizeof(double), err));
        if (hess)
            TR_TRY(host_room((void **)&r->hh, &r->hhcap, 144 * ns, sizeof(double), err));
        if (nsel > 0) {
            TR_TRY(dev_room(s, &r->g, &r->gcap, 12 * ns, sizeof(double), err));
            if (hess)
                TR_TRY(dev_room(s, &r->h, &r->hcap, 144 * ns, sizeof(double), err));
            else
                TR_TRY(dev_room(s, &r->h, &r->hcap, 1, sizeof(double), err)); /* an argument, never written */
            TR_TRY(clb_run(s, K_strut_rows_blocks, n, err, A(r->x), A(r->quad), A(np), A(r->off), A(hess), A(r->g),
                           A(r->h), END));
            TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, r->g, CL_FALSE, 0, 12 * ns * sizeof(double), r->hg, 0,
                                            NULL, NULL));
            if (hess)
                TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, r->h, CL_FALSE, 0, 144 * ns * sizeof(double), r->hh,
                                                0, NULL, NULL));
        }
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, r->d, CL_FALSE, 0, n * sizeof(double), r->hd, 0, NULL, NULL));
        TR_CL_CHECK(clEnqueueReadBuffer(s->ctx.queue, r->off, CL_TRUE, 0, (n + 1) * sizeof(int), r->hoff, 0, NULL,
                                        NULL));
        for (size_t p = 0; p < n; p++)
            r->hsel[p] = r->hoff[p + 1] > r->hoff[p] ? r->hoff[p] : -1;
    } else
        TR_CL_CHECK(clFinish(s->ctx.queue));
    q->nsel = (size_t)nsel;
    q->sum = q->sum0 + sc[0];
    q->dmin = sc[1];
    q->d = r->hd;
    q->sel = r->hsel;
    q->g = r->hg;
    q->h = hess ? r->hh : NULL;
cleanup:
    return rc;
}

int clb_strut_rows(void *sp, tr_strut_rows *q, tr_error *err)
{
    cl_state *s = sp;
    if (q->mode != TR_ROWS_VALUE && q->mode != TR_ROWS_GRAD && q->mode != TR_ROWS_HESS)
        return tr_fail(err, TR_EINVAL, "strut_rows: unknown mode %d", q->mode);
    int rc = upload(s, q, err);
    if (rc == TR_OK)
        rc = q->mode == TR_ROWS_VALUE ? rows_value(s, q, err) : rows_blocks(s, q, err);
    if (rc != TR_OK)
        tr_fail_wrap(err, rc, "strut rows");
    return rc;
}
