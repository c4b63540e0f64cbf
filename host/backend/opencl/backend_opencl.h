/* The OpenCL backend (backend.h): state in device memory, one program with
 * every kernel, the step loop's per-step read-back limited to a few scalars. */
#ifndef TR_BACKEND_OPENCL_H
#define TR_BACKEND_OPENCL_H

#include "backend/backend.h"

/* Registry entry: spec "opencl", "auto", "P:D" or a device-name part; returns
 * TR_EUNSUPPORTED for specs that are not OpenCL's and when "auto" finds no
 * usable device (the registry then falls back to the reference). */
int tr_backend_opencl_open(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err);

/* Same, with OpenCL profiling events on every kernel launch (for the bench;
 * it synchronises after each launch, so time whole steps without it). */
int tr_backend_opencl_open_profiled(const char *spec, const tr_curve *c, tr_backend *out,
                                    tr_error *err);

typedef struct tr_kernel_time {
    char kernel[48]; /* kernel function name */
    long launches;
    double seconds;     /* summed device execution time (profiling events) */
} tr_kernel_time;

/* Per-kernel totals since open (profiled backends only; else returns 0).
 * Returns the number of entries written (at most max). */
int tr_backend_opencl_kernel_times(const tr_backend *b, tr_kernel_time *out, int max);

/* The edge-block solver an OpenCL backend uses: "thomas", "twisted" (CPU
 * devices' default), "pcr-group" or "pcr-levels" (see TIGHTROPE_CL_TRIDIAG in
 * the README); NULL for other backends. */
const char *tr_backend_opencl_tridiag(const tr_backend *b);

#endif
