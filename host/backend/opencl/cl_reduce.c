/* This file contains the device reductions (sum, dot, min/max, count, scan) into the scalar
 * buffer (cl_reduce.h). */
#include "backend/opencl/cl_reduce.h"

#include <string.h>

#include "backend/opencl/cl_error.h"

/* Stage-1 work-groups at most (see kernels/reduce.cl): enough to keep a
 * GPU's compute units busy, few enough that a CPU device is not dominated by
 * work-group scheduling. The count depends only on n and the device's launch
 * shape (stage1_global), so results do too: the same bits for the same input
 * on the same device. */
#define TR_RED_GROUPS 64
/* Sums of at most this many values skip stage 1 (sixteen per item of
 * sum_final's one work-group): the per-work-item partials on CPU devices. */
#define TR_RED_DIRECT (16 * TR_LOCAL_SIZE)

/* Stage 1's global size for n entries: at most TR_RED_GROUPS work-groups
 * on a GPU; on a CPU device as many as the blocks of an items launch
 * (tr_cl_launch_items), since there every work-group with barriers costs
 * microseconds whatever its size: 64 groups made a dot product over 4800
 * entries take 26 us on PoCL. */
static size_t stage1_global(const tr_cl_ctx *ctx, size_t n)
{
    size_t g = tr_cl_global(n);
    size_t groups = ctx->block_items && ctx->block_items < TR_RED_GROUPS ? ctx->block_items
                                                                          : TR_RED_GROUPS;
    return g < groups * TR_LOCAL_SIZE ? g : groups * TR_LOCAL_SIZE;
}

int tr_cl_build_all(const tr_cl_ctx *ctx, cl_program *prog, tr_error *err)
{
    static const char *const files[] = {"reduce.cl",   "tree.cl",    "tension.cl",
                                        "contacts.cl", "correct.cl", "tridiag.cl",  "twisted.cl",
                                        "measure.cl",  "solver_rows.cl"};
    return tr_cl_build(ctx, files, (int)(sizeof files / sizeof files[0]), "", prog, err);
}

int tr_cl_reduce_init(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_program prog, size_t n,
                      tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    memset(r, 0, sizeof *r);
    TR_CL_CHECK((r->length_partial = clCreateKernel(prog, "length_partial", &e), e));
    TR_CL_CHECK((r->minmax_partial = clCreateKernel(prog, "minmax_partial", &e), e));
    TR_CL_CHECK((r->sum_final = clCreateKernel(prog, "sum_final", &e), e));
    TR_CL_CHECK((r->minmax_final = clCreateKernel(prog, "minmax_final", &e), e));
    TR_CL_CHECK((r->edge_lengths = clCreateKernel(prog, "edge_lengths", &e), e));
    TR_CL_CHECK((r->sum_partial = clCreateKernel(prog, "sum_partial", &e), e));
    TR_CL_CHECK((r->dot_partial = clCreateKernel(prog, "dot_partial", &e), e));
    TR_CL_CHECK((r->isum_partial = clCreateKernel(prog, "isum_partial", &e), e));
    TR_CL_CHECK((r->scan_local = clCreateKernel(prog, "scan_local", &e), e));
    TR_CL_CHECK((r->scan_sums = clCreateKernel(prog, "scan_sums", &e), e));
    TR_CL_CHECK((r->scan_add = clCreateKernel(prog, "scan_add", &e), e));
    r->groups = tr_cl_global(n) / TR_LOCAL_SIZE;
    TR_CL_CHECK((r->pa = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, r->groups * sizeof(double),
                                        NULL, &e),
                 e));
    TR_CL_CHECK((r->pb = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, r->groups * sizeof(double),
                                        NULL, &e),
                 e));
    return TR_OK;
cleanup:
    tr_cl_reduce_free(r);
    return rc;
}

void tr_cl_reduce_free(tr_cl_reduce *r)
{
    cl_kernel *k[] = {&r->length_partial, &r->minmax_partial, &r->sum_final, &r->minmax_final,
                      &r->edge_lengths, &r->sum_partial, &r->dot_partial, &r->isum_partial,
                      &r->scan_local, &r->scan_sums, &r->scan_add};
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        if (*k[i])
            clReleaseKernel(*k[i]);
    if (r->pa)
        clReleaseMemObject(r->pa);
    if (r->pb)
        clReleaseMemObject(r->pb);
    memset(r, 0, sizeof *r);
}

static int check_size(const tr_cl_reduce *r, int n, tr_error *err)
{
    if (n < 1 || tr_cl_global((size_t)n) / TR_LOCAL_SIZE > r->groups)
        return tr_fail(err, TR_EINVAL, "reduction over %d items exceeds the %zu prepared", n,
                       r->groups * TR_LOCAL_SIZE);
    return TR_OK;
}

/* Stage 2: sum_final folds the m partial sums into out[slot]. */
static int sum_stage2(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem src, int m, cl_mem out,
                      int slot, tr_error *err)
{
    int rc = TR_OK;
    size_t l = TR_LOCAL_SIZE;
    TR_CL_ARGS(r->sum_final, 0, TR_CL_A(src), TR_CL_A(m), TR_CL_A(out), TR_CL_A(slot));
    TR_TRY(tr_cl_launch(ctx, r->sum_final, l, l, err));
cleanup:
    return rc;
}

int tr_cl_reduce_length(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem x, cl_mem next, int n,
                        cl_mem out, int slot, tr_error *err)
{
    int rc = check_size(r, n, err);
    if (rc != TR_OK)
        return rc;
    size_t g = stage1_global(ctx, (size_t)n), l = TR_LOCAL_SIZE;
    int m = (int)(g / l);
    TR_CL_ARGS(r->length_partial, 0, TR_CL_A(x), TR_CL_A(next), TR_CL_A(n), TR_CL_A(r->pa));
    TR_TRY(tr_cl_launch(ctx, r->length_partial, g, l, err));
    rc = sum_stage2(r, ctx, r->pa, m, out, slot, err);
cleanup:
    return rc;
}

int tr_cl_reduce_minmax(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem v, int n, cl_mem out,
                        int slot, tr_error *err)
{
    int rc = check_size(r, n, err);
    if (rc != TR_OK)
        return rc;
    size_t g = stage1_global(ctx, (size_t)n), l = TR_LOCAL_SIZE;
    int m = (int)(g / l);
    TR_CL_ARGS(r->minmax_partial, 0, TR_CL_A(v), TR_CL_A(n), TR_CL_A(r->pa), TR_CL_A(r->pb));
    TR_TRY(tr_cl_launch(ctx, r->minmax_partial, g, l, err));
    TR_CL_ARGS(r->minmax_final, 0, TR_CL_A(r->pa), TR_CL_A(r->pb), TR_CL_A(m), TR_CL_A(out), TR_CL_A(slot));
    TR_TRY(tr_cl_launch(ctx, r->minmax_final, l, l, err));
cleanup:
    return rc;
}

int tr_cl_edge_lengths(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem x, cl_mem next, int n,
                       cl_mem len, tr_error *err)
{
    int rc = TR_OK;
    TR_CL_ARGS(r->edge_lengths, 0, TR_CL_A(x), TR_CL_A(next), TR_CL_A(n), TR_CL_A(len));
    TR_TRY(tr_cl_launch_items(ctx, r->edge_lengths, (size_t)n, err));
cleanup:
    return rc;
}

int tr_cl_reduce_reserve(tr_cl_reduce *r, const tr_cl_ctx *ctx, size_t n, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    size_t groups = tr_cl_global(n) / TR_LOCAL_SIZE;
    if (groups <= r->groups)
        return TR_OK;
    groups += groups / 2;
    cl_mem a = NULL, b = NULL;
    TR_CL_CHECK((a = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, groups * sizeof(double), NULL, &e), e));
    TR_CL_CHECK((b = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, groups * sizeof(double), NULL, &e), e));
    clReleaseMemObject(r->pa);
    clReleaseMemObject(r->pb);
    r->pa = a;
    r->pb = b;
    r->groups = groups;
    return TR_OK;
cleanup:
    if (a)
        clReleaseMemObject(a);
    return rc;
}

/* Stage 1 kernel k over enough items for `items` entries (its arguments
 * before argn already set; argn gets n, argn + 1 the partial sums), then
 * sum_final. */
static int finish_sum(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_kernel k, int argn, int n,
                      int items, cl_mem out, int slot, tr_error *err)
{
    int rc = check_size(r, items, err);
    if (rc != TR_OK)
        return rc;
    size_t g = stage1_global(ctx, (size_t)items), l = TR_LOCAL_SIZE;
    int m = (int)(g / l);
    TR_CL_ARGS(k, (cl_uint)argn, TR_CL_A(n), TR_CL_A(r->pa));
    TR_TRY(tr_cl_launch(ctx, k, g, l, err));
    rc = sum_stage2(r, ctx, r->pa, m, out, slot, err);
cleanup:
    return rc;
}

int tr_cl_reduce_sum(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem v, int n, cl_mem out, int slot,
                     tr_error *err)
{
    int rc = TR_OK;
    if (n <= TR_RED_DIRECT) /* one stage: a few partials per item */
        return sum_stage2(r, ctx, v, n, out, slot, err);
    TR_CL_ARGS(r->sum_partial, 0, TR_CL_A(v));
    rc = finish_sum(r, ctx, r->sum_partial, 1, n, n, out, slot, err);
cleanup:
    return rc;
}

int tr_cl_reduce_dot(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem a, cl_mem b, int n, cl_mem out,
                     int slot, tr_error *err)
{
    int rc = TR_OK;
    TR_CL_ARGS(r->dot_partial, 0, TR_CL_A(a), TR_CL_A(b));
    rc = finish_sum(r, ctx, r->dot_partial, 2, n, n, out, slot, err);
cleanup:
    return rc;
}

int tr_cl_reduce_count(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem v, int n, cl_mem out,
                       int slot, tr_error *err)
{
    int rc = TR_OK;
    TR_CL_ARGS(r->isum_partial, 0, TR_CL_A(v));
    rc = finish_sum(r, ctx, r->isum_partial, 1, n, n, out, slot, err);
cleanup:
    return rc;
}

/* The per-group totals go to pb (as ints: it holds a double for every group
 * of the largest n prepared). The queue is in order, so no reduction is
 * between its stages while a scan runs. */
int tr_cl_reduce_scan(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem in, int n, cl_mem out,
                      tr_error *err)
{
    int rc = check_size(r, n, err);
    if (rc != TR_OK)
        return rc;
    size_t g = tr_cl_global((size_t)n), l = TR_LOCAL_SIZE;
    int groups = (int)(g / l);
    TR_CL_ARGS(r->scan_local, 0, TR_CL_A(in), TR_CL_A(n), TR_CL_A(out), TR_CL_A(r->pb));
    TR_TRY(tr_cl_launch(ctx, r->scan_local, g, l, err));
    TR_CL_ARGS(r->scan_sums, 0, TR_CL_A(r->pb), TR_CL_A(groups), TR_CL_A(out), TR_CL_A(n));
    TR_TRY(tr_cl_launch(ctx, r->scan_sums, l, l, err));
    TR_CL_ARGS(r->scan_add, 0, TR_CL_A(out), TR_CL_A(n), TR_CL_A(r->pb));
    TR_TRY(tr_cl_launch_items(ctx, r->scan_add, (size_t)n, err));
cleanup:
    return rc;
}
