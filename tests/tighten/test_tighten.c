/* The tightening layer as a call (tighten/tighten.h): tr_tighten on the
 * (2,3) torus knot at N = 100 under a time limit returns a rope (the
 * independent thickness oracle finds it at thickness 1: struts >= 2,
 * MinRad >= 1) whose ropelength lies between Denne, Diao and Sullivan's
 * lower bound for every nontrivial knot (15.66, "Quadrisecants give new
 * lower bounds for the ropelength of a knot", Geom. Topol. 10 (2006), in
 * the same convention: length over the tube's radius) and the start's;
 * the progress callback is called; the cancel flag stops a run with no
 * time limit within a second of being raised, the best state kept; bad
 * calls fail with their stage. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "curve/generate.h"
#include "oracle/thickness.h"
#include "testlib.h"
#include "tighten/tighten.h"
#include "util/clock.h"

/* Denne-Diao-Sullivan (2006): every nontrivial knot */
#define KNOT_ROPELENGTH_LOWER_BOUND 15.66

typedef struct watch {
    int calls;
    size_t last_n;
    double last_ropelength;
    /* cancel: raise *flag once the run's elapsed time passes raise_after
     * and its ropelength is below raise_below (the settled start can be
     * longer than the start: the best state kept is then shorter) */
    volatile sig_atomic_t *flag;
    double raise_after, raise_below, raised_at;
} watch;

static void on_progress(const tr_tighten_progress *p, void *user)
{
    watch *w = user;
    w->calls++;
    w->last_n = p->n;
    w->last_ropelength = p->ropelength;
    if (w->flag && !*w->flag && p->elapsed >= w->raise_after && p->ropelength < w->raise_below) {
        *w->flag = SIGINT;
        w->raised_at = tr_clock_seconds();
    }
}

static double oracle_ropelength(const tr_curve *c, tr_thickness *t)
{
    tr_error err;
    CHECK_OK(tr_thickness_measure(c, NULL, t, NULL, &err));
    return t->ropelength;
}

/* The result is a rope at thickness 1, measured afresh, and shorter than
 * the start, above the bound. */
static void check_rope(const tr_tighten_result *r, double start_rl)
{
    tr_thickness t;
    double rl = oracle_ropelength(&r->curve, &t);
    CHECK(r->curve.nv == 100 && r->curve.ncomp == 1);
    CHECK_NEAR(t.thickness, 1.0, 1e-9);
    CHECK(t.dcsd >= 2.0 * (1.0 - 1e-9));
    CHECK(t.minrad >= 1.0 - 1e-9);
    CHECK_NEAR(rl, r->ropelength, 1e-9 * rl);
    CHECK(rl > KNOT_ROPELENGTH_LOWER_BOUND);
    CHECK(rl < start_rl);
}

static void timed_run(const tr_curve *start, double start_rl)
{
    tr_tighten_options opt;
    tr_tighten_options_default(&opt);
    watch w = {0};
    opt.device = "reference";
    opt.time_limit = 6.0;
    opt.progress = on_progress;
    opt.progress_every = 0.05;
    opt.user = &w;
    tr_tighten_result r;
    tr_error err;
    double t0 = tr_clock_seconds();
    CHECK_OK(tr_tighten(start, &opt, &r, &err));
    double took = tr_clock_seconds() - t0;
    CHECK(took <= 6.0 + 1.0);
    check_rope(&r, start_rl);
    CHECK(w.calls > 0);
    CHECK(w.last_n == 100);
    CHECK(!r.interrupted && r.stop != TR_STOP_SIGNAL);
    CHECK(r.steps > 0);
    CHECK(r.tries == 1 && r.road == 1 && r.seed == 1);
    /* the certificate, at N = 100 by default */
    CHECK(r.certified && isfinite(r.kkt_residual) && r.kkt_residual >= 0);
    /* the (2,3) torus knot stays the trefoil (knot_type.h): determinant 3 */
    CHECK(r.type_checked && strstr(r.type_line, "determinant 3") != NULL);
    printf("tr_tighten: trefoil N 100 in %.1f s: ropelength %.6f (start %.3f), %ld steps, stop %s, kkt %.2e, "
           "%d progress calls\n", took, r.ropelength, start_rl, r.steps, tr_stop_reason_name(r.stop), r.kkt_residual,
           w.calls);
    tr_tighten_result_free(&r);
}

static void cancelled_run(const tr_curve *start, double start_rl)
{
    tr_tighten_options opt;
    tr_tighten_options_default(&opt);
    volatile sig_atomic_t flag = 0;
    watch w = {.flag = &flag, .raise_after = 0.5, .raise_below = start_rl - 0.1};
    opt.device = "reference";
    /* no limit but the flag: only a fallback, far past the second the flag has */
    opt.time_limit = 30.0;
    opt.cancel = &flag;
    opt.progress = on_progress;
    opt.progress_every = 0.05;
    opt.user = &w;
    tr_tighten_result r;
    tr_error err;
    CHECK_OK(tr_tighten(start, &opt, &r, &err));
    double after = tr_clock_seconds() - w.raised_at;
    CHECK(flag != 0);
    CHECK(after < 1.0);
    CHECK(r.interrupted && r.stop == TR_STOP_SIGNAL);
    /* the best state is kept: a rope, shorter than the start; no certificate */
    check_rope(&r, start_rl);
    CHECK(!r.certified && isnan(r.kkt_residual));
    printf("tr_tighten: cancelled %.3f s after the flag, ropelength %.6f\n", after, r.ropelength);
    tr_tighten_result_free(&r);
}

static void refused(void)
{
    tr_tighten_options opt;
    tr_tighten_options_default(&opt);
    tr_tighten_result r;
    tr_error err;
    CHECK(tr_tighten(NULL, &opt, &r, &err) == TR_EINVAL);
    CHECK(r.failed_at == TR_TIGHTEN_AT_START && r.curve.nv == 0);
    /* an open rope whose ends are free would come out untied */
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 100, &err));
    c.closed[0] = 0;
    opt.device = "reference";
    CHECK(tr_tighten(&c, &opt, &r, &err) == TR_EGEOMETRY);
    CHECK(r.failed_at == TR_TIGHTEN_AT_START);
    CHECK(strstr(err.msg, "free") != NULL);
    tr_curve_free(&c);
    /* a resumed run with no checkpoint there */
    opt.resume = "no-such-checkpoint.ckpt";
    CHECK(tr_tighten(NULL, &opt, &r, &err) != TR_OK);
    CHECK(r.failed_at == TR_TIGHTEN_AT_RESUME || r.failed_at == TR_TIGHTEN_AT_START);
}

int main(void)
{
    tr_curve c;
    tr_error err;
    if (tr_make_torus(&c, 2, 3, 100, &err) != TR_OK) {
        fprintf(stderr, "test_tighten: %s\n", err.msg);
        return 1;
    }
    tr_thickness t;
    double start_rl = oracle_ropelength(&c, &t);
    CHECK(start_rl > KNOT_ROPELENGTH_LOWER_BOUND);
    timed_run(&c, start_rl);
    cancelled_run(&c, start_rl);
    refused();
    tr_curve_free(&c);
    return tr_test_finish("test_tighten");
}
