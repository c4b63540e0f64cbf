#include "cl_grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cl_error.h"

#define ARG(k, i, v) TR_CL_CHECK(clSetKernelArg((k), (i), sizeof(v), &(v)))

static void release(cl_mem *m)
{
    if (*m)
        clReleaseMemObject(*m);
    *m = NULL;
}

static int alloc_lists(tr_cl_grid *g, const tr_cl_ctx *ctx, int cap, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    release(&g->list);
    g->cap = cap;
    TR_CL_CHECK((g->list = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE,
                                          (size_t)g->n * (size_t)cap * sizeof(int), NULL, &e),
                 e));
cleanup:
    return rc;
}

int tr_cl_grid_init(tr_cl_grid *g, const tr_cl_ctx *ctx, cl_program prog, int n, int cap,
                    tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    memset(g, 0, sizeof *g);
    if (n < 1)
        return tr_fail(err, TR_EINVAL, "neighbour search over %d items", n);
    g->n = n;
    g->npad = 1;
    while (g->npad < n)
        g->npad *= 2;
    TR_CL_CHECK((g->axis = clCreateKernel(prog, "grid_axis", &e), e));
    TR_CL_CHECK((g->keys = clCreateKernel(prog, "grid_keys", &e), e));
    TR_CL_CHECK((g->bitonic = clCreateKernel(prog, "bitonic_pass", &e), e));
    TR_CL_CHECK((g->reset = clCreateKernel(prog, "cell_reset", &e), e));
    TR_CL_CHECK((g->bounds = clCreateKernel(prog, "cell_bounds", &e), e));
    TR_CL_CHECK((g->pairs = clCreateKernel(prog, "grid_pairs", &e), e));
    TR_CL_CHECK((g->keybuf = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE,
                                            (size_t)g->npad * sizeof(cl_ulong), NULL, &e),
                 e));
    TR_CL_CHECK((g->tmp = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, (size_t)n * sizeof(double),
                                         NULL, &e),
                 e));
    TR_CL_CHECK((g->scal = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, 8 * sizeof(double), NULL,
                                          &e),
                 e));
    TR_CL_CHECK((g->count = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, (size_t)n * sizeof(int),
                                           NULL, &e),
                 e));
    TR_CL_CHECK((g->overflow = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, sizeof(int), NULL,
                                              &e),
                 e));
    TR_TRY(alloc_lists(g, ctx, cap > 0 ? cap : 16, err));
    return TR_OK;
cleanup:
    tr_cl_grid_free(g);
    return rc;
}

void tr_cl_grid_free(tr_cl_grid *g)
{
    cl_kernel *k[] = {&g->axis, &g->keys, &g->bitonic, &g->reset, &g->bounds, &g->pairs};
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        if (*k[i])
            clReleaseKernel(*k[i]);
    cl_mem *m[] = {&g->keybuf, &g->cell_start, &g->cell_end, &g->tmp,
                   &g->scal,   &g->count,      &g->list,     &g->overflow};
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        release(m[i]);
    memset(g, 0, sizeof *g);
}

static int launch(const tr_cl_ctx *ctx, cl_kernel k, size_t n, tr_error *err)
{
    int rc = TR_OK;
    size_t gsz = tr_cl_global(n), l = TR_CL_LOCAL;
    TR_CL_CHECK(clEnqueueNDRangeKernel(ctx->queue, k, 1, NULL, &gsz, &l, 0, NULL, NULL));
cleanup:
    return rc;
}

int tr_cl_grid_build(tr_cl_grid *g, const tr_cl_ctx *ctx, tr_cl_reduce *red,
                     const tr_cl_topology *t, cl_mem x, int edges, double r, double tilt,
                     cl_mem gap, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    int n = g->n;
    double s[8];
    if (t->nv != n)
        return tr_fail(err, TR_EINVAL, "neighbour grid prepared for %d items, curve has %d", n, t->nv);

    /* Bounding box and longest edge: the only read-back besides the overflow flag. */
    for (int axis = 0; axis < 3; axis++) {
        ARG(g->axis, 0, x);
        ARG(g->axis, 1, n);
        ARG(g->axis, 2, axis);
        ARG(g->axis, 3, g->tmp);
        TR_TRY(launch(ctx, g->axis, (size_t)n, err));
        TR_TRY(tr_cl_reduce_minmax(red, ctx, g->tmp, n, g->scal, 2 * axis, err));
    }
    TR_TRY(tr_cl_edge_lengths(red, ctx, x, t->next, n, g->tmp, err));
    TR_TRY(tr_cl_reduce_minmax(red, ctx, g->tmp, n, g->scal, 6, err));
    TR_CL_CHECK(clEnqueueReadBuffer(ctx->queue, g->scal, CL_TRUE, 0, sizeof s, s, 0, NULL, NULL));
    for (int i = 0; i < 8; i++)
        if (!isfinite(s[i])) {
            rc = tr_fail(err, TR_EGEOMETRY, "non-finite coordinates on the device");
            goto cleanup;
        }

    /* A partner closer than r has its item centre within r + (longest edge)
     * (edge midpoints) or r (vertices): cells that wide make 27 cells enough.
     * Very spread-out curves get wider cells rather than a huge cell table. */
    double h = r + (edges ? s[7] : 0.0);
    if (!(h > 0))
        h = 1.0;
    double ext[3] = {s[1] - s[0], s[3] - s[2], s[5] - s[4]};
    const double max_cells = 4.0 * n + 4096.0;
    for (int a = 0; a < 3; a++)
        if (!isfinite(ext[a])) {
            rc = tr_fail(err, TR_EGEOMETRY, "the curve spans more than a double can hold");
            goto cleanup;
        }
    /* counted in double: ext / h can exceed any integer type before h grows */
    long dims[3];
    for (;;) {
        double total = 1, d[3];
        for (int a = 0; a < 3; a++) {
            d[a] = floor(ext[a] / h) + 1.0;
            total *= d[a];
        }
        if (total <= max_cells) {
            for (int a = 0; a < 3; a++)
                dims[a] = (long)d[a];
            break;
        }
        h *= 1.25;
    }
    size_t ncell = (size_t)(dims[0] * dims[1] * dims[2]);
    if (ncell > g->ncell_cap) {
        release(&g->cell_start);
        release(&g->cell_end);
        g->ncell_cap = ncell;
        TR_CL_CHECK((g->cell_start = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE,
                                                    ncell * sizeof(int), NULL, &e),
                     e));
        TR_CL_CHECK((g->cell_end = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE,
                                                  ncell * sizeof(int), NULL, &e),
                     e));
    }
    g->h = h;
    for (int a = 0; a < 3; a++)
        g->dims[a] = (int)dims[a];
    double inv_h = 1.0 / h;
    int nx = g->dims[0], ny = g->dims[1], nz = g->dims[2], nc = (int)ncell;

    ARG(g->keys, 0, x);
    ARG(g->keys, 1, t->next);
    ARG(g->keys, 2, n);
    ARG(g->keys, 3, g->npad);
    ARG(g->keys, 4, edges);
    ARG(g->keys, 5, s[0]);
    ARG(g->keys, 6, s[2]);
    ARG(g->keys, 7, s[4]);
    ARG(g->keys, 8, inv_h);
    ARG(g->keys, 9, nx);
    ARG(g->keys, 10, ny);
    ARG(g->keys, 11, nz);
    ARG(g->keys, 12, g->keybuf);
    TR_TRY(launch(ctx, g->keys, (size_t)g->npad, err));

    ARG(g->bitonic, 0, g->keybuf);
    ARG(g->bitonic, 3, g->npad);
    for (int k = 2; k <= g->npad; k *= 2)
        for (int j = k / 2; j > 0; j /= 2) {
            ARG(g->bitonic, 1, j);
            ARG(g->bitonic, 2, k);
            TR_TRY(launch(ctx, g->bitonic, (size_t)g->npad, err));
        }

    ARG(g->reset, 0, g->cell_start);
    ARG(g->reset, 1, g->cell_end);
    ARG(g->reset, 2, nc);
    TR_TRY(launch(ctx, g->reset, ncell, err));
    ARG(g->bounds, 0, g->keybuf);
    ARG(g->bounds, 1, g->npad);
    ARG(g->bounds, 2, g->cell_start);
    ARG(g->bounds, 3, g->cell_end);
    TR_TRY(launch(ctx, g->bounds, (size_t)g->npad, err));

    int flag = 0;
    for (int attempt = 0; attempt < 2; attempt++) {
        int zero = 0;
        flag = 0;
        TR_CL_CHECK(clEnqueueWriteBuffer(ctx->queue, g->overflow, CL_FALSE, 0, sizeof zero, &zero, 0,
                                         NULL, NULL));
        cl_mem a[] = {x, t->next};
        ARG(g->pairs, 0, a[0]);
        ARG(g->pairs, 1, a[1]);
        ARG(g->pairs, 2, n);
        ARG(g->pairs, 3, edges);
        ARG(g->pairs, 4, t->comp);
        ARG(g->pairs, 5, t->pos);
        ARG(g->pairs, 6, t->comp_n);
        ARG(g->pairs, 7, t->comp_closed);
        ARG(g->pairs, 8, gap);
        ARG(g->pairs, 9, r);
        ARG(g->pairs, 10, tilt);
        ARG(g->pairs, 11, g->keybuf);
        ARG(g->pairs, 12, g->cell_start);
        ARG(g->pairs, 13, g->cell_end);
        ARG(g->pairs, 14, s[0]);
        ARG(g->pairs, 15, s[2]);
        ARG(g->pairs, 16, s[4]);
        ARG(g->pairs, 17, inv_h);
        ARG(g->pairs, 18, nx);
        ARG(g->pairs, 19, ny);
        ARG(g->pairs, 20, nz);
        ARG(g->pairs, 21, g->cap);
        ARG(g->pairs, 22, g->count);
        ARG(g->pairs, 23, g->list);
        ARG(g->pairs, 24, g->overflow);
        TR_TRY(launch(ctx, g->pairs, (size_t)n, err));
        TR_CL_CHECK(clEnqueueReadBuffer(ctx->queue, g->overflow, CL_TRUE, 0, sizeof flag, &flag, 0,
                                        NULL, NULL));
        if (!flag)
            break;
        /* Rare (after a big move): size the lists to the largest count and redo. */
        int *cnt = malloc((size_t)n * sizeof *cnt);
        if (!cnt) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory growing neighbour lists");
            goto cleanup;
        }
        e = clEnqueueReadBuffer(ctx->queue, g->count, CL_TRUE, 0, (size_t)n * sizeof(int), cnt, 0,
                                NULL, NULL);
        if (e != CL_SUCCESS)
            free(cnt);
        TR_CL_CHECK(e);
        int most = 0;
        for (int i = 0; i < n; i++)
            most = cnt[i] > most ? cnt[i] : most;
        free(cnt);
        if ((double)most * n > 5e8) {
            rc = tr_fail(err, TR_EGEOMETRY,
                         "%d neighbours for one item within %g: the curve is far too dense", most, r);
            goto cleanup;
        }
        TR_TRY(alloc_lists(g, ctx, most + most / 4 + 4, err));
    }
    /* the lists were sized to the counts of the first pass; a second
     * overflow means the kernel disagrees with itself, never a silent cut */
    if (flag)
        rc = tr_fail(err, TR_EOPENCL, "neighbour lists still overflow after growing them");
cleanup:
    return rc;
}
