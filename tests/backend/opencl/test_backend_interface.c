/* This file contains the test of the backend interface's operations for the
 * CLI (backend.h): opening exactly the device asked for, describe, profile,
 * the device listing and the spec check, through the registry only. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/backend.h"
#include "curve/generate.h"
#include "testlib.h"

static void test_reference(const tr_curve *c)
{
    tr_backend b;
    tr_error err;
    REQUIRE_OK(tr_backend_open_device("serial", c, 1, &b, &err));
    CHECK(b.ops->serial == 1);
    char how[64] = "x";
    tr_backend_describe(&b, how, sizeof how);
    CHECK(how[0] == '\0');
    tr_measure m;
    CHECK_OK(b.ops->measure(b.state, &m, NULL, NULL, &err));
    tr_kernel_time k[4];
    CHECK(tr_backend_profile(&b, k, 4) == 0); /* the reference does not profile */
    tr_backend_close(&b);
}

static void test_opencl(const tr_curve *c)
{
    tr_backend b;
    tr_error err;
    /* never a fallback: an OpenCL spec opens OpenCL or fails */
    int rc = tr_backend_open_device("opencl", c, 1, &b, &err);
    if (rc != TR_OK) {
        printf("no usable OpenCL device (%s): the OpenCL half is skipped\n", err.msg);
        return;
    }
    CHECK(b.ops->serial == 0);
    CHECK(!strcmp(b.ops->name, "opencl"));
    char how[64];
    tr_backend_describe(&b, how, sizeof how);
    CHECK(!strncmp(how, "edge block ", 11));
    tr_kernel_time k[TR_BACKEND_PROFILE_MAX];
    int n0 = tr_backend_profile(&b, k, TR_BACKEND_PROFILE_MAX);
    tr_measure m;
    CHECK_OK(b.ops->measure(b.state, &m, NULL, NULL, &err));
    int n1 = tr_backend_profile(&b, k, TR_BACKEND_PROFILE_MAX);
    CHECK(n1 > 0 && n1 >= n0); /* measure launched kernels, and they were timed */
    long launches = 0;
    for (int i = 0; i < n1; i++) {
        CHECK(k[i].kernel[0] != '\0' && k[i].seconds >= 0.0);
        launches += k[i].launches;
    }
    CHECK(launches > 0);
    CHECK(tr_backend_profile(&b, k, 1) == 1); /* at most max */
    tr_backend_close(&b);
    /* unprofiled: no times */
    REQUIRE_OK(tr_backend_open_device("opencl", c, 0, &b, &err));
    CHECK_OK(b.ops->measure(b.state, &m, NULL, NULL, &err));
    CHECK(tr_backend_profile(&b, k, TR_BACKEND_PROFILE_MAX) == 0);
    tr_backend_close(&b);
}

static void test_listing(void)
{
    tr_device_list l;
    tr_error err;
    REQUIRE_OK(tr_backend_list_devices(&l, &err));
    const char *env = getenv("TIGHTROPE_DEVICE");
    CHECK(!strcmp(l.default_spec, env && *env ? env : "auto"));
    CHECK(l.n > 0 || l.none_reason[0] != '\0');
    for (int i = 0; i < l.n; i++) {
        int p, d;
        char tail;
        CHECK(sscanf(l.dev[i].id, "%d:%d%c", &p, &d, &tail) == 2);
        CHECK(l.dev[i].usable == (l.dev[i].reason[0] == '\0'));
        CHECK(l.dev[i].type != NULL);
        /* a usable device's id is a spec that checks */
        if (l.dev[i].usable)
            CHECK(tr_backend_check_spec(l.dev[i].id, &err) == TR_OK);
    }
    if (l.picked)
        CHECK(!strcmp(l.selected, "reference") || strchr(l.selected, ':') != NULL);
    tr_backend_device_list_free(&l);
    CHECK(l.dev == NULL && l.n == 0);
    CHECK(tr_backend_check_spec("reference", &err) == TR_OK);
    CHECK(tr_backend_check_spec("cpu-reference", &err) == TR_OK);
    CHECK(tr_backend_check_spec("no-such-device-anywhere", &err) == TR_EINVAL);
}

int main(void)
{
    tr_curve c;
    tr_error err;
    if (tr_make_circle(&c, 3.0, 64, &err) != TR_OK) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    test_reference(&c);
    test_opencl(&c);
    test_listing();
    tr_curve_free(&c);
    return tr_test_finish("test_backend_interface");
}
