/* The library leaves its caller's signal handlers as they were
 * (backend/opencl/cl_signals.h): PoCL's LLVM, loaded when the devices are
 * listed and the kernels built, installs handlers of its own on SIGINT,
 * SIGTERM and SIGHUP, and before the devices' calls were bracketed a
 * caller's handlers were found replaced after them. Here the test's own
 * handlers are installed, the devices listed, an OpenCL backend opened (its
 * kernels built) and a step's forces evaluated, and each handler must still be the test's. Skipped (77) where
 * no OpenCL device is usable, after the listing's check. */
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "backend/backend.h"
#include "curve/generate.h"
#include "testlib.h"

static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
#define NSIG_KEPT (int)(sizeof sigs / sizeof sigs[0])

static void on_signal(int sig) { (void)sig; }

static void install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < NSIG_KEPT; i++)
        CHECK(sigaction(sigs[i], &sa, NULL) == 0);
}

static void check_ours(const char *after)
{
    for (int i = 0; i < NSIG_KEPT; i++) {
        struct sigaction now;
        CHECK(sigaction(sigs[i], NULL, &now) == 0);
        if ((now.sa_flags & SA_SIGINFO) || now.sa_handler != on_signal)
            tr_test_report(__FILE__, __LINE__, "after %s, signal %d's handler is not the caller's", after, sigs[i]);
    }
}

/* 1: checked on a device, 0: no usable OpenCL device */
static int run(void)
{
    install();
    tr_device_list l;
    tr_error err;
    CHECK_OK(tr_backend_list_devices(&l, &err));
    check_ours("listing the devices");
    tr_backend_device_list_free(&l);
    tr_curve c = {0};
    if (tr_make_torus(&c, 2, 3, 96, &err) != TR_OK) {
        tr_test_report(__FILE__, __LINE__, "tr_make_torus: %s", err.msg);
        return 1;
    }
    tr_backend b;
    if (tr_backend_open_device("opencl", &c, 0, &b, &err) != TR_OK) {
        printf("no usable OpenCL device (%s): the backend's check is skipped\n", err.msg);
        tr_curve_free(&c);
        return 0;
    }
    check_ours("opening an OpenCL backend");
    tr_measure m;
    CHECK_OK(b.ops->measure(b.state, &m, NULL, NULL, &err));
    check_ours("a measure on the device");
    tr_backend_close(&b);
    tr_curve_free(&c);
    return 1;
}

int main(void)
{
    if (!run() && !tr_test_failures)
        return TR_SKIP;
    return tr_test_finish("test_cl_signals");
}
