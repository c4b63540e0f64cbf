/* launch_shapes [DEVICE] [N]: wall time of the CG's axpy kernel (cg_p,
 * kernels/correct.cl: y += alpha p, p = z + beta p) over N entries
 * (default 2 x 10^5, the row list of a loose N = 10^5 curve) in the two
 * launch shapes of tr_cl_launch_items: one
 * index per work-item in groups of 64 to 4096, and a few work-items of one
 * each, every one walking a contiguous block (common.clh TR_ITEMS). 200
 * launches back to back after one untimed launch per shape; prints ms per
 * launch. The measurement behind the choice of blocks on CPU devices. */
#include <stdio.h>
#include <stdlib.h>

#include "backend/opencl/cl_device.h"
#include "backend/opencl/cl_error.h"
#include "backend/opencl/cl_reduce.h"
#include "layout.h"
#include "util/clock.h"

/* ms per launch of k over global items in groups of local (arguments set). */
static int time_shape(const tr_cl_ctx *ctx, cl_kernel k, size_t global, size_t local, double *ms,
                      tr_error *err)
{
    int rc = TR_OK;
    const int reps = 200;
    TR_TRY(tr_cl_launch(ctx, k, global, local, err)); /* PoCL compiles for a new local size */
    TR_CL_CHECK(clFinish(ctx->queue));
    double t = tr_clock_seconds();
    for (int i = 0; i < reps; i++)
        TR_TRY(tr_cl_launch(ctx, k, global, local, err));
    TR_CL_CHECK(clFinish(ctx->queue));
    *ms = 1e3 * (tr_clock_seconds() - t) / reps;
cleanup:
    return rc;
}

int main(int argc, char **argv)
{
    const char *spec = argc > 1 ? argv[1] : "opencl";
    int n = argc > 2 ? atoi(argv[2]) : 200000;
    tr_error error = {0}, *err = &error;
    tr_device_choice ch;
    tr_cl_ctx ctx = {0};
    cl_program prog = NULL;
    cl_kernel k = NULL;
    enum { NBUF = 4 };
    cl_mem v[NBUF] = {NULL};
    cl_int e = CL_SUCCESS;
    int rc = TR_OK;
    if (n < 1)
        n = 200000;
    TR_TRY(tr_device_select(spec, &ch, err));
    if (ch.kind != TR_DEVICE_OPENCL) {
        fprintf(stderr, "launch_shapes: '%s' is not an OpenCL device\n", spec);
        return 2;
    }
    TR_TRY(tr_cl_ctx_open(&ctx, &ch.cl, 0, err));
    TR_TRY(tr_cl_build_all(&ctx, &prog, err));
    TR_CL_CHECK((k = clCreateKernel(prog, "cg_p", &e), e));
    /* cg_p(y, p, z, sc, nl) */
    size_t nd = (size_t)n * sizeof(double);
    const size_t bytes[NBUF] = {nd, nd, nd, 64 * sizeof(double)};
    for (int i = 0; i < NBUF; i++) {
        TR_CL_CHECK((v[i] = clCreateBuffer(ctx.context, CL_MEM_READ_WRITE, bytes[i], NULL, &e), e));
        char zero = 0;
        TR_CL_CHECK(clEnqueueFillBuffer(ctx.queue, v[i], &zero, 1, 0, bytes[i], 0, NULL, NULL));
    }
    /* sc[SC_PQ] and sc[SC_RZ] (kernels/layout.h) 1: alpha = 0 / 1, beta = 0 / 1 */
    double one = 1.0;
    TR_CL_CHECK(clEnqueueWriteBuffer(ctx.queue, v[3], CL_TRUE, SC_PQ * sizeof(double), sizeof one, &one, 0,
                                     NULL, NULL));
    TR_CL_CHECK(clEnqueueWriteBuffer(ctx.queue, v[3], CL_TRUE, SC_RZ * sizeof(double), sizeof one, &one, 0,
                                     NULL, NULL));
    TR_CL_ARGS(k, 0, TR_CL_A(v[0]), TR_CL_A(v[1]), TR_CL_A(v[2]), TR_CL_A(v[3]), TR_CL_A(n));
    printf("%s, cg_p over %d entries, ms per launch (200 launches)\n", ch.cl.name, n);
    const size_t locals[] = {64, 256, 1024, 4096};
    for (size_t i = 0; i < sizeof locals / sizeof locals[0]; i++) {
        if (locals[i] > ch.cl.max_work_group)
            continue;
        size_t g = ((size_t)n + locals[i] - 1) / locals[i] * locals[i];
        double ms;
        TR_TRY(time_shape(&ctx, k, g, locals[i], &ms, err));
        printf("  one index per item, groups of %4zu: %.4f\n", locals[i], ms);
    }
    const size_t items[] = {2, 4, 8, 16, 32, 64};
    for (size_t i = 0; i < sizeof items / sizeof items[0]; i++) {
        double ms;
        TR_TRY(time_shape(&ctx, k, items[i], 1, &ms, err));
        printf("  blocks: %2zu work-items of one:    %.4f\n", items[i], ms);
    }
cleanup:
    for (int i = 0; i < NBUF; i++)
        if (v[i])
            clReleaseMemObject(v[i]);
    if (k)
        clReleaseKernel(k);
    if (prog)
        clReleaseProgram(prog);
    tr_cl_ctx_close(&ctx);
    if (rc != TR_OK) {
        fprintf(stderr, "launch_shapes: %s\n", err->msg);
        return 1;
    }
    return 0;
}
