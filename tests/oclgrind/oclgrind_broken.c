/* Runs one kernel of tests/oclgrind/broken.cl over 64 ints, on a device
 * chosen as the tests choose theirs ("opencl"):
 *   oclgrind_broken fine | out_of_bounds | race | write_read_only
 * Every OpenCL call is checked and the program exits 0 when they all
 * succeed: a conformant implementation need not notice the bugs, so only
 * Oclgrind's reports tell (tests/oclgrind.cmake runs it under
 * scripts/oclgrind_run.sh). `fine` also checks its result. The kernel
 * file is read from the source tree through TIGHTROPE_KERNEL_DIR, as
 * kernel work does, so the reports name it by its path. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/cl_device.h"
#include "backend/opencl/cl_error.h"
#include "backend/opencl/kernel_source.h"
#include "testlib.h"

enum { N = 64 };

static int run(const tr_cl_ctx *ctx, const char *kernel, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    char *src = NULL;
    cl_program prog = NULL;
    cl_kernel k = NULL;
    cl_mem in = NULL, out = NULL;
    int host_in[N], host_out[N], n = N;
    for (int i = 0; i < N; i++)
        host_in[i] = i + 1, host_out[i] = -1;
    TR_TRY(tr_kernel_source_load("broken.cl", &src, err));
    TR_CL_CHECK((prog = clCreateProgramWithSource(ctx->context, 1, (const char **)&src, NULL, &e), e));
    TR_CL_CHECK(clBuildProgram(prog, 1, &ctx->info.did, "", NULL, NULL));
    TR_CL_CHECK((k = clCreateKernel(prog, kernel, &e), e));
    TR_CL_CHECK((in = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                     sizeof host_in, host_in, &e),
                 e));
    TR_CL_CHECK((out = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                                      sizeof host_out, host_out, &e),
                 e));
    TR_CL_ARGS(k, 0, TR_CL_A(in), TR_CL_A(out), TR_CL_A(n));
    TR_TRY(tr_cl_launch(ctx, k, N, N, err));
    TR_CL_CHECK(clEnqueueReadBuffer(ctx->queue, out, CL_TRUE, 0, sizeof host_out, host_out, 0, NULL,
                                    NULL));
    if (!strcmp(kernel, "fine"))
        for (int i = 0; i < N; i++)
            CHECK(host_out[i] == 2 * (i + 1));
cleanup:
    if (in)
        clReleaseMemObject(in);
    if (out)
        clReleaseMemObject(out);
    if (k)
        clReleaseKernel(k);
    if (prog)
        clReleaseProgram(prog);
    free(src);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s fine|out_of_bounds|race|write_read_only\n", argv[0]);
        return 2;
    }
    tr_error err;
    tr_device_choice ch;
    if (tr_device_select("opencl", &ch, &err) != TR_OK || ch.kind != TR_DEVICE_OPENCL) {
        printf("no usable opencl device: skipped\n");
        return TR_SKIP;
    }
    printf("device %d:%d %s, kernel %s\n", ch.cl.platform, ch.cl.device, ch.cl.name, argv[1]);
    setenv("TIGHTROPE_KERNEL_DIR", TR_SOURCE_DIR "/tests/oclgrind", 1);
    tr_cl_ctx ctx;
    if (tr_cl_ctx_open(&ctx, &ch.cl, 0, &err) != TR_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    int rc = run(&ctx, argv[1], &err);
    tr_cl_ctx_close(&ctx);
    if (rc != TR_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    return tr_test_finish(argv[1]);
}
