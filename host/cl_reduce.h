/* Device reductions (kernels/reduce.cl): results land in a device buffer of
 * scalars so a step can queue several and the host reads them back at once. */
#ifndef TR_CL_REDUCE_H
#define TR_CL_REDUCE_H

#include "cl_device.h"

typedef struct tr_cl_reduce {
    cl_program prog;
    cl_kernel length_partial, minmax_partial, sum_final, minmax_final;
    cl_mem pa, pb;   /* per-work-group partials */
    size_t groups;   /* capacity of pa, pb */
} tr_cl_reduce;

/* Builds reduce.cl and sizes the partial buffers for up to n items. */
int tr_cl_reduce_init(tr_cl_reduce *r, const tr_cl_ctx *ctx, size_t n, tr_error *err);
void tr_cl_reduce_free(tr_cl_reduce *r);

/* Queues out[slot] = sum over vertices i < n of |x[next[i]] - x[i]| (next[i] < 0: no edge). */
int tr_cl_reduce_length(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem x, cl_mem next, int n,
                        cl_mem out, int slot, tr_error *err);

/* Queues out[slot] = min, out[slot + 1] = max of v[0..n), n >= 1. */
int tr_cl_reduce_minmax(tr_cl_reduce *r, const tr_cl_ctx *ctx, cl_mem v, int n, cl_mem out,
                        int slot, tr_error *err);

#endif
