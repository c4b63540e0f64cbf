/* Tests the second-order solver (solver/newton.h) with its strut rows
 * through a backend (tr_newton_params.backend, backend.h strut_rows): with
 * the serial reference it must take the host path's steps to the bit (the
 * same file), with the OpenCL device (PoCL where there is no GPU) the same
 * answer to ~1e-9. Cases: the wobbled 32-gon unknot and the 2 x 40-gon
 * Hopf link of test_newton.c, and the N = 2400 tight trefoil subsampled
 * to 600 (thousands of listed pairs, hundreds active). Without an OpenCL
 * device the device half is skipped. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "backend/backend.h"
#include "curve/curve_io.h"
#include "curve/generate.h"
#include "solver/newton.h"
#include "testlib.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Solves a copy of c with the rows on be (NULL: the host path). */
static int solve(const tr_curve *c, const tr_backend *be, tr_curve *out, tr_newton_stats *st)
{
    tr_error err = {0};
    if (tr_curve_copy(out, c, &err))
        return 1;
    tr_newton_params p;
    tr_newton_params_default(&p);
    p.time_limit = 120;
    p.backend = be;
    int rc = tr_newton(out, &p, st, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    return rc;
}

static void run_case(const char *name, const tr_curve *c, const tr_backend *ref, const tr_backend *cl)
{
    tr_curve h = {0}, r = {0}, d = {0};
    tr_newton_stats sh, sr, sd;
    REQUIRE_OK(solve(c, NULL, &h, &sh));
    REQUIRE_OK(solve(c, ref, &r, &sr));
    CHECK(sh.accepted && sr.accepted);
    /* the reference: the same steps, the same curve to the bit */
    CHECK(sr.iters == sh.iters && sr.outer == sh.outer && sr.factorizations == sh.factorizations);
    CHECK(sr.ropelength_after == sh.ropelength_after);
    CHECK(!memcmp(r.x, h.x, 3 * c->nv * sizeof *h.x));
    printf("%s: host %.12f (%d steps), reference backend %.12f (%d steps)", name, sh.ropelength_after, sh.iters,
           sr.ropelength_after, sr.iters);
    if (cl) {
        REQUIRE_OK(solve(c, cl, &d, &sd));
        printf(", OpenCL %.12f (%d steps)", sd.ropelength_after, sd.iters);
        CHECK(sd.accepted);
        CHECK_NEAR(sd.ropelength_after, sh.ropelength_after, 1e-9 * sh.ropelength_after);
        CHECK(sd.t_rows > 0.0);
        tr_curve_free(&d);
    }
    printf("\n");
    tr_curve_free(&h);
    tr_curve_free(&r);
}

int main(void)
{
    tr_error err = {0};
    tr_curve cs[3] = {{0}};
    const char *names[3] = {"unknot n=32", "hopf n=40", "trefoil n=600 (tight)"};
    if (tr_make_circle(&cs[0], 1.6, 32, &err) || tr_make_hopf(&cs[1], 40, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    for (size_t i = 0; i < 32; i++)
        cs[0].x[3 * i + 2] += 0.05 * 1.6 * sin(3.0 * 2.0 * M_PI * (double)i / 32.0);
    char path[1024];
    snprintf(path, sizeof path, "%s/bench/data/trefoil_2400.vect", TR_SOURCE_DIR);
    tr_curve big = {0};
    size_t n = 600;
    if (tr_curve_read(path, TR_FORMAT_AUTO, &big, &err) || tr_resample_smooth(&big, &n, &cs[2], &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    tr_curve_free(&big);
    tr_backend ref, cl;
    if (tr_backend_open_device("reference", &cs[0], 0, &ref, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    int have_cl = tr_backend_open_device("opencl", &cs[0], 0, &cl, &err) == TR_OK;
    if (!have_cl)
        printf("no usable OpenCL device (%s): the device runs are skipped\n", err.msg);
    for (int i = 0; i < 3; i++) {
        run_case(names[i], &cs[i], &ref, have_cl ? &cl : NULL);
        tr_curve_free(&cs[i]);
    }
    tr_backend_close(&ref);
    if (have_cl)
        tr_backend_close(&cl);
    return tr_test_finish("test_newton_device");
}
