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

/* The edge-block solver an OpenCL backend uses: "thomas", "twisted" (CPU
 * devices' default), "pcr-group" or "pcr-levels" (see TIGHTROPE_CL_TRIDIAG in
 * the README); NULL for other backends. (describe says it as "edge block
 * NAME"; profile gives the per-kernel times.) */
const char *tr_backend_opencl_tridiag(const tr_backend *b);

/* The device listing of backend.h (tr_backend_list_devices) and its spec
 * check, for the OpenCL devices. */
int tr_backend_opencl_list_devices(tr_device_list *out, tr_error *err);
int tr_backend_opencl_check_spec(const char *spec, tr_error *err);

#endif
