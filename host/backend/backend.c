/* This file contains the backend registry: which backends exist, how a device
 * spec picks one, and the listing of the devices they can run on. */
#include "backend/backend.h"
#include "backend/opencl/backend_opencl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/device_spec.h"

typedef struct tr_backend_entry {
    const char *name;
    int (*open)(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err);
    /* an accelerated backend's profiling open, device listing and spec check */
    int (*open_profiled)(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err);
    int (*list_devices)(tr_device_list *out, tr_error *err);
    int (*check_spec)(const char *spec, tr_error *err);
} tr_backend_entry;

/* Accelerated backends first, in the order "auto" tries them; the serial
 * reference last. Adding a backend = one line here. */
static const tr_backend_entry registry[] = {
    {"opencl", tr_backend_opencl_open, tr_backend_opencl_open_profiled,
     tr_backend_opencl_list_devices, tr_backend_opencl_check_spec},
    {"reference", tr_backend_reference_open, NULL, NULL, NULL},
};

#define N_REGISTRY (sizeof registry / sizeof registry[0])

int tr_backend_open(const char *spec, const tr_curve *c, tr_backend *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (!spec || !*spec)
        spec = getenv("TIGHTROPE_DEVICE");
    if (!spec || !*spec)
        spec = "auto";
    if (tr_device_spec_is_reference(spec))
        return tr_backend_reference_open("reference", c, out, err);
    if (!strcmp(spec, "auto")) {
        char why[512] = "";
        for (size_t i = 0; i < N_REGISTRY; i++) {
            if (registry[i].open == tr_backend_reference_open)
                continue;
            tr_error e2;
            int rc = registry[i].open(spec, c, out, &e2);
            if (rc == TR_OK)
                return TR_OK;
            if (rc != TR_EUNSUPPORTED || !why[0])
                snprintf(why, sizeof why, "%.40s: %.400s", registry[i].name, e2.msg);
            memset(out, 0, sizeof *out);
        }
        int rc = tr_backend_reference_open("reference", c, out, err);
        if (rc == TR_OK && why[0])
            snprintf(out->warning, sizeof out->warning, "using the serial reference (%.200s)", why);
        return rc;
    }
    /* A backend that knows the device but cannot use it (no fp64, no
     * usable device) says why; that reason, not "unknown", is the error. */
    char why[512] = "";
    for (size_t i = 0; i < N_REGISTRY; i++) {
        if (registry[i].open == tr_backend_reference_open)
            continue;
        tr_error e2 = {{0}};
        int rc = registry[i].open(spec, c, out, &e2);
        if (rc != TR_EUNSUPPORTED) {
            if (rc != TR_OK && err)
                *err = e2;
            return rc;
        }
        snprintf(why, sizeof why, "%.500s", e2.msg);
        memset(out, 0, sizeof *out);
    }
    if (why[0])
        return tr_fail(err, TR_EUNSUPPORTED, "device '%.60s': %s", spec, why);
    return tr_fail(err, TR_EINVAL, "unknown device '%s' (try 'reference' or 'auto')", spec);
}

void tr_backend_close(tr_backend *b)
{
    if (!b)
        return;
    if (b->ops && b->ops->destroy)
        b->ops->destroy(b->state);
    memset(b, 0, sizeof *b);
}

int tr_backend_open_device(const char *spec, const tr_curve *c, int profiling, tr_backend *out,
                           tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (tr_device_spec_is_reference(spec))
        return tr_backend_reference_open("reference", c, out, err);
    int rc = tr_fail(err, TR_EINVAL, "unknown device '%s'", spec ? spec : "");
    for (size_t i = 0; i < N_REGISTRY; i++) {
        if (registry[i].open == tr_backend_reference_open)
            continue;
        rc = (profiling ? registry[i].open_profiled : registry[i].open)(spec, c, out, err);
        if (rc != TR_EUNSUPPORTED)
            return rc;
        memset(out, 0, sizeof *out);
    }
    return rc;
}

void tr_backend_describe(const tr_backend *b, char *out, size_t size)
{
    if (size)
        out[0] = '\0';
    if (b && b->ops && b->ops->describe)
        b->ops->describe(b->state, out, size);
}

int tr_backend_profile(const tr_backend *b, tr_kernel_time *out, int max)
{
    return b && b->ops && b->ops->profile ? b->ops->profile(b->state, out, max) : 0;
}

int tr_backend_list_devices(tr_device_list *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < N_REGISTRY; i++)
        if (registry[i].list_devices)
            return registry[i].list_devices(out, err); /* one accelerated backend today */
    return tr_fail(err, TR_EUNSUPPORTED, "no backend lists devices");
}

void tr_backend_device_list_free(tr_device_list *l)
{
    if (!l)
        return;
    free(l->dev);
    memset(l, 0, sizeof *l);
}

int tr_backend_check_spec(const char *spec, tr_error *err)
{
    if (tr_device_spec_is_reference(spec))
        return TR_OK;
    for (size_t i = 0; i < N_REGISTRY; i++)
        if (registry[i].check_spec)
            return registry[i].check_spec(spec, err); /* one accelerated backend today */
    return tr_fail(err, TR_EINVAL, "unknown device '%s'", spec ? spec : "");
}
