/* Device layer: error names, the checking macro's message, device selection,
 * build failures carrying the log, and the reduction kernels against serial
 * sums on a trefoil, a two-component link and two open ropes. Skips (77)
 * when no usable OpenCL device exists. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/opencl/cl_device.h"
#include "backend/opencl/cl_error.h"
#include "backend/opencl/cl_reduce.h"
#include "curve/curve.h"
#include "testlib.h"
#include "util/compensated_sum.h"
#include "backend/opencl/kernel_source.h"

#define TR_PI 3.14159265358979323846

/* Trefoil (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t) scaled by s, n vertices. */
static void fill_trefoil(double *x, size_t n, double s)
{
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * TR_PI * (double)i / (double)n;
        x[3 * i] = s * (sin(t) + 2 * sin(2 * t));
        x[3 * i + 1] = s * (cos(t) - 2 * cos(2 * t));
        x[3 * i + 2] = -s * sin(3 * t);
    }
}

static int make_test_curve(tr_curve *c, int kind, size_t n, tr_error *err)
{
    if (kind == 0) { /* trefoil, one closed component */
        unsigned char closed = 1;
        int rc = tr_curve_alloc(c, 1, &n, &closed, err);
        if (rc == TR_OK)
            fill_trefoil(c->x, n, 3.0);
        return rc;
    }
    if (kind == 1) { /* Hopf-like link: two circles of radius 4 through each other's centre */
        size_t nv[2] = {n / 2 > 3 ? n / 2 : 3, n - n / 2 > 3 ? n - n / 2 : 3};
        unsigned char closed[2] = {1, 1};
        int rc = tr_curve_alloc(c, 2, nv, closed, err);
        if (rc != TR_OK)
            return rc;
        for (size_t i = 0; i < nv[0]; i++) {
            double t = 2 * TR_PI * (double)i / (double)nv[0];
            c->x[3 * i] = 4 * cos(t), c->x[3 * i + 1] = 4 * sin(t), c->x[3 * i + 2] = 0;
        }
        for (size_t i = 0; i < nv[1]; i++) {
            double t = 2 * TR_PI * (double)i / (double)nv[1];
            double *p = c->x + 3 * (nv[0] + i);
            p[0] = 4 + 4 * cos(t), p[1] = 0, p[2] = 4 * sin(t);
        }
        return TR_OK;
    }
    /* two open ropes (clasp-like U shapes in perpendicular planes) */
    size_t nv[2] = {n / 2 > 2 ? n / 2 : 2, n - n / 2 > 2 ? n - n / 2 : 2};
    unsigned char closed[2] = {0, 0};
    int rc = tr_curve_alloc(c, 2, nv, closed, err);
    if (rc != TR_OK)
        return rc;
    for (size_t i = 0; i < nv[0]; i++) {
        double p = TR_PI + TR_PI * (double)i / (double)(nv[0] - 1);
        c->x[3 * i] = 3 * cos(p), c->x[3 * i + 1] = 0, c->x[3 * i + 2] = 3 * sin(p);
    }
    for (size_t i = 0; i < nv[1]; i++) {
        double q = TR_PI * (double)i / (double)(nv[1] - 1);
        double *v = c->x + 3 * (nv[0] + i);
        v[0] = 0, v[1] = 3 * cos(q), v[2] = -3 + 3 * sin(q);
    }
    return TR_OK;
}

static int *next_array(const tr_curve *c)
{
    int *next = malloc(c->nv * sizeof *next);
    for (int k = 0; k < c->ncomp; k++)
        for (size_t i = c->start[k]; i < c->start[k + 1]; i++)
            next[i] = i + 1 < c->start[k + 1] ? (int)(i + 1) : (c->closed[k] ? (int)c->start[k] : -1);
    return next;
}

static void test_names(void)
{
    CHECK(!strcmp(tr_cl_strerror(-54), "CL_INVALID_WORK_GROUP_SIZE"));
    CHECK(!strcmp(tr_cl_strerror(-11), "CL_BUILD_PROGRAM_FAILURE"));
    CHECK(!strcmp(tr_cl_strerror(-1001), "CL_PLATFORM_NOT_FOUND_KHR"));
    CHECK(!strcmp(tr_cl_strerror(-72), "CL_MAX_SIZE_RESTRICTION_EXCEEDED"));
    CHECK(!strcmp(tr_cl_strerror(12345), "CL_UNKNOWN_ERROR"));
    /* every code from 0 to -72 that the 3.0 specification defines has a name */
    for (int c = 0; c >= -72; c--)
        if (c > -20 || c <= -30)
            CHECK(strcmp(tr_cl_strerror(c), "CL_UNKNOWN_ERROR") != 0);

    tr_error err;
    int rc = tr_cl_fail(&err, -54, "clEnqueueNDRangeKernel(q, k, 1, NULL, &g, &l, 0, NULL, NULL)",
                        "/x/host/backend/opencl/backend_opencl.c", 212);
    CHECK(rc == TR_EOPENCL);
    CHECK(!strcmp(err.msg,
                  "clEnqueueNDRangeKernel: CL_INVALID_WORK_GROUP_SIZE (-54) [backend_opencl.c:212]"));
    /* the errcode_ret form names the create call, not the assignment target */
    tr_cl_fail(&err, -61, "(buf = clCreateBuffer(ctx, 0, n, NULL, &e), e)", "a.c", 1);
    CHECK(!strncmp(err.msg, "clCreateBuffer: CL_INVALID_BUFFER_SIZE (-61)", 44));
}

/* A build log that counts lines of the whole program (Oclgrind's compiler
 * ignores #line in its messages) is mapped back to the files; locations
 * already in a file (a name cut short at a space or a quote included), or
 * outside every file, stay as they are. */
static void test_log_locate(void)
{
    const char *src[] = {"#line 1 \"kernels/common.clh\"\na\nb\n",
                         "#line 1 \"/k dir/\\\"q\\\".cl\"\nc\n",
                         "#line 1 \"kernels/tension.cl\"\nd\ne\nf\n"};
    /* lines of the whole program: 1 directive, 2-3 common.clh, 4 directive,
     * 5 the quoted file, 6 directive, 7-9 tension.cl */
    char *got = tr_kernel_log_locate("input.cl:8:3: error: x | input.cl:5:1: note: y\n"
                                     "kernels/tension.cl:2:1: error: z (input.cl:4:1, input.cl:99:1)\n"
                                     "/k dir/\"q\".cl:2:1: error: w",
                                     src, 3);
    const char *want = "kernels/tension.cl:2:3: error: x | /k dir/\"q\".cl:1:1: note: y\n"
                       "kernels/tension.cl:2:1: error: z (input.cl:4:1, input.cl:99:1)\n"
                       "/k dir/\"q\".cl:2:1: error: w";
    CHECK(got && !strcmp(got, want));
    if (got && strcmp(got, want))
        fprintf(stderr, "located log: %s\n", got);
    free(got);
    /* NVIDIA's compiler ignores #line too, and calls the program "<kernel>" */
    got = tr_kernel_log_locate("<kernel>:8:1: error: unknown type name 'q'\n<kernel>:42:1: note: r", src, 3);
    want = "kernels/tension.cl:2:1: error: unknown type name 'q'\n<kernel>:42:1: note: r";
    CHECK(got && !strcmp(got, want));
    if (got && strcmp(got, want))
        fprintf(stderr, "located log: %s\n", got);
    free(got);
}

/* The macro jumps to the cleanup ladder with the message filled in. */
static int failing_call(tr_error *err, int *cleaned)
{
    int rc = TR_OK;
    TR_CL_CHECK(clFinish(NULL));
    rc = 99; /* not reached */
cleanup:
    *cleaned = 1;
    return rc;
}

static void test_selection(int have_device)
{
    tr_error err;
    tr_device_choice ch;
    CHECK_OK(tr_device_select("reference", &ch, &err));
    CHECK(ch.kind == TR_DEVICE_REFERENCE && ch.warning[0] == '\0');
    CHECK(tr_device_select("97:3", &ch, &err) == TR_EINVAL);
    CHECK(strstr(err.msg, "97:3") != NULL);
    CHECK(tr_device_select("no-such-device-name", &ch, &err) == TR_EINVAL);
    CHECK_OK(tr_device_select("auto", &ch, &err));
    tr_device_choice any;
    if (have_device) {
        /* auto takes GPUs and accelerators only; "opencl" any usable device */
        CHECK_OK(tr_device_select("opencl", &any, &err));
        int gpu = (any.cl.type & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR)) != 0;
        CHECK(gpu ? ch.kind == TR_DEVICE_OPENCL : (ch.kind == TR_DEVICE_REFERENCE && ch.warning[0]));
        ch = any;
        CHECK(ch.kind == TR_DEVICE_OPENCL && ch.cl.usable && ch.cl.fp64);
        char pd[32];
        snprintf(pd, sizeof pd, "%d:%d", ch.cl.platform, ch.cl.device);
        tr_device_choice again;
        CHECK_OK(tr_device_select(pd, &again, &err));
        CHECK(again.kind == TR_DEVICE_OPENCL && again.cl.did == ch.cl.did);
        /* the platform vendor is a name to select by (PoCL: "The pocl
         * project", so --device pocl), whenever it names one usable device */
        CHECK(ch.cl.platform_vendor[0] != '\0');
        int same_vendor = 0;
        tr_cl_device_list l;
        if (tr_cl_enumerate(&l, &err) == TR_OK) {
            for (int i = 0; i < l.n; i++)
                same_vendor += l.dev[i].usable && !strcmp(l.dev[i].platform_vendor, ch.cl.platform_vendor);
            tr_cl_device_list_free(&l);
        }
        if (same_vendor == 1 && strlen(ch.cl.platform_vendor) < 128) {
            CHECK_OK(tr_device_select(ch.cl.platform_vendor, &again, &err));
            CHECK(again.kind == TR_DEVICE_OPENCL && again.cl.did == ch.cl.did);
        }
    } else {
        CHECK(ch.kind == TR_DEVICE_REFERENCE && ch.warning[0] != '\0');
        CHECK(tr_device_select("opencl", &any, &err) != TR_OK || any.kind != TR_DEVICE_OPENCL);
    }
}

/* The embedded text of kernel file `name` as it is in kernels/ (NULL if
 * there is none); tr_kernel_source_load would add its #line directive. */
static const char *embedded(const char *name)
{
    for (const tr_kernel_source *k = tr_kernel_sources; k->name; k++)
        if (!strcmp(k->name, name))
            return k->text;
    return NULL;
}

static int write_text(const char *dir, const char *name, const char *text)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    int ok = f && text && fputs(text, f) >= 0;
    if (f)
        ok = fclose(f) == 0 && ok;
    return ok;
}

/* Writes the preamble (TR_CL_PREAMBLE) and one kernel file `name` with text
 * `src` into the build's tests directory, for tr_cl_build under
 * TIGHTROPE_KERNEL_DIR. */
static int write_kernel_dir(const char *name, const char *src, char *dir, size_t dirsize)
{
    snprintf(dir, dirsize, "%s/tests", TR_BINARY_DIR);
    static const char *const preamble[TR_CL_PREAMBLE_COUNT] = TR_CL_PREAMBLE;
    int ok = write_text(dir, name, src);
    for (int k = 0; k < TR_CL_PREAMBLE_COUNT; k++)
        ok = ok && write_text(dir, preamble[k], embedded(preamble[k]));
    return ok;
}

static void test_build_failure(const tr_cl_ctx *ctx)
{
    /* A kernel directory whose reduce.cl has a syntax error: the message names
     * the call, the error, the options and the compiler's complaint. */
    char dir[1024];
    tr_error err;
    CHECK(write_kernel_dir("broken.cl",
                           "__kernel void broken(__global real *x) { x[0] = undefined_name; }\n",
                           dir, sizeof dir));
    setenv("TIGHTROPE_KERNEL_DIR", dir, 1);
    cl_program prog = NULL;
    const char *files[] = {"broken.cl"};
    tr_test_expect_cl_error("clBuildProgram", "CL_BUILD_PROGRAM_FAILURE");
    int rc = tr_cl_build(ctx, files, 1, "-cl-std=CL1.2", &prog, &err);
    unsetenv("TIGHTROPE_KERNEL_DIR");
    CHECK(rc == TR_EOPENCL && prog == NULL);
    CHECK(strstr(err.msg, "clBuildProgram: CL_BUILD_PROGRAM_FAILURE (-11)") != NULL);
    CHECK(strstr(err.msg, "-cl-std=CL1.2") != NULL);
    CHECK(strstr(err.msg, "undefined_name") != NULL);
    CHECK(strchr(err.msg, '\n') == NULL);
    /* the compiler names the file and its line (the #line directive) */
    char where[1100];
    snprintf(where, sizeof where, "%s/broken.cl:1:", dir);
    CHECK(strstr(err.msg, where) != NULL);
    if (rc == TR_OK && prog)
        clReleaseProgram(prog);
}

/* A syntax error in one file of the whole program (tension.cl, not the
 * first) from a kernel directory: the message names that file and the line
 * of the error, not the first file nor a line of the concatenated program
 * (PoCL: "line 846 of tempfile_*.cl"). The embedded sources carry the
 * directive that makes it so too, naming kernels/FILE. */
static void test_build_failure_line(const tr_cl_ctx *ctx)
{
    char *text = NULL;
    tr_error err;
    CHECK_OK(tr_kernel_source_load("reduce.cl", &text, &err));
    static const char directive[] = "#line 1 \"kernels/reduce.cl\"\n";
    CHECK(text && !strncmp(text, directive, strlen(directive)));
    free(text);

    char dir[1024];
    snprintf(dir, sizeof dir, "%s/tests/kernels_broken_tension", TR_BINARY_DIR);
    char mk[1100];
    snprintf(mk, sizeof mk, "mkdir -p '%s'", dir);
    CHECK(system(mk) == 0);
    int line = 1, ok = 1;
    for (const tr_kernel_source *k = tr_kernel_sources; k->name; k++) {
        if (strcmp(k->name, "tension.cl")) {
            ok = ok && write_text(dir, k->name, k->text);
            continue;
        }
        /* one bad declaration after the file's last line */
        size_t n = strlen(k->text);
        char *bad = malloc(n + 64);
        CHECK(bad != NULL && n > 0 && k->text[n - 1] == '\n');
        if (!bad)
            return;
        for (size_t i = 0; i < n; i++)
            line += k->text[i] == '\n';
        snprintf(bad, n + 64, "%str_no_such_type broken_here;\n", k->text);
        ok = ok && write_text(dir, k->name, bad);
        free(bad);
    }
    CHECK(ok);
    setenv("TIGHTROPE_KERNEL_DIR", dir, 1);
    cl_program prog = NULL;
    tr_test_expect_cl_error("clBuildProgram", "CL_BUILD_PROGRAM_FAILURE");
    int rc = tr_cl_build_all(ctx, &prog, &err);
    unsetenv("TIGHTROPE_KERNEL_DIR");
    CHECK(rc == TR_EOPENCL && prog == NULL);
    char where[1200];
    snprintf(where, sizeof where, "%s/tension.cl:%d:1:", dir, line);
    int named = strstr(err.msg, where) != NULL && strstr(err.msg, "tr_no_such_type") != NULL &&
                !strstr(err.msg, "building reduce.cl ...");
    if (!named)
        fprintf(stderr, "build error does not name %s: %s\n", where, err.msg);
    CHECK(named);
    if (rc == TR_OK && prog)
        clReleaseProgram(prog);
}

/* The curvature rows' turning angle (common.clh tr_turning_angle, a Cephes
 * atan of our own) against the C library's atan2, an independent
 * implementation (glibc's is correctly rounded in nearly all cases): on
 * angles across [0, pi] at every scale, both branches of the argument
 * reduction and their boundaries, and the exact cases. Moshier gives 1.8e-16
 * relative for the atan; the quotient and the reduction add a rounding or
 * two, so 4 ulp of the angle bounds the difference. */
static void test_turning_angle(const tr_cl_ctx *ctx)
{
    enum { N = 4096 };
    static const char src[] =
        "__kernel void angles(__global const real *s, __global const real *c,\n"
        "                     __global real *out, const int n)\n"
        "{ int i = get_global_id(0); if (i < n) out[i] = tr_turning_angle(s[i], c[i]); }\n";
    char dir[1024];
    CHECK(write_kernel_dir("angles.cl", src, dir, sizeof dir));
    setenv("TIGHTROPE_KERNEL_DIR", dir, 1);
    cl_program prog = NULL;
    tr_error err;
    const char *files[] = {"angles.cl"};
    int rc = tr_cl_build(ctx, files, 1, "", &prog, &err);
    unsetenv("TIGHTROPE_KERNEL_DIR");
    CHECK_OK(rc);
    if (rc != TR_OK)
        return;
    double *sv = malloc(3 * N * sizeof *sv);
    CHECK(sv != NULL);
    if (!sv) {
        clReleaseProgram(prog);
        return;
    }
    double *cv = sv + N, *got = sv + 2 * N;
    int n = 0;
    /* the exact cases, tiny angles, and subnormal ratios and operands */
    static const double special[][2] = {{0, 1},      {0, -1},      {1, 0},        {0, 0},
                                        {1e-300, 1}, {1, 1e-300},  {1e-310, 1},   {1e-300, 1e10},
                                        {1e-310, -1}, {5e-324, 1e-320}, {1, -1e-310}};
    for (size_t k = 0; k < sizeof special / sizeof special[0]; k++)
        sv[n] = special[k][0], cv[n] = special[k][1], n++;
    unsigned long long u = 88172645463325252ull; /* xorshift: any fixed sequence */
    while (n < N) {
        u ^= u << 13, u ^= u >> 7, u ^= u << 17;
        double r = (double)(u >> 11) / 9007199254740992.0;
        double theta;
        if (n % 4 == 0)
            theta = TR_PI * r; /* uniform */
        else if (n % 4 == 1)
            theta = pow(10.0, -12.0 + 12.0 * r); /* small, as on fine curves */
        else if (n % 4 == 2)
            theta = atan(0.66) + 1e-6 * (r - 0.5); /* the reduction's boundary */
        else
            theta = TR_PI / 2 + 1e-6 * (r - 0.5); /* the s = |c| switch, 0.75 pi too below */
        if (n % 8 == 6)
            theta = 0.75 * TR_PI + 1e-6 * (r - 0.5);
        double len = pow(10.0, -3.0 + 6.0 * r);
        sv[n] = len * sin(theta), cv[n] = len * cos(theta), n++;
    }
    cl_int e = CL_SUCCESS;
    cl_kernel k = clCreateKernel(prog, "angles", &e);
    CHECK(e == CL_SUCCESS);
    cl_mem bs = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                               N * sizeof(double), sv, &e);
    CHECK(e == CL_SUCCESS);
    cl_mem bc = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                               N * sizeof(double), cv, &e);
    CHECK(e == CL_SUCCESS);
    cl_mem bo = clCreateBuffer(ctx->context, CL_MEM_WRITE_ONLY, N * sizeof(double), NULL, &e);
    CHECK(e == CL_SUCCESS);
    int nn = N;
    CHECK(tr_cl_args_at(&err, __FILE__, __LINE__, k, 0, TR_CL_A(bs), TR_CL_A(bc), TR_CL_A(bo),
                        TR_CL_A(nn), TR_CL_END) == TR_OK);
    /* an argument past the last (angles has four) is named by kernel and index */
    tr_test_expect_cl_error("clSetKernelArg", "CL_INVALID_ARG_INDEX");
    CHECK(tr_cl_args_at(&err, "here.c", 7, k, 3, TR_CL_A(nn), TR_CL_A(nn), TR_CL_END) == TR_EOPENCL);
    int named = strcmp(err.msg, "kernel angles, argument 4: clSetKernelArg: "
                                "CL_INVALID_ARG_INDEX (-49) [here.c:7]") == 0;
    if (!named)
        fprintf(stderr, "argument error: %s\n", err.msg);
    CHECK(named);
    size_t g = N;
    CHECK(clEnqueueNDRangeKernel(ctx->queue, k, 1, NULL, &g, NULL, 0, NULL, NULL) == CL_SUCCESS);
    CHECK(clEnqueueReadBuffer(ctx->queue, bo, CL_TRUE, 0, N * sizeof(double), got, 0, NULL, NULL) ==
          CL_SUCCESS);
    double worst = 0.0;
    int bad = 0;
    for (int i = 0; i < N; i++) {
        double want = atan2(sv[i], cv[i]);
        /* in units of want's last place (subnormals: the smallest step) */
        double ulps = got[i] == want ? 0.0 : fabs(got[i] - want) / (nextafter(want, INFINITY) - want);
        worst = fmax(worst, ulps);
        if (!(ulps <= 4.0) && bad++ < 5)
            fprintf(stderr, "turning angle (%.17g, %.17g): %.17g, atan2 %.17g\n", sv[i], cv[i],
                    got[i], want);
    }
    CHECK(bad == 0);
    printf("turning angle: worst %.2f ulp of libm atan2 over %d cases\n", worst, N);
    clReleaseMemObject(bs);
    clReleaseMemObject(bc);
    clReleaseMemObject(bo);
    clReleaseKernel(k);
    clReleaseProgram(prog);
    free(sv);
}

static void test_reductions(const tr_cl_ctx *ctx)
{
    tr_error err;
    tr_cl_reduce red;
    const size_t sizes[] = {3, 4, 7, 63, 64, 65, 1021, 1024, 4099};
    const size_t maxn = 4099 + 6;
    cl_program prog = NULL;
    if (tr_cl_build_all(ctx, &prog, &err) != TR_OK || tr_cl_reduce_init(&red, ctx, prog, maxn, &err) != TR_OK) {
        tr_test_failures++;
        fprintf(stderr, "reduce init: %s\n", err.msg);
        return;
    }
    for (int kind = 0; kind < 3; kind++)
        for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
            tr_curve c;
            size_t n = sizes[s] + (kind ? 3 : 0); /* links and ropes need >= 2 per component */
            CHECK_OK(make_test_curve(&c, kind, n, &err));
            int *next = next_array(&c);
            double *coord = malloc(c.nv * sizeof *coord);
            cl_int e;
            cl_mem bx = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                       3 * c.nv * sizeof(double), c.x, &e);
            cl_mem bn = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                       c.nv * sizeof(int), next, &e);
            for (size_t i = 0; i < c.nv; i++)
                coord[i] = c.x[3 * i + 2] + 1e-3 * (double)(i % 7); /* z with ripples */
            cl_mem bv = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                       c.nv * sizeof(double), coord, &e);
            cl_mem out = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, 4 * sizeof(double), NULL, &e);
            CHECK(e == CL_SUCCESS);
            double got[4] = {0, 0, 0, 0};
            CHECK_OK(tr_cl_reduce_length(&red, ctx, bx, bn, (int)c.nv, out, 0, &err));
            CHECK_OK(tr_cl_reduce_minmax(&red, ctx, bv, (int)c.nv, out, 1, &err));
            CHECK_OK(tr_cl_reduce_sum(&red, ctx, bv, (int)c.nv, out, 3, &err));
            CHECK(clEnqueueReadBuffer(ctx->queue, out, CL_TRUE, 0, 4 * sizeof(double), got, 0, NULL,
                                      NULL) == CL_SUCCESS);
            /* the sum, one stage up to 1024 entries and two above: against
             * the host's Neumaier sum; either errs by at most ~log2(N) eps of
             * the sum of magnitudes, so 1e-14 of that bounds the difference */
            tr_csum hs = {0.0, 0.0};
            double mag = 0.0;
            for (size_t i = 0; i < c.nv; i++) {
                tr_csum_add(&hs, coord[i]);
                mag += fabs(coord[i]);
            }
            CHECK_NEAR(got[3], tr_csum_value(&hs), 1e-14 * mag);
            /* Pairwise (device) and Neumaier (host) sums of N positive edge
             * lengths both err by at most ~log2(N) eps L < 13 * 1.1e-16 L, so
             * 1e-14 relative bounds the difference with margin; each edge
             * length itself is computed with the same operations (no FMA). */
            double want = tr_curve_length(&c);
            CHECK_NEAR(got[0], want, 1e-14 * want);
            double lo = coord[0], hi = coord[0];
            for (size_t i = 0; i < c.nv; i++)
                lo = fmin(lo, coord[i]), hi = fmax(hi, coord[i]);
            CHECK(got[1] == lo && got[2] == hi); /* min/max are exact */
            if (!(fabs(got[0] - want) <= 1e-14 * want) || got[1] != lo || got[2] != hi)
                fprintf(stderr, "kind %d n %zu: length %.17g vs %.17g, min %g/%g max %g/%g\n", kind,
                        c.nv, got[0], want, got[1], lo, got[2], hi);
            clReleaseMemObject(bx);
            clReleaseMemObject(bn);
            clReleaseMemObject(bv);
            clReleaseMemObject(out);
            free(next);
            free(coord);
            tr_curve_free(&c);
        }
    /* a closed form: the regular 1024-gon inscribed in the unit circle has length 2048 sin(pi/1024) */
    {
        size_t n = 1024;
        unsigned char closed = 1;
        tr_curve c;
        CHECK_OK(tr_curve_alloc(&c, 1, &n, &closed, &err));
        for (size_t i = 0; i < n; i++)
            c.x[3 * i] = cos(2 * TR_PI * i / n), c.x[3 * i + 1] = sin(2 * TR_PI * i / n);
        int *next = next_array(&c);
        cl_int e;
        cl_mem bx = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                   3 * n * sizeof(double), c.x, &e);
        cl_mem bn = clCreateBuffer(ctx->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                   n * sizeof(int), next, &e);
        cl_mem out = clCreateBuffer(ctx->context, CL_MEM_READ_WRITE, sizeof(double), NULL, &e);
        double got = 0;
        CHECK_OK(tr_cl_reduce_length(&red, ctx, bx, bn, (int)n, out, 0, &err));
        CHECK(clEnqueueReadBuffer(ctx->queue, out, CL_TRUE, 0, sizeof got, &got, 0, NULL, NULL) ==
              CL_SUCCESS);
        /* cos/sin of the vertices are accurate to ~1 ulp, so each edge to a few ulp */
        CHECK_NEAR(got, 2048 * sin(TR_PI / 1024), 1e-13);
        /* too many items for the prepared partial buffers is an error, not an overrun */
        CHECK(tr_cl_reduce_length(&red, ctx, bx, bn, 1 << 20, out, 0, &err) == TR_EINVAL);
        clReleaseMemObject(bx);
        clReleaseMemObject(bn);
        clReleaseMemObject(out);
        free(next);
        tr_curve_free(&c);
    }
    tr_cl_reduce_free(&red);
    clReleaseProgram(prog);
}

int main(void)
{
    test_names();
    test_log_locate();
    tr_error err;
    int cleaned = 0;
    tr_test_expect_cl_error("clFinish", "CL_INVALID_COMMAND_QUEUE");
    CHECK(failing_call(&err, &cleaned) == TR_EOPENCL && cleaned);
    CHECK(!strncmp(err.msg, "clFinish: CL_INVALID_COMMAND_QUEUE (-36)", 40));

    tr_device_choice ch;
    int have = tr_device_select("opencl", &ch, &err) == TR_OK && ch.kind == TR_DEVICE_OPENCL;
    test_selection(have);
    if (!have) {
        printf("no usable opencl device: device tests skipped (%s)\n", ch.warning);
        return tr_test_failures ? tr_test_finish("test_opencl_device") : TR_SKIP;
    }
    printf("device %d:%d %s\n", ch.cl.platform, ch.cl.device, ch.cl.name);
    tr_cl_ctx ctx;
    if (tr_cl_ctx_open(&ctx, &ch.cl, 0, &err) != TR_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    test_build_failure(&ctx);
    test_build_failure_line(&ctx);
    test_turning_angle(&ctx);
    test_reductions(&ctx);
    tr_cl_ctx_close(&ctx);
    return tr_test_finish("test_opencl_device");
}
