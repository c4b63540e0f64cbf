/* The polish stage on a small trefoil tightened briefly by the engine: the
 * oracle's ropelength strictly decreases; the result has equal edges, MinRad
 * >= 1 and dcsd >= 2 (it is rescaled to thickness 1); no strand passed
 * another: every accepted iterate, seen by an observer, keeps the oracle's
 * shortest doubly-critical distance far above twice the largest vertex
 * motion between iterates (so no pair of segments can have met on the
 * straight-line path between them, the engine's argument) and MinRad near 1.
 * A Hopf link keeps its Gauss linking number; a clasp (constrained ends)
 * is polished in place with its ends on their planes, and skipped (left
 * unchanged) below thickness 1, where it could only be rescaled. In the engine's run loop with refinement,
 * polish (every level) ends shorter than the same run without it. From
 * KnotPlot's loose 4_1 at N = 100, polish (restarted while a run still
 * shortens the rope) ends converged: one more polish does not shorten it by
 * more than 1e-7; a single augmented-Lagrangian run creeps at a stiff
 * penalty and stops where the next run still gains 3e-4. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine/engine.h"
#include "curve/generate.h"
#include "engine/polish.h"
#include "curve/curve_io.h"
#include "testlib.h"
#include "oracle/thickness.h"
#include "util/vec3.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct watch {
    tr_curve c;  /* topology; x holds the previous iterate */
    long iterates;
    double worst_dcsd, worst_minrad, worst_move;
    double worst_ratio; /* min over iterates of dcsd / (2 max move) */
} watch;

static void observe(void *user, const double *x, size_t nv)
{
    watch *w = user;
    double m = 0.0;
    for (size_t i = 0; i < nv; i++)
        m = fmax(m, sqrt(v3_dist2(x + 3 * i, w->c.x + 3 * i)));
    memcpy(w->c.x, x, 3 * nv * sizeof *x);
    tr_thickness t;
    tr_error err;
    CHECK_OK(tr_thickness_measure(&w->c, NULL, &t, NULL, &err));
    w->iterates++;
    w->worst_dcsd = fmin(w->worst_dcsd, t.dcsd);
    w->worst_minrad = fmin(w->worst_minrad, t.minrad);
    w->worst_move = fmax(w->worst_move, m);
    if (m > 0)
        w->worst_ratio = fmin(w->worst_ratio, t.dcsd / (2.0 * m));
}

static double edge_dev(const tr_curve *c)
{
    double worst = 0.0;
    for (int k = 0; k < c->ncomp; k++) {
        size_t s = c->start[k], n = tr_comp_nv(c, k), ne = tr_comp_ne(c, k);
        double mean = tr_comp_length(c, k) / (double)ne;
        for (size_t l = 0; l < ne; l++)
            worst = fmax(worst, fabs(sqrt(v3_dist2(c->x + 3 * (s + l), c->x + 3 * (s + (l + 1) % n))) - mean) / mean);
    }
    return worst;
}

/* A curve tightened by the engine for a bounded number of steps. */
static void engine_curve(const tr_curve *start, int steps, tr_curve *out)
{
    tr_error err;
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, start, "reference", NULL, &err));
    for (int k = 0; k < steps; k++) {
        int acc;
        CHECK_OK(tr_engine_step(e, &acc, &err));
    }
    CHECK_OK(tr_engine_get_curve(e, out, &err));
    tr_engine_destroy(e);
}

/* polishes c (observed) and checks the guards and the result */
static void polish_checked(tr_curve *c, const char *name, double *before, double *after)
{
    tr_error err;
    tr_thickness t0, t1;
    CHECK_OK(tr_thickness_measure(c, NULL, &t0, NULL, &err));
    watch w = {.worst_dcsd = INFINITY, .worst_minrad = INFINITY, .worst_ratio = INFINITY};
    CHECK_OK(tr_curve_copy(&w.c, c, &err));
    for (size_t i = 0; i < 3 * c->nv; i++) /* polish works at thickness 1 */
        w.c.x[i] /= t0.thickness;
    tr_polish_params pp;
    tr_polish_params_default(&pp);
    pp.time_limit = 8.0;
    pp.observe = observe;
    pp.user = &w;
    tr_polish_stats st;
    CHECK_OK(tr_polish(c, &pp, &st, &err));
    CHECK_OK(tr_thickness_measure(c, NULL, &t1, NULL, &err));
    printf("%s: ropelength %.6f -> %.6f (oracle %.6f), %d rounds, %d iterations, %d evaluations, %d rebuilds, "
           "%.2f s, violation %.2g, edge deviation %.2g\n",
           name, t0.ropelength, st.ropelength_after, t1.ropelength, st.outer, st.inner_iters, st.evals, st.rebuilds,
           st.seconds, st.max_viol, edge_dev(c));
    printf("  %ld iterates: worst dcsd %.6f, MinRad %.6f, largest vertex step %.4f, dcsd / (2 step) >= %.1f\n",
           w.iterates, w.worst_dcsd, w.worst_minrad, w.worst_move, w.worst_ratio);
    CHECK(st.accepted);
    CHECK(!st.skipped);
    CHECK(t1.ropelength < t0.ropelength - 1e-3);
    CHECK_NEAR(t1.ropelength, st.ropelength_after, 1e-12 * t1.ropelength);
    CHECK(t1.thickness >= 1.0 - 1e-12);
    CHECK(t1.minrad >= 1.0 - 1e-12);
    CHECK(t1.dcsd >= 2.0 - 1e-12);
    CHECK(edge_dev(c) < 1e-4);
    CHECK(w.iterates > 10);
    CHECK(w.worst_move <= pp.max_move * (1.0 + 1e-9));
    CHECK(w.worst_dcsd >= 1.9);
    CHECK(w.worst_ratio > 10.0);
    CHECK(w.worst_minrad >= 0.9);
    *before = t0.ropelength;
    *after = t1.ropelength;
    tr_curve_free(&w.c);
}

/* the TightKnot table's ropelength of `knot` (an independent code's: octrope's
 * rows for the two knots kept in tests/data/tightknot) */
static double table_ropelength(const char *knot)
{
    char path[4096], name[64];
    FILE *f = fopen(tr_source_path(path, sizeof path, "tests/data/tightknot/octrope.tsv"), "r");
    CHECK(f != NULL);
    double rl = NAN;
    char line[512];
    while (f && fgets(line, sizeof line, f)) {
        unsigned n;
        double v;
        if (sscanf(line, "%63s %u %lf", name, &n, &v) == 3 && !strcmp(name, knot))
            rl = v;
    }
    if (f)
        fclose(f);
    return rl;
}

/* KnotPlot's 4_1, resampled to N = 100, polished from its loose start */
static void polish_loose_figure_eight(void)
{
    tr_error err;
    char path[4096];
    tr_curve k, c;
    REQUIRE_OK(tr_curve_read(tr_source_path(path, sizeof path, "tests/data/knotplot/4.1.vect"), TR_FORMAT_AUTO, &k, &err));
    size_t n = 100;
    CHECK_OK(tr_resample(&k, &n, &c, &err));
    tr_thickness t0, t1;
    CHECK_OK(tr_thickness_measure(&c, NULL, &t0, NULL, &err));
    tr_curve once, tgt;
    CHECK_OK(tr_curve_copy(&once, &c, &err));
    CHECK_OK(tr_curve_copy(&tgt, &c, &err));
    tr_polish_params pp;
    tr_polish_params_default(&pp);
    tr_polish_stats st, st1, again;
    CHECK_OK(tr_polish(&c, &pp, &st, &err));
    CHECK_OK(tr_thickness_measure(&c, NULL, &t1, NULL, &err));
    pp.max_restarts = 1;
    CHECK_OK(tr_polish(&once, &pp, &st1, &err));
    pp.max_restarts = 100;
    CHECK_OK(tr_polish(&c, &pp, &again, &err));
    /* a target the first run already beats (the start's own ropelength):
     * no restart after it, although restarts would shorten the rope further */
    tr_polish_stats st_t;
    pp.target = t0.ropelength;
    CHECK_OK(tr_polish(&tgt, &pp, &st_t, &err));
    pp.target = 0;
    CHECK(st_t.accepted && st_t.restarts == 1 && st_t.ropelength_after <= t0.ropelength);
    printf("4_1 N 100 from KnotPlot: ropelength %.6f -> %.6f in %d runs (%.2f s), one run %.6f; polished again %.9f "
           "-> %.9f; TightKnot table (N 400, another conformation) %.6f\n",
           t0.ropelength, t1.ropelength, st.restarts, st.seconds, st1.ropelength_after, again.ropelength_before,
           again.ropelength_after, table_ropelength("4_1"));
    CHECK(st.accepted && st1.accepted);
    CHECK(st.restarts > 1 && st1.restarts == 1);
    CHECK(t1.thickness >= 1.0 - 1e-12);
    CHECK(t1.ropelength <= st1.ropelength_after);
    CHECK(again.ropelength_before - again.ropelength_after <= 1e-7 * again.ropelength_before);
    tr_curve_free(&once);
    tr_curve_free(&tgt);
    tr_curve_free(&c);
    tr_curve_free(&k);
}

/* the two components' linking number (testlib.h) */
static double linking_number(const tr_curve *c)
{
    return tr_test_linking_number(c->x + 3 * c->start[0], tr_comp_nv(c, 0), c->x + 3 * c->start[1], tr_comp_nv(c, 1));
}

/* The engine's run loop with refinement (72 -> 144), levels ended early
 * (residual 0.9) so that the polish does the work: with polish (every
 * level) the result is shorter than without, the final polish was accepted
 * and the state is a valid rope. */
static double run_levels(int polish, tr_engine_progress *p)
{
    tr_error err;
    tr_curve s, f;
    CHECK_OK(tr_make_torus(&s, 2, 3, 72, &err));
    tr_engine_params prm;
    tr_engine_params_default(&prm);
    prm.polish = polish;
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, &s, "reference", &prm, &err));
    tr_engine_limits lim = {.refine_to = 144, .residual = 0.9, .coarse_residual = 0.9, .max_steps = 3000};
    tr_stop_reason why;
    CHECK_OK(tr_engine_run(e, &lim, &why, &err));
    tr_engine_get_progress(e, p);
    CHECK_OK(tr_engine_get_curve(e, &f, &err));
    tr_thickness t;
    CHECK_OK(tr_thickness_measure(&f, NULL, &t, NULL, &err));
    printf("levels 72 -> 144, polish %d: stop %s, %ld steps, ropelength %.6f (polish %d: %.6f -> %.6f)\n", polish,
           tr_stop_reason_name(why), p->steps, t.ropelength, p->polished, p->polish_before, p->polish_after);
    CHECK(t.vertices == 144);
    CHECK(t.dcsd >= 2.0 * t.thickness * (1.0 - 1e-12));
    CHECK(p->edge_dev < 1e-9);
    CHECK(p->min_strut >= 2.0 - 1e-7);
    CHECK(p->minrad >= 1.0 - 1e-6);
    tr_curve_free(&f);
    tr_curve_free(&s);
    tr_engine_destroy(e);
    return t.ropelength;
}

int main(void)
{
    {
        tr_engine_progress p0, p1;
        double without = run_levels(0, &p0), with = run_levels(1, &p1);
        CHECK(p0.polished == 0);
        CHECK(p1.polished == 1);
        CHECK(p1.polish_after < p1.polish_before);
        CHECK(with <= p1.polish_after * (1.0 + 1e-7));
        CHECK(with < without - 1e-3);
    }

    polish_loose_figure_eight();

    tr_error err;
    tr_curve s, c;
    double before, after;
    /* trefoil, N = 72 */
    CHECK_OK(tr_make_torus(&s, 2, 3, 72, &err));
    engine_curve(&s, 40, &c);
    polish_checked(&c, "trefoil N 72", &before, &after);
    /* polishing a polished curve never makes it longer: kept as it is
     * unless the oracle's ropelength went down */
    tr_curve keep;
    CHECK_OK(tr_curve_copy(&keep, &c, &err));
    tr_polish_stats st;
    CHECK_OK(tr_polish(&c, NULL, &st, &err));
    tr_thickness ta;
    CHECK_OK(tr_thickness_measure(&c, NULL, &ta, NULL, &err));
    printf("trefoil again: %s, %.9f -> %.9f\n", st.accepted ? "accepted" : "kept", after, ta.ropelength);
    CHECK(ta.ropelength <= after);
    CHECK(st.accepted || memcmp(c.x, keep.x, 3 * c.nv * sizeof *c.x) == 0);
    tr_curve_free(&keep);
    tr_curve_free(&c);
    tr_curve_free(&s);
    /* Hopf link: linking number +-1 kept */
    CHECK_OK(tr_make_hopf(&s, 48, &err));
    double lk0 = linking_number(&s);
    engine_curve(&s, 20, &c);
    polish_checked(&c, "hopf N 2x48", &before, &after);
    double lk1 = linking_number(&c);
    printf("hopf: linking number %.9f -> %.9f\n", lk0, lk1);
    CHECK_NEAR(fabs(lk0), 1.0, 1e-6);
    CHECK_NEAR(lk1, lk0, 1e-6);
    tr_curve_free(&c);
    tr_curve_free(&s);
    /* a step cap the pair-list rebuild rule cannot honour is refused */
    {
        tr_curve t;
        CHECK_OK(tr_make_torus(&t, 2, 3, 72, &err));
        tr_polish_params bad;
        tr_polish_params_default(&bad);
        bad.max_move = bad.skin / 4;
        CHECK(tr_polish(&t, &bad, &st, &err) == TR_EINVAL);
        tr_curve_free(&t);
    }
    /* clasp: constrained ends are polished in place (never rescaled): they
     * stay on their planes and the rope stays at thickness 1 */
    CHECK_OK(tr_make_clasp(&s, 40, 5.0, &err));
    engine_curve(&s, 20, &c);
    tr_thickness tc0, tc1;
    CHECK_OK(tr_thickness_measure(&c, NULL, &tc0, NULL, &err));
    tr_polish_params cp;
    tr_polish_params_default(&cp);
    cp.time_limit = 8.0;
    CHECK_OK(tr_polish(&c, &cp, &st, &err));
    CHECK_OK(tr_thickness_measure(&c, NULL, &tc1, NULL, &err));
    printf("clasp 2x40: %s, %.9f -> %.9f\n", st.accepted ? "accepted" : "kept", tc0.ropelength, tc1.ropelength);
    CHECK(!st.skipped && st.accepted);
    CHECK(tc1.ropelength < tc0.ropelength);
    CHECK(tc1.thickness >= 1.0 - 1e-8);
    double off = 0.0;
    for (size_t i = 0; i < c.nv; i++)
        if (c.vcst[i] >= 0)
            off = fmax(off, tr_constraint_violation(&c.cst[c.vcst[i]], c.x + 3 * i));
    CHECK(off < 1e-12);
    /* below thickness 1 it cannot be: skipped, unchanged */
    tr_curve_free(&c);
    CHECK_OK(tr_curve_copy(&c, &s, &err));
    for (size_t i = 0; i < 3 * c.nv; i++)
        c.x[i] *= 0.5;
    tr_curve keep2;
    CHECK_OK(tr_curve_copy(&keep2, &c, &err));
    CHECK_OK(tr_polish(&c, &cp, &st, &err));
    CHECK(st.skipped && !st.accepted);
    CHECK(memcmp(c.x, keep2.x, 3 * c.nv * sizeof *c.x) == 0);
    tr_curve_free(&keep2);
    tr_curve_free(&c);
    tr_curve_free(&s);
    return tr_test_finish("test_polish");
}
