/* This file contains the OpenCL device layer: platform and device enumeration
 * (FP64, a kernel build before a device is called usable), selection by spec,
 * the context and queue, and program builds (cl_device.h). */
#include "backend/opencl/cl_device.h"
#include "backend/opencl/cl_reduce.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "backend/opencl/cl_error.h"
#include "backend/opencl/cl_signals.h"
#include "backend/opencl/kernel_source.h"
#include "util/device_spec.h"

static void get_string(cl_device_id d, cl_device_info what, char *buf, size_t n)
{
    size_t got = 0;
    if (clGetDeviceInfo(d, what, n - 1, buf, &got) != CL_SUCCESS)
        got = 0;
    buf[got < n ? got : n - 1] = '\0';
}

/* Extension strings can be long (PoCL: ~1 KB), so query the size first. */
static int has_extension(cl_device_id d, const char *ext)
{
    size_t n = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, 0, NULL, &n) != CL_SUCCESS || n == 0)
        return 0;
    char *s = malloc(n + 1);
    if (!s)
        return 0;
    int found = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_EXTENSIONS, n, s, NULL) == CL_SUCCESS) {
        s[n] = '\0';
        size_t len = strlen(ext);
        for (char *p = strstr(s, ext); p; p = strstr(p + 1, ext))
            if ((p == s || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0')) {
                found = 1;
                break;
            }
    }
    free(s);
    return found;
}

/* "auto" ranks by a crude throughput estimate: compute units x clock, with
 * GPUs and accelerators weighted by the lanes one of their compute units
 * runs at once. Good enough to prefer a discrete GPU over a CPU driver; ties
 * go to the lower P:D so the choice is reproducible. */
static double device_score(const tr_cl_device_info *d)
{
    double lanes = (d->type & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR)) ? 32.0 : 1.0;
    double clock = d->clock_mhz ? d->clock_mhz : 1000.0;
    return lanes * (double)(d->compute_units ? d->compute_units : 1) * clock;
}

static void describe_device(tr_cl_device_info *d)
{
    cl_device_id id = d->did;
    get_string(id, CL_DEVICE_NAME, d->name, sizeof d->name);
    get_string(id, CL_DEVICE_VENDOR, d->vendor, sizeof d->vendor);
    get_string(id, CL_DEVICE_VERSION, d->version, sizeof d->version);
    get_string(id, CL_DRIVER_VERSION, d->driver, sizeof d->driver);
    if (clGetDeviceInfo(id, CL_DEVICE_TYPE, sizeof d->type, &d->type, NULL) != CL_SUCCESS)
        d->type = 0;
    if (clGetDeviceInfo(id, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof d->compute_units, &d->compute_units,
                        NULL) != CL_SUCCESS)
        d->compute_units = 0;
    if (clGetDeviceInfo(id, CL_DEVICE_MAX_CLOCK_FREQUENCY, sizeof d->clock_mhz, &d->clock_mhz,
                        NULL) != CL_SUCCESS)
        d->clock_mhz = 0;
    if (clGetDeviceInfo(id, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof d->global_mem, &d->global_mem, NULL) !=
        CL_SUCCESS)
        d->global_mem = 0;
    if (clGetDeviceInfo(id, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof d->max_work_group,
                        &d->max_work_group, NULL) != CL_SUCCESS)
        d->max_work_group = 0;
    cl_device_fp_config fp = 0;
    if (clGetDeviceInfo(id, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof fp, &fp, NULL) != CL_SUCCESS)
        fp = 0;
    int ext = has_extension(id, "cl_khr_fp64") || has_extension(id, "cl_amd_fp64");
    d->fp64 = ext && fp != 0;
    cl_bool avail = CL_FALSE, compiler = CL_FALSE;
    if (clGetDeviceInfo(id, CL_DEVICE_AVAILABLE, sizeof avail, &avail, NULL) != CL_SUCCESS)
        avail = CL_FALSE;
    if (clGetDeviceInfo(id, CL_DEVICE_COMPILER_AVAILABLE, sizeof compiler, &compiler, NULL) !=
        CL_SUCCESS)
        compiler = CL_FALSE;

    d->usable = 0;
    if (!d->fp64)
        snprintf(d->reason, sizeof d->reason,
                 "no double precision (cl_khr_fp64 missing): curvature near 1 needs fp64");
    else if (!avail)
        snprintf(d->reason, sizeof d->reason, "device reports itself unavailable");
    else if (!compiler)
        snprintf(d->reason, sizeof d->reason, "no opencl c compiler for this device");
    else if (d->max_work_group < TR_LOCAL_SIZE)
        snprintf(d->reason, sizeof d->reason, "work-group limit %zu below the %d the kernels use",
                 d->max_work_group, TR_LOCAL_SIZE);
    else {
        d->usable = 1;
        d->reason[0] = '\0';
    }
    d->score = device_score(d);
}

/* A device whose driver cannot build our kernels is not usable, however
 * it describes itself: they are built once here (the driver caches the
 * binary, PoCL in POCL_CACHE_DIR, so the backend's own build is cheap). */
static void check_kernels(tr_cl_device_info *d)
{
    tr_cl_ctx ctx;
    tr_error why;
    cl_program prog = NULL;
    int rc = tr_cl_ctx_open(&ctx, d, 0, &why);
    if (rc == TR_OK) {
        rc = tr_cl_build_all(&ctx, &prog, &why);
        if (prog)
            clReleaseProgram(prog);
        tr_cl_ctx_close(&ctx);
    }
    if (rc != TR_OK) {
        d->usable = 0;
        snprintf(d->reason, sizeof d->reason, "the kernels do not build: %.480s", why.msg);
    }
}

static int enumerate(tr_cl_device_list *out, tr_error *err)
{
    int rc = TR_OK;
    cl_platform_id *plat = NULL;
    cl_device_id *devs = NULL;
    memset(out, 0, sizeof *out);

    cl_uint np = 0;
    cl_int e = clGetPlatformIDs(0, NULL, &np);
    /* ocl-icd answers CL_PLATFORM_NOT_FOUND_KHR when no ICD file exists;
     * that is "no OpenCL here", not a failure of the program. */
    if (e == CL_PLATFORM_NOT_FOUND_KHR || (e == CL_SUCCESS && np == 0)) {
        tr_error why;
        if (e != CL_SUCCESS)
            tr_cl_fail(&why, e, "clGetPlatformIDs", __FILE__, __LINE__);
        snprintf(out->none_reason, sizeof out->none_reason, "%.160s%sno opencl platform (icd) installed",
                 e != CL_SUCCESS ? why.msg : "", e != CL_SUCCESS ? ": " : "");
        return TR_OK;
    }
    TR_CL_CHECK(e);
    plat = calloc(np, sizeof *plat);
    if (!plat) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory listing opencl platforms");
        goto cleanup;
    }
    TR_CL_CHECK(clGetPlatformIDs(np, plat, NULL));

    for (cl_uint p = 0; p < np; p++) {
        char pname[128];
        size_t got = 0;
        TR_CL_CHECK(clGetPlatformInfo(plat[p], CL_PLATFORM_NAME, sizeof pname - 1, pname, &got));
        pname[got < sizeof pname ? got : sizeof pname - 1] = '\0';
        char pvendor[128];
        TR_CL_CHECK(clGetPlatformInfo(plat[p], CL_PLATFORM_VENDOR, sizeof pvendor - 1, pvendor, &got));
        pvendor[got < sizeof pvendor ? got : sizeof pvendor - 1] = '\0';

        cl_uint nd = 0;
        e = clGetDeviceIDs(plat[p], CL_DEVICE_TYPE_ALL, 0, NULL, &nd);
        if (e == CL_DEVICE_NOT_FOUND || nd == 0)
            continue; /* a platform without devices (e.g. POCL_DEVICES naming none) */
        TR_CL_CHECK(e);
        free(devs);
        devs = calloc(nd, sizeof *devs);
        tr_cl_device_info *grown = realloc(out->dev, (size_t)(out->n + (int)nd) * sizeof *grown);
        if (!devs || !grown) {
            if (grown)
                out->dev = grown;
            rc = tr_fail(err, TR_ENOMEM, "out of memory listing opencl devices");
            goto cleanup;
        }
        out->dev = grown;
        TR_CL_CHECK(clGetDeviceIDs(plat[p], CL_DEVICE_TYPE_ALL, nd, devs, NULL));
        for (cl_uint d = 0; d < nd; d++) {
            tr_cl_device_info *info = &out->dev[out->n++];
            memset(info, 0, sizeof *info);
            info->platform = (int)p;
            info->device = (int)d;
            info->pid = plat[p];
            info->did = devs[d];
            snprintf(info->platform_name, sizeof info->platform_name, "%s", pname);
            snprintf(info->platform_vendor, sizeof info->platform_vendor, "%s", pvendor);
            describe_device(info);
            if (info->usable)
                check_kernels(info);
        }
    }
    if (out->n == 0)
        snprintf(out->none_reason, sizeof out->none_reason,
                 "opencl platforms found but none has a device");

cleanup:
    free(plat);
    free(devs);
    if (rc != TR_OK)
        tr_cl_device_list_free(out);
    return rc;
}

/* the platforms' first calls load PoCL's LLVM, and the kernels' test builds
 * run it: the caller's signal handlers are kept (cl_signals.h) */
int tr_cl_enumerate(tr_cl_device_list *out, tr_error *err)
{
    tr_cl_signals kept;
    tr_cl_signals_keep(&kept);
    int rc = enumerate(out, err);
    tr_cl_signals_restore(&kept);
    return rc;
}

void tr_cl_device_list_free(tr_cl_device_list *l)
{
    free(l->dev);
    l->dev = NULL;
    l->n = 0;
}

const char *tr_device_spec_default(void)
{
    const char *s = getenv("TIGHTROPE_DEVICE");
    return (s && *s) ? s : "auto";
}

static int contains_nocase(const char *hay, const char *needle)
{
    size_t n = strlen(needle);
    for (; *hay; hay++) {
        size_t k = 0;
        while (k < n && hay[k] && tolower((unsigned char)hay[k]) == tolower((unsigned char)needle[k]))
            k++;
        if (k == n)
            return 1;
    }
    return n == 0;
}

static int parse_pd(const char *s, int *p, int *d)
{
    char *end;
    if (!isdigit((unsigned char)s[0]))
        return 0;
    long a = strtol(s, &end, 10);
    if (*end != ':' || !isdigit((unsigned char)end[1]))
        return 0;
    long b = strtol(end + 1, &end, 10);
    if (*end || a > 1000 || b > 1000)
        return 0;
    *p = (int)a;
    *d = (int)b;
    return 1;
}

int tr_device_select(const char *spec, tr_device_choice *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (!spec || !*spec)
        spec = tr_device_spec_default();
    snprintf(out->spec, sizeof out->spec, "%s", spec);
    if (tr_device_spec_is_reference(spec)) {
        out->kind = TR_DEVICE_REFERENCE;
        return TR_OK;
    }

    tr_cl_device_list l;
    tr_error why; /* err may be NULL; the message is needed for the warning */
    int rc = tr_cl_enumerate(&l, &why);
    if (rc != TR_OK) {
        if (strcmp(spec, "auto"))
            return tr_fail(err, rc, "%s", why.msg);
        /* auto: OpenCL is broken here; the reference still works. */
        out->kind = TR_DEVICE_REFERENCE;
        snprintf(out->warning, sizeof out->warning, "using the serial reference: %.400s", why.msg);
        return TR_OK;
    }

    if (!strcmp(spec, "auto") || !strcmp(spec, "opencl")) {
        /* "auto" means the fastest: an OpenCL driver running on this host's
         * own CPU (PoCL) was measured slower than the serial reference on the
         * whole step (bench/notes/2026-11-23-opencl-targets-issue-4.md), so
         * auto takes the best GPU or
         * accelerator, whatever a CPU driver scores; "opencl" or P:D still
         * selects a CPU driver. */
        int best = -1, best_accel = -1;
        for (int i = 0; i < l.n; i++) {
            if (!l.dev[i].usable)
                continue;
            if (best < 0 || l.dev[i].score > l.dev[best].score)
                best = i;
            if ((l.dev[i].type & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR)) &&
                (best_accel < 0 || l.dev[i].score > l.dev[best_accel].score))
                best_accel = i;
        }
        if (!strcmp(spec, "auto") && best_accel >= 0)
            best = best_accel;
        int cpu_only = best >= 0 && best_accel < 0;
        if (best >= 0 && !(cpu_only && !strcmp(spec, "auto"))) {
            out->kind = TR_DEVICE_OPENCL;
            out->cl = l.dev[best];
        } else if (best >= 0) {
            out->kind = TR_DEVICE_REFERENCE;
            snprintf(out->warning, sizeof out->warning,
                     "using the serial reference: the only opencl devices run on this cpu (%d:%d "
                     "%.100s), slower than the reference here; --device opencl selects them",
                     l.dev[best].platform, l.dev[best].device, l.dev[best].name);
        } else if (!strcmp(spec, "opencl")) {
            rc = tr_fail(err, TR_EUNSUPPORTED, "no usable opencl device (%.400s)",
                         l.n ? l.dev[0].reason : l.none_reason);
        } else {
            out->kind = TR_DEVICE_REFERENCE;
            snprintf(out->warning, sizeof out->warning,
                     "using the serial reference: no usable opencl device (%.300s)",
                     l.n ? l.dev[0].reason : l.none_reason);
        }
        tr_cl_device_list_free(&l);
        return rc;
    }

    int p, d, found = -1, matches = 0;
    if (parse_pd(spec, &p, &d)) {
        for (int i = 0; i < l.n; i++)
            if (l.dev[i].platform == p && l.dev[i].device == d)
                found = i;
        if (found < 0)
            rc = tr_fail(err, TR_EINVAL, "no opencl device %d:%d ('tightrope devices' lists them)", p, d);
    } else {
        for (int i = 0; i < l.n; i++)
            /* the platform vendor lets "pocl", "nvidia" or "amd" select a driver */
            if (contains_nocase(l.dev[i].name, spec) || contains_nocase(l.dev[i].platform_name, spec) ||
                contains_nocase(l.dev[i].platform_vendor, spec)) {
                /* Prefer usable matches; an unusable one is reported below. */
                if (found < 0 || (l.dev[i].usable && !l.dev[found].usable))
                    found = i;
                matches += l.dev[i].usable;
            }
        if (found < 0)
            rc = tr_fail(err, TR_EINVAL,
                         "no device matches '%s' (use reference, auto, P:D or part of a device, platform or vendor name)", spec);
        else if (matches > 1)
            rc = tr_fail(err, TR_EINVAL, "'%s' matches %d usable devices; use P:D", spec, matches);
    }
    if (rc == TR_OK && !l.dev[found].usable)
        rc = tr_fail(err, TR_EUNSUPPORTED, "opencl device %d:%d (%s) is unusable: %s",
                     l.dev[found].platform, l.dev[found].device, l.dev[found].name,
                     l.dev[found].reason);
    if (rc == TR_OK) {
        out->kind = TR_DEVICE_OPENCL;
        out->cl = l.dev[found];
    }
    tr_cl_device_list_free(&l);
    return rc;
}

static int ctx_open(tr_cl_ctx *ctx, const tr_cl_device_info *dev, int profiling, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    memset(ctx, 0, sizeof *ctx);
    ctx->info = *dev;
    ctx->profiling = profiling;
    int blocks = (dev->type & CL_DEVICE_TYPE_CPU) != 0;
    const char *v = getenv("TIGHTROPE_CL_ITEMS");
    if (v && *v) {
        if (strcmp(v, "one") && strcmp(v, "blocks"))
            return tr_fail(err, TR_EINVAL, "TIGHTROPE_CL_ITEMS='%s': use one or blocks", v);
        blocks = !strcmp(v, "blocks");
    }
    /* a few blocks per core, so that uneven ones (a tight knot's crowded
     * stretches) still balance */
    size_t units = dev->compute_units ? dev->compute_units : 1;
    ctx->block_items = blocks ? TR_CL_BLOCKS_PER_UNIT * units : 0;
    if (profiling && !(ctx->prof = calloc(1, sizeof *ctx->prof)))
        return tr_fail(err, TR_ENOMEM, "out of memory for the kernel profile");
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)dev->pid, 0};
    TR_CL_CHECK((ctx->context = clCreateContext(props, 1, &dev->did, NULL, NULL, &e), e));
    TR_CL_CHECK((ctx->queue = clCreateCommandQueue(ctx->context, dev->did,
                                                   profiling ? CL_QUEUE_PROFILING_ENABLE : 0, &e),
                 e));
    return TR_OK;
cleanup:
    tr_cl_ctx_close(ctx);
    return rc;
}

int tr_cl_ctx_open(tr_cl_ctx *ctx, const tr_cl_device_info *dev, int profiling, tr_error *err)
{
    tr_cl_signals kept;
    tr_cl_signals_keep(&kept);
    int rc = ctx_open(ctx, dev, profiling, err);
    tr_cl_signals_restore(&kept);
    return rc;
}

void tr_cl_ctx_close(tr_cl_ctx *ctx)
{
    if (ctx->queue)
        clReleaseCommandQueue(ctx->queue);
    if (ctx->context)
        clReleaseContext(ctx->context);
    free(ctx->prof);
    ctx->queue = NULL;
    ctx->context = NULL;
    ctx->prof = NULL;
}

/* The profile entry of kernel k, added on first sight (NULL when full). */
static int prof_slot(tr_cl_prof *p, cl_kernel k)
{
    char name[sizeof p->name[0]];
    tr_cl_kernel_name(k, name, sizeof name);
    for (int i = 0; i < p->count; i++)
        if (!strcmp(p->name[i], name))
            return i;
    if (p->count == TR_CL_PROF_MAX)
        return -1;
    snprintf(p->name[p->count], sizeof p->name[0], "%s", name);
    return p->count++;
}

int tr_cl_launch(const tr_cl_ctx *ctx, cl_kernel k, size_t global, size_t local, tr_error *err)
{
    int rc = TR_OK;
    cl_event ev = NULL;
    TR_CL_CHECK(clEnqueueNDRangeKernel(ctx->queue, k, 1, NULL, &global, &local, 0, NULL,
                                       ctx->prof ? &ev : NULL));
    if (ev) {
        cl_ulong t0 = 0, t1 = 0;
        TR_CL_CHECK(clWaitForEvents(1, &ev));
        TR_CL_CHECK(clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, NULL));
        TR_CL_CHECK(clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, NULL));
        int i = prof_slot(ctx->prof, k);
        if (i >= 0) {
            ctx->prof->seconds[i] += 1e-9 * (double)(t1 - t0);
            ctx->prof->launches[i]++;
        }
    }
cleanup:
    if (ev)
        clReleaseEvent(ev);
    return rc;
}

size_t tr_cl_items_global(const tr_cl_ctx *ctx, size_t n)
{
    if (!ctx->block_items)
        return tr_cl_global(n);
    return n < ctx->block_items ? (n ? n : 1) : ctx->block_items;
}

int tr_cl_launch_items(const tr_cl_ctx *ctx, cl_kernel k, size_t n, tr_error *err)
{
    /* blocks: always one item per group, since PoCL compiles a kernel again
     * for every local size it meets */
    return tr_cl_launch(ctx, k, tr_cl_items_global(ctx, n), ctx->block_items ? 1 : TR_LOCAL_SIZE, err);
}

/* One-line error text: the build log's line breaks become " | ". */
static void fold_lines(const char *in, char *out, size_t n)
{
    size_t w = 0;
    for (const char *r = in; *r && w + 4 < n; r++) {
        if (*r == '\n' || *r == '\r') {
            while (w > 0 && out[w - 1] == ' ')
                w--;
            while (r[1] == '\n' || r[1] == '\r' || r[1] == ' ')
                r++;
            if (w > 0 && r[1]) {
                memcpy(out + w, " | ", 3);
                w += 3;
            }
        } else {
            out[w++] = *r;
        }
    }
    out[w] = '\0';
}

/* The OpenCL C compiler of some drivers (PoCL's clang, in this process)
 * writes to the process's stderr itself, beside the build log: "2 errors
 * generated." came before the one line that said what failed. While a
 * program builds, descriptor 2 points at a temporary file; what the
 * compiler wrote there goes into the error message (when the build fails)
 * or nowhere. Without a temporary file the build runs as before. */
typedef struct stderr_hold {
    int saved;
    FILE *tmp;
} stderr_hold;

static void hold_stderr(stderr_hold *h)
{
    fflush(stderr);
    h->saved = -1;
    h->tmp = tmpfile();
    if (!h->tmp)
        return;
    h->saved = dup(2);
    if (h->saved < 0 || dup2(fileno(h->tmp), 2) < 0) {
        if (h->saved >= 0)
            close(h->saved);
        h->saved = -1;
        fclose(h->tmp);
        h->tmp = NULL;
    }
}

/* Restores stderr; *text (may be NULL) gets up to n - 1 bytes of what was
 * written to it meanwhile. */
static void release_stderr(stderr_hold *h, char *text, size_t n)
{
    if (text && n)
        text[0] = '\0';
    if (!h->tmp)
        return;
    fflush(stderr);
    dup2(h->saved, 2);
    close(h->saved);
    if (text && n && fseek(h->tmp, 0, SEEK_SET) == 0) {
        size_t got = fread(text, 1, n - 1, h->tmp);
        text[got] = '\0';
        for (size_t i = 0; i < got; i++) /* one line of plain text */
            if (text[i] == '\0' || (text[i] != '\n' && (unsigned char)text[i] < ' '))
                text[i] = ' ';
    }
    fclose(h->tmp);
    h->tmp = NULL;
}

static int build(const tr_cl_ctx *ctx, const char *const *files, int nfiles, const char *options,
                cl_program *out, tr_error *err)
{
    int rc = TR_OK;
    cl_int e = CL_SUCCESS;
    cl_program prog = NULL;
    char *log = NULL;
    static const char *const preamble[TR_CL_PREAMBLE_COUNT] = TR_CL_PREAMBLE;
    const int np = TR_CL_PREAMBLE_COUNT;
    char **src = calloc((size_t)(nfiles + np), sizeof *src);
    *out = NULL;
    if (!src)
        return tr_fail(err, TR_ENOMEM, "out of memory loading kernels");
    for (int i = 0; i < np; i++)
        TR_TRY(tr_kernel_source_load(preamble[i], &src[i], err));
    for (int i = 0; i < nfiles; i++)
        TR_TRY(tr_kernel_source_load(files[i], &src[np + i], err));
    TR_CL_CHECK((prog = clCreateProgramWithSource(ctx->context, (cl_uint)(nfiles + np),
                                                  (const char **)src, NULL, &e),
                 e));
    if (!options)
        options = "";
    /* kernels/common.clh GROUP_SLICE_FOR: the shape of a work-group's loop
     * follows the launch shape (tr_cl_launch_items) */
    char opts[512];
    if (snprintf(opts, sizeof opts, "%s%s", options, ctx->block_items ? " -DTR_BLOCK_ITEMS" : "") >=
        (int)sizeof opts) {
        rc = tr_fail(err, TR_EINVAL, "OpenCL build options too long: '%s'", options);
        goto cleanup;
    }
    options = opts;
    stderr_hold hold = {.saved = -1, .tmp = NULL};
    char said[256] = "";
    /* TIGHTROPE_CL_BUILD_STDERR=keep leaves stderr to the runtime during
     * the build: a checker such as Oclgrind reports a failed build there,
     * and its harness (scripts/oclgrind_run.sh) must see that report */
    const char *keep = getenv("TIGHTROPE_CL_BUILD_STDERR");
    int hold_it = !(keep && !strcmp(keep, "keep"));
    if (hold_it)
        hold_stderr(&hold);
    e = clBuildProgram(prog, 1, &ctx->info.did, options, NULL, NULL);
    if (hold_it)
        release_stderr(&hold, said, sizeof said);
    if (e != CL_SUCCESS) {
        size_t n = 0;
        if (clGetProgramBuildInfo(prog, ctx->info.did, CL_PROGRAM_BUILD_LOG, 0, NULL, &n) ==
                CL_SUCCESS &&
            n > 0 && (log = malloc(n + 1)) != NULL) {
            if (clGetProgramBuildInfo(prog, ctx->info.did, CL_PROGRAM_BUILD_LOG, n, log, NULL) !=
                CL_SUCCESS)
                log[0] = '\0';
            log[n] = '\0';
        }
        /* every file: the log's "FILE:LINE:" says which one failed */
        char what[256] = "", folded[768], chatter[256];
        for (int i = 0; i < np + nfiles; i++) {
            size_t w = strlen(what);
            snprintf(what + w, sizeof what - w, "%s%s", i ? ", " : "",
                     i < np ? preamble[i] : files[i - np]);
        }
        char *located = log ? tr_kernel_log_locate(log, (const char *const *)src, np + nfiles) : NULL;
        fold_lines(located ? located : log ? log : "", folded, sizeof folded);
        free(located);
        fold_lines(said, chatter, sizeof chatter);
        /* the compiler's own words first (an error message is cut at its
         * end), then what it wrote on stderr ("2 errors generated."), then
         * the call and what it built */
        rc = tr_fail(err, TR_EOPENCL, "%s%s%s (clBuildProgram: %s (%d) building %s with options '%s')",
                     folded[0] ? folded : "no build log", chatter[0] && !strstr(folded, chatter) ? " | " : "",
                     chatter[0] && !strstr(folded, chatter) ? chatter : "", tr_cl_strerror(e), (int)e, what,
                     options);
        goto cleanup;
    }
    *out = prog;
    prog = NULL;
cleanup:
    if (prog)
        clReleaseProgram(prog);
    free(log);
    for (int i = 0; i < nfiles + np; i++)
        free(src[i]);
    free(src);
    return rc;
}

/* the build runs PoCL's LLVM: the caller's signal handlers are kept */
int tr_cl_build(const tr_cl_ctx *ctx, const char *const *files, int nfiles, const char *options, cl_program *out,
                tr_error *err)
{
    tr_cl_signals kept;
    tr_cl_signals_keep(&kept);
    int rc = build(ctx, files, nfiles, options, out, err);
    tr_cl_signals_restore(&kept);
    return rc;
}
