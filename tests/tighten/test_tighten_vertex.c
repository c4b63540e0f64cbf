/* tr_tighten in SP-FEM's vertex contact model (tighten.h, contacts
 * TR_CONTACTS_VERTEX; tighten/vertex_route.c), the library's side of
 * `tighten --contacts vertex` (tests/vertex_contacts.cmake has the command
 * line's):
 *  - the unknot: a wobbled 32-gon goes to the regular 32-gon with MinRad 1,
 *    the shortest closed 32-gon with MinRad >= 1, whose vertices K =
 *    ceil(pi / e) = 16 apart (e = 2 tan(pi/32)) lie 2 / cos(pi/32) > 2
 *    apart: ropelength 64 tan(pi/32) in the vertex model; the result's
 *    figures are the vertex oracle's, measured again here on its curve, the
 *    run is said solved and its knot type checked;
 *  - the cancel flag raised before the run: the start comes back, at the
 *    model's thickness 1, interrupted;
 *  - what the model refuses: an open rope, and the options of Rawdon's
 *    route (TR_EINVAL, nothing returned), which Rawdon's model takes. */
#include <math.h>
#include <signal.h>
#include <stdio.h>

#include "curve/generate.h"
#include "oracle/vertex_thickness.h"
#include "testlib.h"
#include "tighten/tighten.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define N 32

static void wobbled_circle(tr_curve *c)
{
    tr_error err;
    REQUIRE_OK(tr_make_circle(c, 1.6, N, &err));
    for (size_t i = 0; i < N; i++)
        c->x[3 * i + 2] += 0.08 * sin(6.0 * M_PI * (double)i / N);
}

static void vertex_options(tr_tighten_options *o)
{
    tr_tighten_options_default(o);
    o->contacts = TR_CONTACTS_VERTEX;
    o->time_limit = 60;
}

static void test_unknot(void)
{
    tr_curve c = {0};
    wobbled_circle(&c);
    tr_tighten_options o;
    vertex_options(&o);
    tr_tighten_result r;
    tr_error err;
    REQUIRE_OK(tr_tighten(&c, &o, &r, &err));
    tr_vertex_thickness vt;
    CHECK_OK(tr_vertex_thickness_measure(&r.curve, NULL, NULL, &vt, &err));
    double want = 2.0 * N * tan(M_PI / N);
    printf("vertex model, unknot n=%d: %.12f (closed form %.12f), K %zu, %ld steps, stop %s\n", N, vt.ropelength,
           want, vt.exclusion, r.steps, tr_stop_reason_name(r.stop));
    CHECK(r.vertex && r.vertex_why == NULL);
    CHECK(r.stop == TR_STOP_SOLVED && !r.interrupted);
    CHECK(vt.exclusion == 16 && r.vt.exclusion == 16);
    CHECK_NEAR(vt.thickness, 1.0, 1e-12);
    CHECK_NEAR(vt.ropelength, want, 1e-8 * want);
    CHECK_NEAR(r.ropelength, vt.ropelength, 1e-12 * want);
    CHECK(r.type_checked);
    CHECK(isnan(r.kkt_residual) && !r.certified);
    tr_tighten_result_free(&r);
    tr_curve_free(&c);
}

static void test_cancelled(void)
{
    tr_curve c = {0};
    wobbled_circle(&c);
    tr_tighten_options o;
    vertex_options(&o);
    volatile sig_atomic_t stop = 1;
    o.cancel = &stop;
    tr_tighten_result r;
    tr_error err;
    REQUIRE_OK(tr_tighten(&c, &o, &r, &err));
    tr_vertex_thickness start, got;
    CHECK_OK(tr_vertex_thickness_measure(&c, NULL, NULL, &start, &err));
    CHECK_OK(tr_vertex_thickness_measure(&r.curve, NULL, NULL, &got, &err));
    CHECK(r.interrupted && r.stop == TR_STOP_SIGNAL && r.steps == 0);
    CHECK_NEAR(got.thickness, 1.0, 1e-12);
    CHECK_NEAR(got.ropelength, start.ropelength, 1e-12 * start.ropelength);
    tr_tighten_result_free(&r);
    tr_curve_free(&c);
}

static void refused(const tr_curve *c, const tr_tighten_options *o, const char *what)
{
    tr_tighten_result r;
    tr_error err;
    int rc = tr_tighten(c, o, &r, &err);
    if (rc != TR_EINVAL || r.failed_at != TR_TIGHTEN_AT_START || r.curve.x)
        tr_test_report(__FILE__, __LINE__, "%s: not refused (rc %d)", what, rc);
    else
        printf("refused, %s: %s\n", what, err.msg);
    if (rc == TR_OK)
        tr_tighten_result_free(&r);
}

static void test_refused(void)
{
    tr_curve c = {0};
    wobbled_circle(&c);
    tr_tighten_options o;
    vertex_options(&o);
    o.refine_to = 64;
    refused(&c, &o, "--refine-to");
    CHECK(tr_tighten_vertex_conflict(&o) != NULL);
    vertex_options(&o);
    o.tries = 2;
    refused(&c, &o, "--tries");
    vertex_options(&o);
    o.kkt = 1;
    refused(&c, &o, "--kkt");
    vertex_options(&o);
    o.device = "reference";
    refused(&c, &o, "--device");
    /* the same options in Rawdon's model are no conflict */
    o.contacts = TR_CONTACTS_RAWDON;
    o.refine_to = 64;
    o.tries = 2;
    o.kkt = 1;
    CHECK(tr_tighten_vertex_conflict(&o) == NULL);
    vertex_options(&o);
    CHECK(tr_tighten_vertex_conflict(&o) == NULL);
    c.closed[0] = 0;
    refused(&c, &o, "an open rope");
    tr_curve_free(&c);
}

int main(void)
{
    test_unknot();
    test_cancelled();
    test_refused();
    return tr_test_finish("test_tighten_vertex");
}
