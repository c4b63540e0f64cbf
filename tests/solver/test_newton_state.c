/* Tests the Newton solver's resumable state (solver/newton.h
 * tr_newton_state, newton_state.c): a solve stopped part-way by its step
 * limit, its state written to a file and read back, and resumed, must end
 * where the solve that was not stopped ends (the oracle's ropelength of the
 * result, to 1e-9 relative) in the steps that solve had left (to a couple),
 * since the resumed run holds the same iterate, multipliers, penalty, strut
 * list and loop counters. The same comparison must fail for a resume that
 * drops the penalty (mu back to its first value) or the iterate (the start's
 * positions): the check is one that a lossy state does not pass. The curve:
 * the N = 1600 trefoil of bench/data spline-resampled to 400 vertices, a
 * tight start the solver settles in a few hundred steps (about a second);
 * and, without the lossy variants, a Hopf link and a clasp (several
 * components, open ropes, constrained ends).
 * Also: a state file cut short, or not one, is refused naming the file. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve_io.h"
#include "curve/generate.h"
#include "oracle/thickness.h"
#include "solver/newton.h"
#include "testlib.h"
#include "testlib_oracle.h"

/* the states a run hands over: each written to path, and how many */
typedef struct saved {
    const char *path;
    int calls, failed;
    int iter;
    long steps;
} saved;

static int save_state(void *user, const tr_newton_state *s, tr_error *err)
{
    saved *sv = user;
    sv->calls++;
    sv->iter = s->iter;
    sv->steps = s->steps;
    int rc = tr_newton_state_write(sv->path, s, err);
    if (rc)
        sv->failed++;
    return rc;
}

/* solves a copy of start (max_iter loop iterations, resumed from r if not
 * NULL, its state to sv if not NULL); the oracle's ropelength of the result */
static double solve(const tr_curve *start, int max_iter, const tr_newton_state *r, saved *sv, tr_newton_stats *st)
{
    tr_curve c = {0};
    tr_error err = {0};
    if (tr_curve_copy(&c, start, &err))
        return NAN;
    tr_newton_params p;
    tr_newton_params_default(&p);
    p.time_limit = 120; /* a guard only: the solves take about a second */
    p.max_iter = max_iter;
    p.resume = r;
    if (sv) {
        p.state = save_state;
        p.user = sv;
    }
    double rl = NAN;
    if (tr_newton(&c, &p, st, &err) == TR_OK && st->accepted)
        rl = tr_test_ropelength(&c);
    else
        printf("  solve: %s\n", err.msg[0] ? err.msg : (st->why_rejected ? st->why_rejected : "not accepted"));
    tr_curve_free(&c);
    return rl;
}

/* Does a resumed run end as the uninterrupted one: the same ropelength to
 * 1e-9 relative, in the steps it had left (to 2)? */
static int same_end(double rl, int steps, double rl_full, int steps_left)
{
    return fabs(rl - rl_full) <= 1e-9 * rl_full && abs(steps - steps_left) <= 2;
}

/* The same resume on other curves: a link (two components) and a clasp
 * (open ropes, ends held on planes: the gauge and the constraints), each
 * stopped at half the iterations of a solve of at most max_iter, resumed,
 * and compared with the solve that was not stopped (a result or none, its
 * ropelength, its steps and updates) */
static void check_resume(const char *name, const tr_curve *c, int max_iter)
{
    tr_newton_stats full, stop, res;
    double rl_full = solve(c, max_iter, NULL, NULL, &full);
    int half = (full.iters + full.outer) / 2;
    const char *path = "test_newton_state_case.state";
    saved sv = {.path = path};
    solve(c, half, NULL, &sv, &stop);
    CHECK(sv.calls == 1 && sv.failed == 0);
    tr_newton_state r = {0};
    tr_error err = {0};
    REQUIRE_OK(tr_newton_state_read(path, &r, &err));
    double rl_res = solve(c, max_iter, &r, NULL, &res);
    printf("%s: uninterrupted %.12f in %d steps (%s), stopped after %d, resumed %.12f in %d more\n", name, rl_full,
           full.iters, full.converged ? "converged" : full.settled ? "settled" : "stopped", stop.iters, rl_res,
           res.iters);
    CHECK((isnan(rl_full) && isnan(rl_res)) || fabs(rl_res - rl_full) <= 1e-9 * rl_full);
    CHECK(abs(stop.iters + res.iters - full.iters) <= 2 && res.outer == full.outer);
    tr_newton_state_free(&r);
    remove(path);
}

static void test_resume_link_and_clasp(void)
{
    tr_curve c = {0};
    tr_error err = {0};
    REQUIRE_OK(tr_make_hopf(&c, 40, &err));
    check_resume("Hopf link, 2 x 40", &c, 400);
    tr_curve_free(&c);
    REQUIRE_OK(tr_make_clasp(&c, 40, 5.0, &err));
    check_resume("clasp, 2 x 40", &c, 400);
    tr_curve_free(&c);
}

static void test_resume(void)
{
    tr_curve in = {0}, c = {0};
    tr_error err = {0};
    REQUIRE_OK(tr_curve_read(TR_SOURCE_DIR "/bench/data/trefoil_1600.vect", TR_FORMAT_AUTO, &in, &err));
    size_t n = 400;
    REQUIRE_OK(tr_resample_smooth(&in, &n, &c, &err));
    tr_curve_free(&in);

    tr_newton_stats full;
    double rl_full = tr_test_ropelength(&c);
    double rl_end = solve(&c, 5000, NULL, NULL, &full);
    printf("uninterrupted: %.12f -> %.12f, %d steps, %d updates, %s\n", rl_full, rl_end, full.iters, full.outer,
           full.converged ? "converged" : full.settled ? "settled" : "stopped");
    CHECK(full.converged || full.settled);
    rl_full = rl_end;
    /* stopped at half its loop iterations (a step or an update each) */
    int half = (full.iters + full.outer) / 2;

    const char *path = "test_newton_state.state";
    saved sv = {.path = path};
    tr_newton_stats stop;
    solve(&c, half, NULL, &sv, &stop);
    printf("stopped at iteration %d: %d steps, %d updates; state handed over %d times\n", half, stop.iters,
           stop.outer, sv.calls);
    /* handed over once, at the unfinished end (no state_every) */
    CHECK(sv.calls == 1 && sv.failed == 0);
    CHECK(sv.iter == half && sv.steps == stop.iters);
    CHECK(!stop.converged && !stop.settled);

    tr_newton_state r = {0};
    REQUIRE_OK(tr_newton_state_read(path, &r, &err));
    CHECK(r.nv == c.nv && r.ncomp == 1 && r.iter == half && r.outer == stop.outer);
    tr_newton_stats res;
    double rl_res = solve(&c, 5000, &r, NULL, &res);
    int left = full.iters - stop.iters;
    printf("resumed: -> %.12f (uninterrupted %.12f, %.1e relative), %d steps (%d left), %d updates in all\n", rl_res,
           rl_full, fabs(rl_res - rl_full) / rl_full, res.iters, left, res.outer);
    CHECK(same_end(rl_res, res.iters, rl_full, left));
    CHECK(res.outer == full.outer);
    CHECK(res.converged == full.converged && res.settled == full.settled);

    /* stopped twice: a resumed run's own state resumes as well (max_iter
     * bounds the iterations from the first run's start) */
    int three_quarters = (3 * (full.iters + full.outer)) / 4;
    const char *path2 = "test_newton_state_2.state";
    saved sv2 = {.path = path2};
    tr_newton_stats stop2, res2;
    solve(&c, three_quarters, &r, &sv2, &stop2);
    tr_newton_state r2 = {0};
    REQUIRE_OK(tr_newton_state_read(path2, &r2, &err));
    CHECK(sv2.calls == 1 && r2.iter == three_quarters && r2.steps == stop.iters + stop2.iters);
    double rl_res2 = solve(&c, 5000, &r2, NULL, &res2);
    printf("stopped again at iteration %d (%d steps), resumed: -> %.12f, %d steps (%d left)\n", three_quarters,
           stop2.iters, rl_res2, res2.iters, left - stop2.iters);
    CHECK(same_end(rl_res2, res2.iters, rl_full, left - stop2.iters));
    tr_newton_state_free(&r2);
    remove(path2);

    /* a resume that loses the penalty: mu back at its first value */
    tr_newton_params defp;
    tr_newton_params_default(&defp);
    double l0min = r.l0[0], mu_kept = r.mu;
    r.mu = defp.mu0 / l0min;
    r.band = 1.0;
    tr_newton_stats nomu;
    /* (the broken resumes get twice the uninterrupted run's iterations:
     * one that has not ended by then does not end as it did) */
    int most = 2 * (full.iters + full.outer);
    double rl_nomu = solve(&c, most, &r, NULL, &nomu);
    printf("resumed without mu (%.1e instead of %.1e): -> %.12f (%.1e relative), %d steps\n", r.mu * l0min,
           mu_kept * l0min, rl_nomu, fabs(rl_nomu - rl_full) / rl_full, nomu.iters);
    CHECK(!same_end(rl_nomu, nomu.iters, rl_full, left));
    tr_newton_state_free(&r);

    /* a resume that loses the iterate: the start's positions, mean edge */
    REQUIRE_OK(tr_newton_state_read(path, &r, &err));
    tr_thickness th;
    REQUIRE_OK(tr_thickness_measure(&c, NULL, &th, NULL, &err));
    for (size_t i = 0; i < 3 * c.nv; i++)
        r.y[i] = c.x[i] / th.thickness;
    r.y[3 * c.nv] = th.length / th.thickness / (double)c.nv;
    tr_newton_stats noy;
    double rl_noy = solve(&c, most, &r, NULL, &noy);
    printf("resumed from the start's positions: -> %.12f (%.1e relative), %d steps\n", rl_noy,
           fabs(rl_noy - rl_full) / rl_full, noy.iters);
    CHECK(!same_end(rl_noy, noy.iters, rl_full, left));
    tr_newton_state_free(&r);

    /* a state of another curve's shape is refused */
    tr_curve other = {0};
    size_t m = 300;
    REQUIRE_OK(tr_resample_smooth(&c, &m, &other, &err));
    REQUIRE_OK(tr_newton_state_read(path, &r, &err));
    tr_newton_params p;
    tr_newton_params_default(&p);
    p.resume = &r;
    tr_newton_stats st;
    CHECK(tr_newton(&other, &p, &st, &err) == TR_EINVAL);
    tr_newton_state_free(&r);
    tr_curve_free(&other);
    tr_curve_free(&c);
}

/* a state file cut short, or not one, is a parse error naming the file */
static void test_bad_files(void)
{
    const char *path = "test_newton_state.state";
    const char *cut = "test_newton_state_cut.state";
    FILE *f = fopen(path, "rb");
    if (!f) {
        CHECK(f != NULL);
        return;
    }
    static unsigned char data[1 << 20];
    size_t n = fread(data, 1, sizeof data, f);
    fclose(f);
    CHECK(n > 1000 && n < sizeof data);
    tr_newton_state r = {0};
    tr_error err = {0};
    size_t cuts[] = {10, 60, n / 2, n - 1};
    for (size_t k = 0; k < sizeof cuts / sizeof *cuts; k++) {
        FILE *g = fopen(cut, "wb");
        if (!g) {
            CHECK(g != NULL);
            return;
        }
        fwrite(data, 1, cuts[k], g);
        fclose(g);
        int rc = tr_newton_state_read(cut, &r, &err);
        printf("cut at byte %zu: %s\n", cuts[k], err.msg);
        CHECK(rc == TR_EPARSE);
        CHECK(strstr(err.msg, cut) != NULL);
        CHECK(r.y == NULL);
    }
    /* one byte more than the state is no state either */
    FILE *g = fopen(cut, "wb");
    if (g) {
        fwrite(data, 1, n, g);
        fputc(0, g);
        fclose(g);
        CHECK(tr_newton_state_read(cut, &r, &err) == TR_EPARSE);
        printf("a byte over: %s\n", err.msg);
    }
    CHECK(tr_newton_state_read(TR_SOURCE_DIR "/bench/data/trefoil_1600.vect", &r, &err) == TR_EPARSE);
    printf("a curve: %s\n", err.msg);
    remove(cut);
}

int main(void)
{
    test_resume();
    test_resume_link_and_clasp();
    test_bad_files();
    return tr_test_finish("test_newton_state");
}
