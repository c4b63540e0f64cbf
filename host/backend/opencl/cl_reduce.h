/* Device reductions (kernels/reduce.cl): results land in a device buffer of
 * scalars so a step can queue several and the host reads them back at once. */
#ifndef TR_CL_REDUCE_H
#define TR_CL_REDUCE_H

#include "backend/opencl/cl_device.h"

typedef struct tr_cl_reduce {
    cl_kernel length_partial, minmax_partial, sum_final, minmax_final, edge_lengths;
    cl_kernel sum_partial, dot_partial, isum_partial;
    cl_kernel scan_local, scan_sums, scan_add;
    cl_mem pa, pb;   /* per-work-group partials */
    size_t groups;   /* capacity of pa, pb */
} tr_cl_reduce;

/* Takes the kernels from prog (built from reduce.cl among others, see
 * tr_cl_build_all) and sizes the partial buffers for up to n items. */
int tr_cl_reduce_init(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_program prog, size_t n,
                      tr_error *err);
void tr_cl_reduce_free(tr_cl_reduce *r);

/* Queues out[slot] = sum over vertices i < n of |x[next[i]] - x[i]| (next[i] < 0: no edge). */
int tr_cl_reduce_length(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem x, cl_mem next, int n,
                        cl_mem out, int slot, tr_error *err);

/* Queues out[slot] = min, out[slot + 1] = max of v[0..n), n >= 1. */
int tr_cl_reduce_minmax(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem v, int n, cl_mem out,
                        int slot, tr_error *err);

/* Grows the partial buffers for reductions over up to n items. */
int tr_cl_reduce_reserve(tr_cl_reduce *r, const tr_cl_ctx *ctx, size_t n, tr_error *err);

/* Queues out[slot] = sum of v[0..n) (compensated per item, then pairwise
 * within work-groups; n <= 1024, e.g. one partial per work-item, goes
 * straight to the one work-group of stage 2). */
int tr_cl_reduce_sum(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem v, int n, cl_mem out, int slot,
                     tr_error *err);
/* Queues out[slot] = a . b over n entries. */
int tr_cl_reduce_dot(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem a, cl_mem b, int n, cl_mem out,
                     int slot, tr_error *err);

/* Queues out[slot] = sum of the ints v[0..n) (a count of flags), as a double. */
int tr_cl_reduce_count(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem v, int n, cl_mem out,
                       int slot, tr_error *err);

/* Queues the exclusive prefix sums of the ints in[0..n) into out[0..n], with
 * out[n] = the total (kernels/reduce.cl scan_*). n >= 1. */
int tr_cl_reduce_scan(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem in, int n, cl_mem out,
                      tr_error *err);

/* Queues len[i] = |x[next[i]] - x[i]| (0 where no edge starts) for i < n. */
int tr_cl_edge_lengths(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem x, cl_mem next, int n,
                       cl_mem len, tr_error *err);

/* The one program every Tightrope kernel lives in (common.clh, then
 * reduce.cl, tree.cl, tension.cl, contacts.cl, correct.cl, tridiag.cl,
 * measure.cl, solver_rows.cl): built once per context, ~0.8 s cold on PoCL. */
int tr_cl_build_all(const tr_cl_ctx *ctx, cl_program *prog, tr_error *err);

#endif
